"""A dataset's shards and the `finflex swim` command that writes each.

Shard k holds the dataset's frames k M .. k M + M - 1 (the last shard fewer): a swim of
its own tank, filled and driven by the shard's seed, which numpy's SeedSequence derives
from the dataset's seed and k alone (spawn key (k,)). So a shard's files depend on the
seed, the configuration and k, never on which worker ran it or when.
"""

from __future__ import annotations

import dataclasses

import numpy as np

FORMATS = ("coco", "yolo", "webdataset")


@dataclasses.dataclass(frozen=True)
class Shard:
    index: int
    first_frame: int  # the dataset's index of the shard's first frame
    frames: int
    seed: int

    @property
    def name(self) -> str:
        return f"shard_{self.index:06d}"


def shard_seed(seed: int, index: int) -> int:
    """The 64-bit seed of shard `index` of a dataset seeded with `seed`."""
    state = np.random.SeedSequence(seed, spawn_key=(index,)).generate_state(1, np.uint64)
    return int(state[0])


def plan_shards(frames: int, shard_frames: int, seed: int) -> list[Shard]:
    return [Shard(k, first, min(shard_frames, frames - first), shard_seed(seed, k))
            for k, first in enumerate(range(0, frames, shard_frames))]


def image_frames(config: dict, shard: Shard) -> list[int]:
    """The swim's frames written as the shard's images: after the warm-up, every
    frame_step-th."""
    swim = config["swim"]
    return [swim["warmup_frames"] + i * swim["frame_step"] for i in range(shard.frames)]


def swim_arguments(config: dict, shard: Shard, formats: tuple[str, ...], out: str,
                   device: str | None = None) -> list[str]:
    """`finflex swim`'s options for `shard`, written to the folder `out`."""
    tank, camera, optics = config["tank"], config["camera"], config["optics"]
    swim, annotation = config["swim"], config["annotation"]
    images = image_frames(config, shard)
    simulated = images[-1] + 1
    args = ["swim", "--out", out, "--seed", str(shard.seed),
            "--fish", str(tank["fish"]), "--tank", f"{tank['diameter_m']!r},{tank['depth_m']!r}",
            "--tanks", str(tank["tanks"]),
            # The swim's length in frames, exactly: it rounds seconds x fps.
            "--fps", repr(swim["fps"]), "--seconds", repr(simulated / swim["fps"]),
            "--normals", swim["normals"],
            # The warm-up frames before the first image are simulated, not drawn.
            "--image-frames", ",".join(map(str, images)), "--video", "none",
            "--draw", "written",
            "--size", f"{camera['width']}x{camera['height']}", "--camera", camera["view"],
            "--samples", str(camera["samples"]),
            "--water", optics["water"],
            "--annotate", "--formats", ",".join(f for f in FORMATS if f in formats),
            "--keypoints", ",".join(annotation["keypoints"])]
    for one in config["species"] or []:
        args += ["--species", f"{one['mesh']}:{one['rig']}"]
    if camera["stereo_baseline_m"] is not None:
        args += ["--stereo", repr(camera["stereo_baseline_m"])]
    if camera["distortion"] is not None:
        args += ["--distortion", ",".join(map(repr, camera["distortion"]))]
    if camera["noise"] is not None:
        args += ["--noise", ",".join(map(repr, camera["noise"]))]
    if optics["turbidity_ntu"] is not None:
        args += ["--turbidity", repr(optics["turbidity_ntu"])]
    if optics["dissolved_a440"] is not None:
        args += ["--dissolved", repr(optics["dissolved_a440"])]
    if optics["vary"]:
        args.append("--vary-optics")
    if optics["refraction"]:
        args.append("--refraction")
    if optics["port"] is not None:
        port = optics["port"]
        args += ["--port", ",".join(repr(port[key]) for key in
                                    ("distance_m", "thickness_m", "refractive_index"))]
    if annotation["depth"]:
        args.append("--depth")
    for name, (a, b) in annotation["length_weight"].items():
        args += ["--length-weight", f"{name}:{a!r},{b!r}"]
    if device is not None:
        args += ["--device", device]
    return args


# Which configuration field each `finflex swim` option comes from, to name it in errors.
OPTION_FIELDS = {
    "--fish": "tank.fish", "--tank": "tank.diameter_m", "--tanks": "tank.tanks",
    "--fps": "swim.fps", "--seconds": "swim.warmup_frames", "--normals": "swim.normals",
    "--size": "camera.width", "--camera": "camera.view", "--samples": "camera.samples",
    "--stereo": "camera.stereo_baseline_m", "--distortion": "camera.distortion",
    "--noise": "camera.noise", "--water": "optics.water", "--turbidity": "optics.turbidity_ntu",
    "--dissolved": "optics.dissolved_a440", "--vary-optics": "optics.vary",
    "--refraction": "optics.refraction", "--port": "optics.port",
    "--keypoints": "annotation.keypoints",
    "--length-weight": "annotation.length_weight", "--species": "species",
    "--depth": "annotation.depth",
}
