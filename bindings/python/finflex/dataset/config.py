"""The dataset's configuration file (JSON, or TOML by its .toml extension): the tank,
the species, the camera, the optics and the swim of `finflex swim`, validated field by
field before anything runs. Every field is optional; `DEFAULTS` holds the defaults and
docs/dataset-at-scale.md the table of fields with the `finflex swim` option each
becomes.
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
import pathlib
from typing import Any

from .errors import DatasetError

KEYPOINTS = ("snout", "tail_fork", "caudal_upper_tip", "caudal_lower_tip",
             "left_pectoral_tip", "right_pectoral_tip")

DEFAULTS: dict[str, Any] = {
    "tank": {"fish": 200, "diameter_m": 3.66, "depth_m": 1.22, "tanks": 1},
    "species": None,  # the bundled fish
    "camera": {"view": "oblique", "width": 640, "height": 360, "samples": 4,
               "stereo_baseline_m": None, "distortion": None, "noise": None},
    "optics": {"water": "ras", "turbidity_ntu": None, "dissolved_a440": None,
               "vary": True, "refraction": False, "port": None},
    "swim": {"fps": 30.0, "warmup_frames": 30, "frame_step": 1, "normals": "jacobian"},
    "annotation": {"keypoints": list(KEYPOINTS), "depth": True, "length_weight": {}},
}


def _fail(field: str, message: str) -> DatasetError:
    return DatasetError(f"config.{field}", f"config.{field}: {message}")


def _number(field: str, value: Any, low: float, high: float, *, integer: bool = False,
            low_open: bool = False) -> float | int:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _fail(field, f"{value!r} is not a number")
    if integer and (not float(value).is_integer()):
        raise _fail(field, f"{value!r} is not a whole number")
    if not math.isfinite(value) or value > high or value < low or (low_open and value == low):
        bracket = "(" if low_open else "["
        raise _fail(field, f"{value!r} is outside {bracket}{low:g}, {high:g}]")
    return int(value) if integer else float(value)


def _choice(field: str, value: Any, choices: tuple[str, ...]) -> str:
    if value not in choices:
        raise _fail(field, f"{value!r} is not one of {', '.join(choices)}")
    return value


def _port(value: Any) -> dict[str, float]:
    """optics.port: {"distance_m", "thickness_m", "refractive_index"}, each optional."""
    field = "optics.port"
    if not isinstance(value, dict):
        raise _fail(field, f"{value!r} is not a table of distance_m, thickness_m, refractive_index")
    ranges = {"distance_m": (0.0001, 0.5, 0.02), "thickness_m": (0.0, 0.1, 0.01),
              "refractive_index": (1.0, 2.0, 1.49)}
    unknown = sorted(set(value) - set(ranges))
    if unknown:
        raise _fail(f"{field}.{unknown[0]}", "is not a field (distance_m, thickness_m, "
                    "refractive_index)")
    return {key: _number(f"{field}.{key}", value.get(key, default), low, high)
            for key, (low, high, default) in ranges.items()}


def _flag(field: str, value: Any) -> bool:
    if not isinstance(value, bool):
        raise _fail(field, f"{value!r} is not true or false")
    return value


def _numbers(field: str, value: Any, count: int, low: float, high: float) -> list[float]:
    if not isinstance(value, list) or len(value) != count:
        raise _fail(field, f"{value!r} is not a list of {count} numbers")
    return [_number(f"{field}[{i}]", v, low, high) for i, v in enumerate(value)]


def _input_file(field: str, value: Any, base: pathlib.Path) -> str:
    if not isinstance(value, str) or not value:
        raise _fail(field, f"{value!r} is not a path")
    path = (base / value).resolve()
    if not path.is_file():
        raise _fail(field, f"'{value}' is not a file (read from {base})")
    return str(path)


def _section(config: dict, name: str) -> dict:
    section = config.get(name, {})
    if not isinstance(section, dict):
        raise _fail(name, f"{section!r} is not a table of fields")
    unknown = sorted(set(section) - set(DEFAULTS[name]))
    if unknown:
        raise _fail(f"{name}.{unknown[0]}", f"unknown field (known: {', '.join(DEFAULTS[name])})")
    merged = copy.deepcopy(DEFAULTS[name])
    merged.update(section)
    return merged


def validate(config: Any, base: pathlib.Path) -> dict[str, Any]:
    """The configuration with every default filled in and every input path absolute;
    DatasetError naming the first bad field. `base`: the folder relative paths start
    from (the configuration file's)."""
    if not isinstance(config, dict):
        raise DatasetError("config", "config: the file does not hold a table of fields")
    unknown = sorted(set(config) - set(DEFAULTS))
    if unknown:
        raise _fail(unknown[0], f"unknown section (known: {', '.join(DEFAULTS)})")
    out: dict[str, Any] = {}

    tank = _section(config, "tank")
    out["tank"] = {
        "fish": _number("tank.fish", tank["fish"], 1, 65535, integer=True),
        "diameter_m": _number("tank.diameter_m", tank["diameter_m"], 0.0, 100.0, low_open=True),
        "depth_m": _number("tank.depth_m", tank["depth_m"], 0.0, 20.0, low_open=True),
        "tanks": _number("tank.tanks", tank["tanks"], 1, 1024, integer=True),
    }

    species = config.get("species", None)
    if species is not None:
        if not isinstance(species, list) or not species:
            raise _fail("species", f"{species!r} is not a list of {{mesh, rig}} tables")
        checked = []
        for i, one in enumerate(species):
            if not isinstance(one, dict) or set(one) != {"mesh", "rig"}:
                raise _fail(f"species[{i}]", f"{one!r} is not a table of exactly mesh and rig")
            checked.append({"mesh": _input_file(f"species[{i}].mesh", one["mesh"], base),
                            "rig": _input_file(f"species[{i}].rig", one["rig"], base)})
        species = checked
    out["species"] = species

    camera = _section(config, "camera")
    out["camera"] = {
        "view": _choice("camera.view", camera["view"],
                        ("above", "oblique", "side", "underwater")),
        "width": _number("camera.width", camera["width"], 16, 16384, integer=True),
        "height": _number("camera.height", camera["height"], 16, 16384, integer=True),
        "samples": _number("camera.samples", camera["samples"], 1, 16, integer=True),
        "stereo_baseline_m": None if camera["stereo_baseline_m"] is None else _number(
            "camera.stereo_baseline_m", camera["stereo_baseline_m"], 0.0, 10.0, low_open=True),
        "distortion": None if camera["distortion"] is None else _numbers(
            "camera.distortion", camera["distortion"], 5, -10.0, 10.0),
        "noise": None if camera["noise"] is None else _numbers(
            "camera.noise", camera["noise"], 2, 0.0, 255.0),
    }

    optics = _section(config, "optics")
    out["optics"] = {
        "water": _choice("optics.water", optics["water"], ("clear", "ras", "turbid")),
        "turbidity_ntu": None if optics["turbidity_ntu"] is None else _number(
            "optics.turbidity_ntu", optics["turbidity_ntu"], 0.0, 100.0),
        "dissolved_a440": None if optics["dissolved_a440"] is None else _number(
            "optics.dissolved_a440", optics["dissolved_a440"], 0.0, 20.0),
        "vary": _flag("optics.vary", optics["vary"]),
        "refraction": _flag("optics.refraction", optics["refraction"]),
        "port": None if optics["port"] is None else _port(optics["port"]),
    }
    if out["optics"]["refraction"] and out["camera"]["view"] == "side":
        raise _fail("optics.refraction", "true with camera.view 'side' (it looks through the wall)")
    if out["optics"]["port"] is not None and not (
            out["optics"]["refraction"] and out["camera"]["view"] == "underwater"):
        raise _fail("optics.port", "the underwater camera's housing: it needs camera.view "
                    "'underwater' and optics.refraction true")
    if out["camera"]["view"] == "underwater" and out["tank"]["tanks"] > 1:
        raise _fail("camera.view", "'underwater' is in one tank's water: not with tank.tanks > 1")

    swim = _section(config, "swim")
    out["swim"] = {
        "fps": _number("swim.fps", swim["fps"], 0.0, 240.0, low_open=True),
        "warmup_frames": _number("swim.warmup_frames", swim["warmup_frames"], 0, 100000,
                                 integer=True),
        "frame_step": _number("swim.frame_step", swim["frame_step"], 1, 1000, integer=True),
        "normals": _choice("swim.normals", swim["normals"], ("rotate", "jacobian")),
    }

    annotation = _section(config, "annotation")
    keypoints = annotation["keypoints"]
    if not isinstance(keypoints, list) or not keypoints:
        raise _fail("annotation.keypoints", f"{keypoints!r} is not a list of keypoint names")
    for i, name in enumerate(keypoints):
        _choice(f"annotation.keypoints[{i}]", name, KEYPOINTS)
        if name in keypoints[:i]:
            raise _fail(f"annotation.keypoints[{i}]", f"{name!r} is listed twice")
    weights = annotation["length_weight"]
    if not isinstance(weights, dict):
        raise _fail("annotation.length_weight", f"{weights!r} is not a table of species: [a, b]")
    out["annotation"] = {
        "keypoints": list(keypoints),
        "depth": _flag("annotation.depth", annotation["depth"]),
        "length_weight": {
            str(name): _numbers(f"annotation.length_weight.{name}", ab, 2, 0.0, 100.0)
            for name, ab in sorted(weights.items())},
    }
    for name, (a, b) in out["annotation"]["length_weight"].items():
        if a <= 0.0 or b <= 0.0:
            raise _fail(f"annotation.length_weight.{name}", f"{[a, b]!r}: a and b must be positive")
    return out


def load(path: str | None) -> dict[str, Any]:
    """The validated configuration of the file at `path` (None: every default)."""
    if path is None:
        return validate({}, pathlib.Path.cwd())
    file = pathlib.Path(path)
    try:
        text = file.read_bytes()
    except OSError as error:
        raise DatasetError("--config", f"--config: cannot read '{path}' ({error.strerror})")
    try:
        if file.suffix == ".toml":
            import tomllib
            raw = tomllib.loads(text.decode("utf-8"))
        else:
            raw = json.loads(text)
    except (ValueError, UnicodeDecodeError) as error:
        raise DatasetError("--config", f"--config: '{path}' does not parse ({error})")
    return validate(raw, file.resolve().parent)


def _file_digest(path: str) -> str:
    return hashlib.sha256(pathlib.Path(path).read_bytes()).hexdigest()


def config_hash(config: dict[str, Any]) -> str:
    """SHA-256 of the validated configuration in canonical JSON, the species by their
    files' contents (so that moving the files keeps the hash and editing them does
    not)."""
    canonical = copy.deepcopy(config)
    if canonical["species"] is not None:
        canonical["species"] = [{"mesh": _file_digest(s["mesh"]), "rig": _file_digest(s["rig"])}
                                for s in canonical["species"]]
    text = json.dumps(canonical, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()


def describe(config: dict[str, Any]) -> dict[str, Any]:
    """The configuration as the manifest records it: the species by file name and
    content digest (no machine's paths)."""
    described = copy.deepcopy(config)
    if described["species"] is not None:
        described["species"] = [
            {key: pathlib.Path(s[key]).name for key in ("mesh", "rig")}
            | {f"{key}_sha256": _file_digest(s[key]) for key in ("mesh", "rig")}
            for s in described["species"]]
    return described
