"""Checks a dataset written by `finflex swim --out DIR --annotate` with the COCO tools
users train with: pycocotools loads coco.json; every annotation's run-length mask is
exactly the pixels of its fish in the 16-bit mask image; area and bbox are the mask's;
every fish in a mask image has one annotation and no annotation is empty; keypoints
marked visible lie on their fish's box (within 3 pixels, a fin's tip 8); COCOeval scores the ground truth against
itself at AP 1. Prints one line and exits 0, or names the first problem and exits 1.

    python check_coco.py DIR
"""
import contextlib
import io
import json
import os
import sys

import numpy as np
from PIL import Image
from pycocotools import mask as mask_utils
from pycocotools.coco import COCO
from pycocotools.cocoeval import COCOeval


KEYPOINTS = ["snout", "tail_fork", "caudal_upper_tip", "caudal_lower_tip", "left_pectoral_tip",
             "right_pectoral_tip"]


def fail(message):
    print("check_coco: " + message)
    sys.exit(1)


def main(folder):
    with contextlib.redirect_stdout(io.StringIO()):
        coco = COCO(os.path.join(folder, "coco.json"))
    categories = coco.loadCats(coco.getCatIds())
    if not categories:
        fail("no categories")
    for category in categories:
        if category.get("keypoints") != KEYPOINTS:
            fail("category %s has keypoints %s" % (category["name"], category.get("keypoints")))
    images = coco.loadImgs(coco.getImgIds())
    if not images:
        fail("no images")
    annotations = 0
    for image in images:
        picture = Image.open(os.path.join(folder, image["file_name"]))
        if picture.size != (image["width"], image["height"]):
            fail("%s is %s, the entry says %dx%d" % (image["file_name"], picture.size,
                                                    image["width"], image["height"]))
        ids = np.array(Image.open(os.path.join(folder, image["mask_file"])), dtype=np.int64)
        if ids.shape != (image["height"], image["width"]):
            fail("%s has shape %s" % (image["mask_file"], ids.shape))
        entries = coco.loadAnns(coco.getAnnIds(imgIds=[image["id"]]))
        seen = set()
        for entry in entries:
            fish = entry["fish_id"] + 1
            if fish in seen:
                fail("fish %d has two annotations in image %d" % (entry["fish_id"], image["id"]))
            seen.add(fish)
            decoded = coco.annToMask(entry).astype(bool)
            expected = ids == fish
            if not decoded.any():
                fail("annotation %d has an empty mask" % entry["id"])
            if not np.array_equal(decoded, expected):
                fail("annotation %d: its mask differs from the mask image in %d pixels"
                     % (entry["id"], int((decoded != expected).sum())))
            rle = entry["segmentation"]
            if int(mask_utils.area(rle)) != entry["area"] or entry["area"] != int(expected.sum()):
                fail("annotation %d: area %s, mask %d" % (entry["id"], entry["area"],
                                                           int(expected.sum())))
            if [float(v) for v in mask_utils.toBbox(rle)] != [float(v) for v in entry["bbox"]]:
                fail("annotation %d: bbox %s, mask's %s" % (entry["id"], entry["bbox"],
                                                            list(mask_utils.toBbox(rle))))
            # A seen keypoint's vertex may lie past its fish's pixels where a thin part
            # covers no pixel centre: the snout and the fork up to 3 pixels past the box,
            # the fins' tips (thinner) up to 8.
            x, y, w, h = entry["bbox"]
            points = entry["keypoints"]
            for k in range(len(KEYPOINTS)):
                u, v, visibility = points[3 * k:3 * k + 3]
                m = 3 if k < 2 else 8
                if visibility == 2 and not (x - m <= u <= x + w + m and y - m <= v <= y + h + m):
                    fail("annotation %d: visible keypoint %d at (%.1f, %.1f) is off its box %s"
                         % (entry["id"], k, u, v, entry["bbox"]))
            if entry["num_keypoints"] != sum(1 for k in range(len(KEYPOINTS))
                                             if points[3 * k + 2] > 0):
                fail("annotation %d: num_keypoints %d" % (entry["id"], entry["num_keypoints"]))
            # Fork length: shorter than the total length on a forked tail, equal on a
            # round one (the Barramundi's).
            if not entry["length_m"] >= entry["fork_length_m"] > 0.5 * entry["length_m"]:
                fail("annotation %d: length %s, fork length %s" % (entry["id"], entry["length_m"],
                                                                    entry["fork_length_m"]))
        present = set(int(v) for v in np.unique(ids)) - {0}
        if present != seen:
            fail("image %d: fish %s in the mask have no annotation" % (image["id"],
                                                                     sorted(present - seen)))
        if image["fish_visible"] != len(seen):
            fail("image %d: fish_visible %d, %d annotations" % (image["id"], image["fish_visible"],
                                                                len(seen)))
        annotations += len(entries)

    # The ground truth as detections scores AP 1 in COCO's own evaluation.
    detections = []
    for entry in coco.loadAnns(coco.getAnnIds()):
        detections.append({"image_id": entry["image_id"], "category_id": entry["category_id"],
                           "bbox": entry["bbox"], "segmentation": entry["segmentation"],
                           "score": 1.0})
    with contextlib.redirect_stdout(io.StringIO()):
        results = coco.loadRes(detections)
        scores = {}
        for kind in ("bbox", "segm"):
            evaluation = COCOeval(coco, results, kind)
            evaluation.evaluate()
            evaluation.accumulate()
            evaluation.summarize()
            scores[kind] = evaluation.stats[0]
    for kind, score in scores.items():
        if abs(score - 1.0) > 1e-9:
            fail("COCOeval %s AP of the ground truth is %.4f, not 1" % (kind, score))
    with open(os.path.join(folder, "camera.json")) as camera_file:
        camera = json.load(camera_file)
    for key in ("fx", "fy", "cx", "cy", "K", "camera_from_world"):
        if key not in camera:
            fail("camera.json has no %s" % key)
    print("check_coco: %d images, %d annotations, %d categories: all agree (AP bbox %.3f, segm %.3f)"
          % (len(images), annotations, len(categories), scores["bbox"], scores["segm"]))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        fail("usage: check_coco.py DIR")
    main(sys.argv[1])
