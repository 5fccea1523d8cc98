"""The dataset folder (`--out`) and its shards' life cycle.

    OUT/manifest.json          every shard: seed, frames, config hash, version, content hash
    OUT/coco.json              the shards' COCO merged (merge.py)
    OUT/yolo/TASK.yaml         Ultralytics YOLO datasets over the shards' labels (merge.py)
    OUT/webdataset.txt         the shards' WebDataset tars, one path a line (merge.py)
    OUT/shards/shard_NNNNNN/   a complete shard: what `finflex swim --annotate` writes,
                               and shard.json (its record, with its content hash)
    OUT/run.json, OUT/logs/    the run's record: workers, devices, times (not content)
    OUT/.staging/              shards being written; cleared when a run starts

A shard is written under .staging and renamed into shards/ only once complete, so a
shard folder under shards/ is always whole; a killed worker leaves at most staging
files, which the next attempt or run removes.
"""

from __future__ import annotations

import concurrent.futures
import hashlib
import json
import os
import pathlib
import shutil
import tempfile
import uuid

from .errors import DatasetError
from .plan import Shard

RECORD = "shard.json"
# Files of a run that are not the dataset's content (they hold times and machines).
RUN_FILES = ("run.json", "logs")


def _writable(folder: pathlib.Path) -> bool:
    # A folder made and removed again: permissions, read-only mounts and quotas alike.
    try:
        os.rmdir(tempfile.mkdtemp(prefix=".finflex-probe-", dir=folder))
        return True
    except OSError:
        return False


def check_out_folder(out: pathlib.Path) -> None:
    """`out` can hold a dataset: an existing writable folder (empty, or a dataset of
    this tool), or a new one in an existing writable folder. Nothing is left behind."""
    if out.exists():
        if not out.is_dir():
            raise DatasetError("--out", f"--out: '{out}' is not a folder")
        if not _writable(out):
            raise DatasetError("--out", f"--out: '{out}' is not writable")
        entries = {p.name for p in out.iterdir()}
        if entries and not (out / "shards").is_dir():
            raise DatasetError("--out", f"--out: '{out}' holds files but no dataset (no shards/)")
        return
    parent = out.parent
    if not parent.is_dir():
        raise DatasetError("--out", f"--out: the folder '{parent}' does not exist")
    if not _writable(parent):
        raise DatasetError("--out", f"--out: '{parent}' is not writable")


def file_digest(path: pathlib.Path) -> str:
    digest = hashlib.sha256()
    with open(path, "rb") as file:
        for block in iter(lambda: file.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def content_files(folder: pathlib.Path) -> list[pathlib.Path]:
    """A shard's content: every file under `folder` but its record, sorted by path."""
    return sorted(p for p in folder.rglob("*") if p.is_file() and p.name != RECORD)


def content_hash(folder: pathlib.Path, files: list[pathlib.Path] | None = None) -> str:
    """SHA-256 over the lines 'PATH SHA256' of the shard's files (`files`, default
    content_files(folder)) in path order (PATH relative to the shard, '/'-separated).
    The files are hashed on a thread per core the process may run on (hashlib lets go
    of the GIL)."""
    files = content_files(folder) if files is None else files
    with concurrent.futures.ThreadPoolExecutor(len(os.sched_getaffinity(0))) as pool:
        digests = list(pool.map(file_digest, files))
    digest = hashlib.sha256()
    for path, file_hash in zip(files, digests):
        digest.update(f"{path.relative_to(folder).as_posix()} {file_hash}\n".encode())
    return digest.hexdigest()


def shard_record(shard: Shard, config_hash: str, formats: tuple[str, ...], version: str,
                 folder: pathlib.Path) -> dict:
    files = content_files(folder)
    return {"index": shard.index, "name": shard.name, "seed": shard.seed,
            "first_frame": shard.first_frame, "frames": shard.frames,
            "config_hash": config_hash, "formats": list(formats), "finflex_version": version,
            "files": len(files), "content_hash": content_hash(folder, files)}


def read_record(folder: pathlib.Path) -> dict | None:
    try:
        return json.loads((folder / RECORD).read_text())
    except (OSError, ValueError):
        return None


def same_shard(record: dict, shard: Shard, config_hash: str, formats: tuple[str, ...],
               version: str) -> bool:
    return (record.get("seed") == shard.seed and record.get("frames") == shard.frames
            and record.get("first_frame") == shard.first_frame
            and record.get("config_hash") == config_hash
            and record.get("formats") == list(formats)
            and record.get("finflex_version") == version)


class Store:
    def __init__(self, out: pathlib.Path):
        self.out = out
        self.shards = out / "shards"
        self.staging = out / ".staging"
        self.logs = out / "logs"

    def prepare(self) -> None:
        """Makes the folders; removes what earlier runs left half-written."""
        self.shards.mkdir(parents=True, exist_ok=True)
        self.logs.mkdir(exist_ok=True)
        shutil.rmtree(self.staging, ignore_errors=True)
        self.staging.mkdir()

    def final(self, shard: Shard) -> pathlib.Path:
        return self.shards / shard.name

    def attempt_folder(self, shard: Shard) -> pathlib.Path:
        """A new staging folder's path for one attempt at `shard` (not made: the swim
        makes it)."""
        return self.staging / f"{shard.name}.{uuid.uuid4().hex[:12]}"

    def running_frames(self, shard: Shard) -> int:
        """The images an attempt at `shard` has written so far (for progress)."""
        count = 0
        for folder in self.staging.glob(f".{shard.name}.*/frames"):
            try:
                count = max(count, sum(1 for p in folder.iterdir() if not p.name.endswith(
                    "_right.png")))
            except OSError:
                pass
        return count

    def commit(self, shard: Shard, attempt: pathlib.Path, record_fields: dict) -> bool:
        """Moves a complete attempt into place with its record. False (and the attempt
        removed) when another attempt got there first."""
        summary = attempt / "summary.json"
        if summary.exists():
            os.replace(summary, self.logs / f"{shard.name}.summary.json")
        record = shard_record(shard, folder=attempt, **record_fields)
        (attempt / RECORD).write_text(json.dumps(record, indent=1) + "\n")
        try:
            os.rename(attempt, self.final(shard))
        except OSError:
            if read_record(self.final(shard)) is None:
                raise
            shutil.rmtree(attempt, ignore_errors=True)
            return False
        return True
