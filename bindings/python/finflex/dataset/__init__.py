"""Annotated datasets of the virtual RAS tank at scale: the frames split into shards,
each shard a `finflex swim --annotate` run on a worker that holds one OpenCL device
(Ray actors: one per GPU, CPU workers on PoCL), deterministic per seed and resumable.

    from finflex.dataset import generate
    summary = generate("out/tank", frames=1000, shard_frames=100, seed=7, workers=4,
                       formats=("coco", "yolo"), config="tank.json")

The same from the shell: `python -m finflex.dataset --out out/tank --frames 1000
--shard-frames 100 --seed 7 --workers 4 --formats coco,yolo --config tank.json`.
docs/dataset-at-scale.md describes the configuration, the folder and the guarantees.
"""

from __future__ import annotations

import json
import os
import pathlib
import re
import shutil
import subprocess
import tempfile
import time

from . import config as config_file
from . import merge
from .errors import DatasetError, ShardFailed
from .plan import FORMATS, OPTION_FIELDS, Shard, plan_shards, swim_arguments
from .pools import LocalPool, RayPool, check_reachable, choose_devices, ray_module, run_shards
from .progress import Progress
from .runner import Job
from .store import Store, check_out_folder, read_record, same_shard

__all__ = ["generate", "DatasetError", "ShardFailed", "FORMATS"]


def find_cli(cli: str | None) -> str:
    """The `finflex` program: `cli`, else $FINFLEX_CLI, else `finflex` on PATH."""
    given = cli or os.environ.get("FINFLEX_CLI")
    path = given or shutil.which("finflex")
    if not path or not os.path.isfile(path) or not os.access(path, os.X_OK):
        where = f"'{given}' is not an executable file" if given else "it is not on PATH"
        raise DatasetError("--finflex", f"--finflex: the finflex program is needed and {where}: "
                           "build it (README.md) and pass --finflex build/apps/finflex or set "
                           "FINFLEX_CLI")
    return os.path.abspath(path)


def _positive(name: str, value, low: int = 1) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or value < low:
        raise DatasetError(name, f"{name}: {value!r} is not a whole number >= {low}")
    return value


def _formats(formats) -> tuple[str, ...]:
    items = formats.split(",") if isinstance(formats, str) else list(formats)
    for item in items:
        if item not in FORMATS:
            raise DatasetError("--formats", f"--formats: '{item}' is not one of "
                               f"{', '.join(FORMATS)}")
    # COCO always: the merged files are made from it.
    return tuple(f for f in FORMATS if f in items or f == "coco")


def _preflight(cli: str, config: dict, formats: tuple[str, ...], seed: int) -> None:
    """One frame of the first shard in a scratch folder: whatever `finflex swim` refuses
    is refused here, before any worker starts, naming the configuration field."""
    scratch = tempfile.mkdtemp(prefix="finflex-dataset-check-")
    try:
        args = [cli] + swim_arguments(config, Shard(0, 0, 1, seed), formats,
                                      os.path.join(scratch, "out"))
        result = subprocess.run(args, capture_output=True, text=True)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    if result.returncode == 0:
        return
    message = (result.stderr.strip().splitlines() or ["(no message)"])[-1]
    message = message.removeprefix("finflex swim: ").removeprefix("error: ")
    option = next((o for o in OPTION_FIELDS if message.startswith(o)), None)
    species = re.match(r"species\[\d+\]", message)
    field = (f"config.{OPTION_FIELDS[option]}" if option else
             f"config.{species.group(0)}" if species else "config")
    raise DatasetError(field, f"{field}: {message}")


def _version(cli: str) -> str:
    result = subprocess.run([cli, "--version"], capture_output=True, text=True)
    return result.stdout.strip().removeprefix("finflex ") or "unknown"


def generate(out, frames: int, shard_frames: int, seed: int = 0, workers: int | None = None,
             address: str | None = None, formats=("coco",), config=None,
             cpu_workers: int | None = None, cpu_threads: int | None = None,
             cli: str | None = None, use_ray: bool | None = None, quiet: bool = False) -> dict:
    """Writes (or completes) the dataset in `out`; the run's summary.

    `frames` frames in shards of `shard_frames`; `seed` the dataset's seed; `workers`
    how many workers (default: one per GPU, else one on the CPU), `cpu_workers` how
    many of them run on the CPU (default: those beyond the GPUs), `cpu_threads` the
    cores of each (default: an equal share); `address` a Ray
    cluster's (default: a private local one); `config` a configuration file's path (or
    a dict of fields). Ray runs the workers unless one worker runs here
    (`use_ray`: force either). DatasetError naming the option or field for bad input
    (nothing written); ShardFailed when a shard failed every attempt."""
    frames = _positive("--frames", frames)
    shard_frames = _positive("--shard-frames", shard_frames)
    seed = _positive("--seed", seed, 0)
    if seed >= 2 ** 64:
        raise DatasetError("--seed", f"--seed: {seed} does not fit in 64 bits")
    if workers is not None:
        workers = _positive("--workers", workers)
    if cpu_workers is not None:
        cpu_workers = _positive("--cpu-workers", cpu_workers, 0)
    if cpu_threads is not None:
        cpu_threads = _positive("--cpu-threads", cpu_threads)
    formats = _formats(formats)
    if isinstance(config, dict):
        settings = config_file.validate(config, pathlib.Path.cwd())
    else:
        settings = config_file.load(config)
    out = pathlib.Path(out).absolute()
    check_out_folder(out)
    if address is not None:
        check_reachable(address)
    cli = find_cli(cli)
    version = _version(cli)
    config_hash = config_file.config_hash(settings)
    shards = plan_shards(frames, shard_frames, seed)

    store = Store(out)
    for shard in shards:  # a shard of another dataset in this folder: refuse, before anything
        record = read_record(store.final(shard))
        if record is not None and not same_shard(record, shard, config_hash, formats, version):
            raise DatasetError("--out", f"--out: '{out}' holds {shard.name} of another dataset "
                               "(other seed, frames, configuration, formats or FinFlex version): "
                               "choose another folder")
    ray_wanted = use_ray if use_ray is not None else (address is not None or (workers or 1) > 1)
    if ray_wanted:
        ray_module()
    elif (workers or 1) > 1:
        raise DatasetError("--workers", "--workers: more than one worker runs on Ray")
    _preflight(cli, settings, formats, shards[0].seed)

    start = time.perf_counter()
    out.mkdir(exist_ok=True)
    store.prepare()
    todo = [s for s in shards if read_record(store.final(s)) is None]
    job = Job(cli=cli, out=str(out), config=settings, formats=formats, config_hash=config_hash,
              version=version)
    if ray_wanted:
        pool = RayPool(job, address, workers or _default_workers(cli), cpu_workers, cpu_threads)
    else:
        choices = choose_devices(1, cpu_workers, _gpu_count(cli), sorted(os.sched_getaffinity(0)),
                                 local=False, cpu_threads=cpu_threads)
        pool = LocalPool(job, choices)
    started = time.perf_counter() - start
    progress = Progress(store, frames, len(shards), sum(s.frames for s in shards if s not in todo),
                        len(shards) - len(todo), quiet=quiet)
    shards_start = time.perf_counter()
    try:
        results = run_shards(pool, todo, progress) if todo else []
        worker_info = [pool.describe(w) for w in pool.workers]
    finally:
        pool.close()
        progress.close()
    shards_seconds = time.perf_counter() - shards_start

    merged = merge.merge_coco(out, shards, {
        "description": "FinFlex virtual RAS tank dataset (python -m finflex.dataset)",
        "frames": frames, "shard_frames": shard_frames, "shards": len(shards), "seed": seed,
        "config_hash": config_hash, "finflex_version": version})
    written = ["coco.json"]
    if "yolo" in formats:
        written += merge.write_yolo(out, shards)
    if "webdataset" in formats:
        written += [merge.write_webdataset_list(out, shards) or "(no tars)"]
    records = [read_record(store.final(s)) for s in shards]
    merge.write_manifest(out, {
        "finflex_version": version, "config_hash": config_hash,
        "config": config_file.describe(settings), "seed": seed, "frames": frames,
        "shard_frames": shard_frames, "formats": list(formats), **merged, "shards": records})
    shutil.rmtree(store.staging, ignore_errors=True)
    wall = time.perf_counter() - start
    summary = _summary(out, shards, todo, results, worker_info, wall, started, shards_seconds,
                       merged, written + ["manifest.json"])
    merge.write_text(out / "run.json", json.dumps(summary, indent=1) + "\n")
    return summary


def _gpu_count(cli: str) -> int:
    from .runner import opencl_devices
    return sum(1 for _, kind in opencl_devices(cli) if kind == "GPU")


def _default_workers(cli: str) -> int:
    return max(1, _gpu_count(cli))


def _summary(out, shards, todo, results, workers, wall, started, shards_seconds, merged,
             written) -> dict:
    made = sum(r["frames"] for r in results)
    overhead = [r["task_seconds"] - r["process_seconds"] for r in results]
    busy = {}
    for r in results:
        key = f"{r['kind']} {r['device']} pid {r['pid']} on {r['host']}"
        entry = busy.setdefault(key, {"kind": r["kind"], "device": r["device"], "frames": 0,
                                      "seconds": 0.0, "shards": 0})
        entry["frames"] += r["frames"]
        entry["seconds"] += r["seconds"]
        entry["shards"] += 1
    for entry in busy.values():
        entry["frames_per_second"] = entry["frames"] / entry["seconds"] if entry["seconds"] else 0
    shard_seconds = sum(r["task_seconds"] for r in results)
    return {
        "out": str(out), "shards": len(shards), "shards_written": len(todo),
        "shards_skipped": len(shards) - len(todo),
        "retries": sum(r["attempts"] - 1 for r in results),
        "frames_written": made, "seconds": wall,
        # The workers' start (Ray's, the devices'), the shards, the merged files after.
        "start_seconds": started, "shards_seconds": shards_seconds,
        "merge_seconds": wall - started - shards_seconds,
        "frames_per_second": made / shards_seconds if shards_seconds > 0 and made else 0.0,
        "workers": workers, "per_worker": list(busy.values()),
        # Per shard: its task's time, handed out to handed back, beyond its swim
        # process's (scheduling, transfers, the record and its hashes).
        "overhead_per_shard_s": (sum(overhead) / len(overhead)) if overhead else 0.0,
        "overhead_share": (sum(overhead) / shard_seconds) if shard_seconds else 0.0,
        **merged, "written": written, "per_shard": results,
    }

