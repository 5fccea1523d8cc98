"""python -m finflex.dataset on PoCL: the same files from 1 worker and 2 Ray workers, a
killed worker's shard retried into the same dataset, an interrupted run resumed, the
merged files read by their readers, and bad input refused with nothing written.
Run by CTest (tests/CMakeLists.txt) with the repository's .venv (pycocotools, Ray)."""

import importlib.util
import json
import os
import pathlib
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from pycocotools.coco import COCO

from finflex.dataset import DatasetError, generate
from finflex.dataset.store import RUN_FILES, content_hash, file_digest
from finflex.dataset.pools import choose_devices

# The Ray runs must run here, not skip (Ray itself is imported by the generator, which
# sets its authentication first).
assert importlib.util.find_spec("ray"), "Ray is not installed (scripts/install-deps.sh)"
CONFIG = {"tank": {"fish": 16}, "camera": {"width": 160, "height": 96, "samples": 1},
          "swim": {"warmup_frames": 3, "frame_step": 2}}
RUN = dict(frames=7, shard_frames=3, seed=11, formats=("coco", "yolo", "webdataset"))


def dataset_files(out: pathlib.Path) -> dict:
    """Every file's SHA-256 by path, but the run's record (times, workers)."""
    return {p.relative_to(out).as_posix(): file_digest(p) for p in sorted(out.rglob("*"))
            if p.is_file() and p.relative_to(out).parts[0] not in RUN_FILES}


def write_config(folder: pathlib.Path, config=CONFIG) -> str:
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "config.json"
    path.write_text(json.dumps(config))
    return str(path)


def command(out, config, *extra):
    return [sys.executable, "-m", "finflex.dataset", "--out", str(out), "--frames", "7",
            "--shard-frames", "3", "--seed", "11", "--formats", "coco,yolo,webdataset",
            "--config", config, "--quiet", *extra]


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    return tmp_path_factory.mktemp("dataset", numbered=True)


@pytest.fixture(scope="module")
def reference(folder):
    out = folder / "one_worker"
    summary = generate(out, workers=1, config=dict(CONFIG), quiet=True, **RUN)
    assert summary["shards_written"] == 3 and summary["images"] == 7
    return out


def swim_processes():
    """pid -> command line of every running `finflex swim`."""
    found = {}
    for entry in pathlib.Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            args = (entry / "cmdline").read_bytes().split(b"\0")
        except OSError:
            continue
        if len(args) > 1 and args[0].endswith(b"finflex") and args[1] == b"swim":
            found[int(entry.name)] = b" ".join(args).decode()
    return found


def wait_for_a_swim_writing(out: pathlib.Path, driver, timeout=120.0) -> int:
    """The pid of a swim of `out` that has begun writing a shard (its staging folder
    made: camera.json, and frames once drawn) not yet complete."""
    staging = str(out / ".staging") + "/"
    deadline = time.time() + timeout
    while time.time() < deadline and driver.poll() is None:
        for pid, line in swim_processes().items():
            if staging not in line:
                continue
            attempt = line.split(staging, 1)[1].split()[0]
            if any((out / ".staging").glob(f".{attempt}.partial-*/camera.json")):
                return pid
        time.sleep(0.01)
    raise AssertionError("no swim was seen writing")


def test_two_ray_workers_write_the_same_files_as_one(reference, folder):
    out = folder / "two_workers"
    summary = generate(out, workers=2, config=dict(CONFIG), quiet=True, **RUN)
    assert len(summary["workers"]) == 2
    assert len({w["pid"] for w in summary["workers"]}) == 2
    assert dataset_files(out) == dataset_files(reference)


def test_a_killed_ray_worker_is_replaced_and_its_shard_redone(reference, folder):
    out = folder / "killed_actor"
    driver = subprocess.Popen(command(out, write_config(folder / "c1"), "--workers", "2"))
    swim = wait_for_a_swim_writing(out, driver)
    actor = int(pathlib.Path(f"/proc/{swim}/stat").read_text().rsplit(")", 1)[1].split()[2])
    os.kill(actor, signal.SIGKILL)  # the worker's swim dies with it
    assert driver.wait(timeout=300) == 0
    run = json.loads((out / "run.json").read_text())
    assert run["retries"] >= 1
    assert dataset_files(out) == dataset_files(reference)
    assert not (out / ".staging").exists()


def test_a_killed_swim_is_retried(reference, folder):
    out = folder / "killed_swim"
    driver = subprocess.Popen(command(out, write_config(folder / "c2"), "--workers", "1"))
    os.kill(wait_for_a_swim_writing(out, driver), signal.SIGKILL)
    assert driver.wait(timeout=300) == 0
    assert json.loads((out / "run.json").read_text())["retries"] == 1
    assert dataset_files(out) == dataset_files(reference)


def test_an_interrupted_run_resumes_with_the_missing_shards_only(reference, folder):
    out = folder / "interrupted"
    config = write_config(folder / "c3")
    driver = subprocess.Popen(command(out, config, "--workers", "1"))
    deadline = time.time() + 120
    while not (out / "shards" / "shard_000000" / "shard.json").exists():
        assert time.time() < deadline and driver.poll() is None
        time.sleep(0.02)
    driver.kill()  # the driver, at once: its swim dies with it
    driver.wait()
    done = {p.name for p in (out / "shards").iterdir()}
    assert 1 <= len(done) < 3
    rerun = subprocess.run(command(out, config, "--workers", "1"), capture_output=True, text=True)
    assert rerun.returncode == 0, rerun.stderr
    run = json.loads((out / "run.json").read_text())
    assert run["shards_skipped"] == len(done)
    assert run["shards_written"] == 3 - len(done)
    assert dataset_files(out) == dataset_files(reference)


def test_the_merged_files_read_back(reference):
    coco = COCO(str(reference / "coco.json"))
    images = coco.loadImgs(coco.getImgIds())
    assert [i["id"] for i in images] == list(range(1, 8))
    annotations = coco.loadAnns(coco.getAnnIds())
    assert len({a["id"] for a in annotations}) == len(annotations) > 0
    assert sorted({a["image_id"] for a in annotations}) == list(range(1, 8))
    for image in images:
        assert (reference / image["file_name"]).is_file()
        assert (reference / image["mask_file"]).is_file()
    for annotation in annotations[:20]:
        mask = coco.annToMask(annotation)
        assert mask.sum() == annotation["area"]
    # YOLO: every listed folder's labels, class and normalised numbers per line.
    for task in ("detect", "segment", "pose"):
        yaml = (reference / "yolo" / f"{task}.yaml").read_text().splitlines()
        folders = [line.split("- ", 1)[1] for line in yaml if line.startswith("  - ")]
        assert len(folders) == 6  # train and val, three shards each
        for images_folder in folders[:3]:
            labels = (reference / "yolo" / images_folder).resolve().parent / "labels"
            for label in labels.glob("*.txt"):
                for line in label.read_text().splitlines():
                    values = np.array(line.split()[1:], dtype=float)
                    assert int(line.split()[0]) in (0, 1)
                    assert np.all((values >= 0.0) & (values <= 2.0))
        if task == "pose":
            assert "kpt_shape: [6, 3]" in yaml
    tars = (reference / "webdataset.txt").read_text().split()
    assert len(tars) == 3 and all((reference / t).is_file() for t in tars)
    # The manifest's hashes are the files'.
    manifest = json.loads((reference / "manifest.json").read_text())
    assert [s["index"] for s in manifest["shards"]] == [0, 1, 2]
    seeds = {s["seed"] for s in manifest["shards"]}
    assert len(seeds) == 3
    for shard in manifest["shards"]:
        assert shard["content_hash"] == content_hash(reference / "shards" / shard["name"])
        assert shard["config_hash"] == manifest["config_hash"]


@pytest.mark.parametrize("change, field", [
    ({"frames": 0}, "--frames"),
    ({"shard_frames": 0}, "--shard-frames"),
    ({"cpu_threads": 0}, "--cpu-threads"),
    ({"frames": -3}, "--frames"),
    ({"formats": ("coco", "parquet")}, "--formats"),
    ({"address": "127.0.0.1:1"}, "--address"),
    ({"out": "/proc/finflex-dataset"}, "--out"),
    ({"config": {"optics": {"turbidity_ntu": -1}}}, "config.optics.turbidity_ntu"),
    ({"config": {"camera": {"lens": 3}}}, "config.camera.lens"),
    ({"config": {"tank": {"fish": 2.5}}}, "config.tank.fish"),
    ({"config": {"species": [{"mesh": "no.obj", "rig": "no.json"}]}}, "config.species[0].mesh"),
    ({"config": {"camera": {"stereo_baseline_m": 0}}}, "config.camera.stereo_baseline_m"),
    ({"config": {"optics": {"port": {"distance_m": 0.01}}}}, "config.optics.port"),
    ({"config": {"camera": {"view": "underwater"}, "optics": {
        "refraction": True, "port": {"thickness_m": -1}}}}, "config.optics.port.thickness_m"),
])
def test_bad_input_is_refused_naming_it_with_nothing_written(folder, change, field):
    out = folder / f"bad_{field.strip('-').replace('.', '_')}"
    arguments = dict(RUN, out=out, workers=1, config=dict(CONFIG), quiet=True)
    arguments.update(change)
    with pytest.raises(DatasetError) as error:
        generate(**arguments)
    assert error.value.field == field, str(error.value)
    assert field in str(error.value) and "\n" not in str(error.value)
    if arguments["out"] == out:
        assert not out.exists()


def test_cpu_workers_get_their_cores_or_a_clear_error():
    choices = choose_devices(3, 2, 1, list(range(8)), local=True, cpu_threads=3)
    assert [c.kind for c in choices] == ["gpu", "cpu", "cpu"]
    assert [c.cores for c in choices[1:]] == [(1, 2, 3), (4, 5, 6)]
    assert all(c.threads == 3 for c in choices[1:])
    with pytest.raises(DatasetError) as error:
        choose_devices(2, 2, 0, list(range(8)), local=True, cpu_threads=5)
    assert error.value.field == "--cpu-workers" and "only 8 cores" in str(error.value)


def test_a_field_only_the_swim_checks_is_named_before_any_worker_starts(folder):
    # A rig that is a file but not a rig: refused by the one-frame check, as its field.
    mesh = pathlib.Path(os.environ["FINFLEX_DATA_DIR"]) / "blub" / "fish_low_resolution.obj"
    config = {"species": [{"mesh": str(mesh), "rig": str(mesh)}]}
    out = folder / "bad_rig"
    with pytest.raises(DatasetError) as error:
        generate(out, workers=1, config=config, quiet=True, **dict(RUN, formats=("coco",)))
    assert error.value.field.startswith("config.species"), str(error.value)
    assert not out.exists()


def test_the_command_line_exits_2_with_one_line(folder):
    out = folder / "bad_command"
    result = subprocess.run(command(out, write_config(folder / "c4"), "--shard-frames", "0"),
                            capture_output=True, text=True)
    assert result.returncode == 2
    assert result.stderr.count("\n") == 1 and "--shard-frames" in result.stderr
    assert not out.exists()


def test_without_ray_several_workers_say_how_to_get_it(folder):
    code = ("import sys; sys.modules['ray'] = None\n"
            "from finflex.dataset.__main__ import main\n"
            f"sys.exit(main({command(folder / 'no_ray', write_config(folder / 'c5'))[3:]!r}"
            " + ['--workers', '2']))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    assert result.returncode == 2
    assert "pip install 'finflex[dataset]'" in result.stderr and "--workers 1" in result.stderr
    assert not (folder / "no_ray").exists()
