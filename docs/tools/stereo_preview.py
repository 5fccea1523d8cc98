#!/usr/bin/env python3
"""A picture of one stereo frame of a `finflex swim --annotate --stereo B --depth`
dataset for the documentation (docs/dataset.md): the left view, the right view and the
left view's depth map (metres, near bright to far dark; nothing drawn black).

A documentation tool, not part of the build or the tests. Needs numpy and Pillow
(the .venv that scripts/install-deps.sh makes has both).

    .venv/bin/python docs/tools/stereo_preview.py DIR FRAME OUT.png
"""
import json
import os
import sys

import numpy as np
from PIL import Image


def main(folder, frame, out):
    with open(os.path.join(folder, "coco.json")) as f:
        coco = json.load(f)
    views = {i["camera"]: i for i in coco["images"] if i["frame"] == frame}
    left = Image.open(os.path.join(folder, views["left"]["file_name"])).convert("RGB")
    right = Image.open(os.path.join(folder, views["right"]["file_name"])).convert("RGB")
    depth = np.load(os.path.join(folder, views["left"]["depth_file"]))
    seen = depth > 0
    near, far = np.percentile(depth[seen], [1, 99])
    shade = np.clip((far - depth) / (far - near), 0.0, 1.0)
    # A blue-to-yellow ramp, black where nothing is.
    rgb = np.stack([shade, 0.35 + 0.55 * shade, 1.0 - 0.8 * shade], axis=-1)
    rgb = (255 * rgb * seen[..., None]).astype(np.uint8)
    w, h = left.size
    sheet = Image.new("RGB", (3 * w, h))
    for k, part in enumerate((left, right, Image.fromarray(rgb))):
        sheet.paste(part, (k * w, 0))
    sheet.save(out, optimize=True)
    print("%s: frame %d, depth %.2f to %.2f m" % (out, frame, near, far))


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(sys.argv[1], int(sys.argv[2]), sys.argv[3])
