"""The dataset's files over its shards, once every shard is complete: one COCO file
(images and annotations renumbered 1.. in shard order, paths relative to the dataset
folder), Ultralytics YOLO dataset YAMLs listing every shard's images, the WebDataset
tars' list, and the manifest. Memory stays that of one shard's COCO file."""

from __future__ import annotations

import json
import os
import pathlib
import re
import shutil

YOLO_TASKS = ("detect", "segment", "pose")


def write_text(path: pathlib.Path, text: str) -> None:
    partial = path.with_name(path.name + ".partial")
    partial.write_text(text)
    os.replace(partial, path)


# A shard's coco.json as `finflex swim` writes it: the head, then
# ,"annotations":[ ... ],"images":[ ... ]}. Each annotation starts {"id":N,"image_id":M,
# and JSON strings hold no bare quote, so these patterns occur nowhere else.
_ANNOTATIONS = ',"annotations":['
_IMAGES = '],"images":'
_ANNOTATION_START = re.compile(r'\{"id":(\d+),"image_id":(\d+),')


def _split_shard_coco(text: str, path: pathlib.Path):
    start, end = text.find(_ANNOTATIONS), text.rfind(_IMAGES)
    if start < 0 or end < start:
        raise ValueError(f"'{path}' is not a COCO file of finflex swim")
    head = json.loads(text[:start] + "}")
    images = json.loads(text[end + len(_IMAGES):].rstrip()[:-1])
    return head, text[start + len(_ANNOTATIONS):end].strip(), images


def merge_coco(out: pathlib.Path, shards: list, info: dict) -> dict:
    """OUT/coco.json from the shards' coco.json files; the counts. The annotations are
    copied as the shards wrote them, only their "id" and "image_id" renumbered."""
    target = out / "coco.json"
    partial = out / "coco.json.partial"
    images_part = out / ".staging" / "coco-images.partial"
    counts = {"images": 0, "annotations": 0}
    with open(partial, "w") as coco, open(images_part, "w") as image_list:
        for shard in shards:
            prefix = f"shards/{shard.name}/"
            path = out / "shards" / shard.name / "coco.json"
            head, annotations, images = _split_shard_coco(path.read_text(), path)
            if shard is shards[0]:
                first = {"info": info, "licenses": head.get("licenses", []),
                         "categories": head["categories"]}
                coco.write(json.dumps(first, separators=(",", ":"))[:-1] + _ANNOTATIONS)
            images.sort(key=lambda i: i["id"])
            new_id = {}
            for image in images:
                counts["images"] += 1
                new_id[image["id"]] = counts["images"]
            for image in images:
                image["shard"] = shard.index
                image["shard_image_id"] = image["id"]
                image["id"] = new_id[image["id"]]
                for key in ("file_name", "mask_file", "depth_file"):
                    if key in image:
                        image[key] = prefix + image[key]
                if "stereo_pair_id" in image:
                    image["stereo_pair_id"] = new_id[image["stereo_pair_id"]]
                image_list.write(("," if image["id"] > 1 else "")
                                 + json.dumps(image, separators=(",", ":")))

            def renumber(match):
                counts["annotations"] += 1
                return f'{{"id":{counts["annotations"]},"image_id":{new_id[int(match[2])]},'

            if annotations:
                coco.write(("," if counts["annotations"] else "")
                           + _ANNOTATION_START.sub(renumber, annotations))
        coco.write(_IMAGES + "[")
    with open(partial, "a") as coco, open(images_part) as image_list:
        shutil.copyfileobj(image_list, coco)
        coco.write("]}\n")
    images_part.unlink()
    os.replace(partial, target)
    return counts


def write_yolo(out: pathlib.Path, shards: list) -> list[str]:
    """OUT/yolo/TASK.yaml per task: the first shard's classes and keypoint shape, and
    every shard's images (Ultralytics resolves the list from the YAML's folder)."""
    written = []
    (out / "yolo").mkdir(exist_ok=True)
    for task in YOLO_TASKS:
        first = out / "shards" / shards[0].name / "yolo" / task / "dataset.yaml"
        if not first.exists():
            continue
        keep = [line for line in first.read_text().splitlines()
                if not line.startswith(("#", "train:", "val:"))]
        folders = [f"../shards/{s.name}/yolo/{task}/images" for s in shards]
        text = (f"# FinFlex dataset for Ultralytics YOLO ({task}): every shard's images and "
                "labels, relative to this file\n"
                + "train:\n" + "".join(f"  - {f}\n" for f in folders)
                + "val:\n" + "".join(f"  - {f}\n" for f in folders)
                + "\n".join(keep) + "\n")
        write_text(out / "yolo" / f"{task}.yaml", text)
        written.append(f"yolo/{task}.yaml")
    return written


def write_webdataset_list(out: pathlib.Path, shards: list) -> str | None:
    """OUT/webdataset.txt: every shard's tars, one path (relative to OUT) a line."""
    tars = []
    for shard in shards:
        folder = out / "shards" / shard.name / "webdataset"
        tars += [f"shards/{shard.name}/webdataset/{p.name}" for p in sorted(folder.glob("*.tar"))]
    if not tars:
        return None
    write_text(out / "webdataset.txt", "\n".join(tars) + "\n")
    return "webdataset.txt"


def write_manifest(out: pathlib.Path, manifest: dict) -> None:
    write_text(out / "manifest.json", json.dumps(manifest, indent=1) + "\n")
