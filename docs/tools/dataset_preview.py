#!/usr/bin/env python3
"""A picture of one frame of a `finflex swim --annotate` dataset for the documentation
(docs/dataset.md): the rendered frame beside its instance mask, each fish in its own
colour, with the COCO boxes and the two keypoints (snout white, tail fork black; a
hidden keypoint drawn hollow).

A documentation tool, not part of the build or the tests. Needs numpy and Pillow
(the .venv that scripts/install-deps.sh makes has both).

    .venv/bin/python docs/tools/dataset_preview.py DIR FRAME OUT.png [X,Y,W,H]

X,Y,W,H crops both halves to that region of the frame (pixels).
"""
import json
import os
import sys

import numpy as np
from PIL import Image, ImageDraw


def main(folder, frame, out, crop=None):
    with open(os.path.join(folder, "coco.json")) as f:
        coco = json.load(f)
    image = next(i for i in coco["images"] if i["frame"] == frame)
    picture = Image.open(os.path.join(folder, image["file_name"])).convert("RGB")
    ids = np.array(Image.open(os.path.join(folder, image["mask_file"])), dtype=np.int64)
    # A colour per fish id, fixed by the id: the same fish has the same colour in every frame.
    rng = np.random.default_rng(1)
    palette = rng.integers(60, 256, size=(int(ids.max()) + 1, 3), dtype=np.uint8)
    palette[0] = (16, 18, 22)
    mask = Image.fromarray(palette[ids])
    draw = ImageDraw.Draw(mask)
    for a in coco["annotations"]:
        if a["image_id"] != image["id"]:
            continue
        x, y, w, h = a["bbox"]
        draw.rectangle([x, y, x + w - 1, y + h - 1], outline=tuple(int(c) for c in palette[a["fish_id"] + 1]))
        for k, colour in ((0, (255, 255, 255)), (1, (0, 0, 0))):
            u, v, visible = a["keypoints"][3 * k:3 * k + 3]
            if visible == 0:
                continue
            box = [u - 3, v - 3, u + 3, v + 3]
            if visible == 2:
                draw.ellipse(box, fill=colour)
            else:
                draw.ellipse(box, outline=colour)
    if crop:
        x, y, w, h = crop
        picture = picture.crop((x, y, x + w, y + h))
        mask = mask.crop((x, y, x + w, y + h))
    both = Image.new("RGB", (picture.width * 2 + 4, picture.height), (255, 255, 255))
    both.paste(picture, (0, 0))
    both.paste(mask, (picture.width + 4, 0))
    both.save(out, optimize=True)
    print("wrote %s: frame %d, %d fish visible of %d" % (out, frame, image["fish_visible"],
                                                         image["fish_in_tank"]))


if __name__ == "__main__":
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3],
         [int(v) for v in sys.argv[4].split(",")] if len(sys.argv) == 5 else None)
