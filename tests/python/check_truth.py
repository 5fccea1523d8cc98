"""Checks what `finflex swim --annotate --formats coco,yolo --depth` writes beyond
coco.json against coco.json (itself checked by check_coco.py):

- the three YOLO datasets, read as Ultralytics documents its label layout: each
  dataset.yaml names the classes (and kpt_shape for pose); every image of coco.json
  is in images/ with a label file in labels/; per fish one line, in coco.json's order:
  the class, the box (COCO's bbox normalised, centre and size), the outline's polygon
  (segment: its area is the mask's, or more where a fish's silhouette has a hole) and
  the keypoints (pose: COCO's, normalised, the same visibility);
- the depth maps: float32 height x width; on the tank's floor within 1 mm of the
  camera ray's intersection with the floor's plane (from camera.json alone, its lens
  distortion undone here by OpenCV's model); at each
  seen keypoint whose pixel shows its own fish, printed: the keypoint's camera depth
  against the surface at its pixel's centre, which the surface's slope across the
  pixel sets apart (a pixel is about 16 mm of fish at 320 x 180);
- weights: weight_kg = a (100 L)^b / 1000 with the category's length_weight;
- spines: 16 points from the snout's keypoint to the tail fork's (exactly those
  points), their polyline's length the annotation's spine_length_m, within 1.0 to 1.3
  of the fork length (the midline rises and falls along the body);
- the WebDataset shards: each image a sample, its files byte for byte;
- a stereo pair (camera.json "stereo"): keypoints on the same row in both views,
  disparity fx B / Z, and the right masks where the disparity puts them;
- each image's "optics": the water's properties per channel recomputed here from its
  composition (pure water, dissolved matter, turbidity), both views of a pair alike,
  and with --vary-optics every frame its own draw within the documented ranges.

Prints one line and exits 0, or names the first problem and exits 1.

    python check_truth.py DIR
"""
import json
import os
import sys

import numpy as np


def fail(message):
    print("check_truth: " + message)
    sys.exit(1)


def read_yaml(path):
    """The flat YAML the datasets use: `key: value` lines and the indented names map."""
    out, names, in_names = {}, {}, False
    with open(path) as f:
        for raw in f:
            line = raw.split("#", 1)[0].rstrip()
            if not line:
                continue
            if in_names and line.startswith("  "):
                index, name = line.strip().split(":", 1)
                names[int(index)] = name.strip()
                continue
            in_names = False
            key, value = line.split(":", 1)
            if key == "names" and not value.strip():
                in_names = True
                continue
            out[key.strip()] = value.strip()
    out["names"] = names
    return out


def shoelace(points):
    x, y = points[:, 0], points[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def undistort(xd, yd, k1, k2, p1, p2, k3):
    """The normalised point that OpenCV's distortion model (cv::projectPoints: radial
    k1 k2 k3, tangential p1 p2) takes to (xd, yd), by fixed-point iteration."""
    x, y = xd, yd
    for _ in range(200):
        r2 = x * x + y * y
        radial = 1 + r2 * (k1 + r2 * (k2 + r2 * k3))
        x, y = ((xd - (2 * p1 * x * y + p2 * (r2 + 2 * x * x))) / radial,
                (yd - (p1 * (r2 + 2 * y * y) + 2 * p2 * x * y)) / radial)
    return x, y


def camera_of(folder, image):
    """The image's camera from camera.json: the stereo pair's right one for a right view."""
    with open(os.path.join(folder, "camera.json")) as f:
        camera = json.load(f)
    return camera["stereo"]["right"] if image.get("camera") == "right" else camera


def snell(d, normal, eta):
    """Unit direction d refracted through a face of unit normal `normal` (towards where d
    comes from) from index n1 to n2, eta = n1 / n2 (Snell's law in vector form)."""
    cos_in = -float(d @ normal)
    cos_out = np.sqrt(1.0 - eta * eta * (1.0 - cos_in * cos_in))
    return eta * d + (eta * cos_in - cos_out) * normal


def refracted(eye, ray, refraction, axis):
    """Where the ray from the eye enters the water and its direction there: bent at the
    water surface's plane (its normal up), or through the camera's flat port (air, the
    window, water; its faces square to the camera's axis `axis`), if it bends."""
    d = ray / np.linalg.norm(ray)
    if refraction is None:
        return eye, d
    n = refraction["refractive_index"]
    if refraction.get("interface", "surface") == "port":
        normal = -axis
        inner = eye + refraction["port_distance_m"] / float(d @ axis) * d
        window = refraction["port_refractive_index"]
        d = snell(d, normal, 1.0 / window)
        outer = inner + refraction["port_thickness_m"] / float(d @ axis) * d
        return outer, snell(d, normal, window / n)
    if eye[1] <= refraction["surface_y_m"] or d[1] >= 0:
        return eye, d
    q = eye + (refraction["surface_y_m"] - eye[1]) / d[1] * d
    return q, snell(d, np.array([0.0, 1.0, 0.0]), 1.0 / n)


def floor_errors(folder, image, depth, ids):
    """On pixels that show the tank's floor (no fish at or next to them, the ray's floor
    point well inside the wall), the depth against the ray's intersection with the plane
    y = 0, from camera.json alone (OpenCV's axes; pixel (i, j)'s centre at i + 0.5,
    j + 0.5; with "refraction", the ray bent at the surface or the camera's port)."""
    camera = camera_of(folder, image)
    with open(os.path.join(folder, "camera.json")) as f:
        refraction = json.load(f).get("refraction")
    k1, k2, p1, p2, k3 = camera["distortion"]
    with open(os.path.join(folder, "summary.json")) as f:
        radius = 0.5 * json.load(f)["tank"]["diameter_m"]
    world_from_camera = np.array(camera["world_from_camera"])
    rotation, eye = world_from_camera[:3, :3], world_from_camera[:3, 3]
    out = []
    for j in range(0, image["height"], 3):
        for i in range(0, image["width"], 3):
            # Floor all around: at a fish's edge a lens takes the nearest pixel's depth.
            if ids[max(j - 1, 0):j + 2, max(i - 1, 0):i + 2].any():
                continue
            x, y = undistort((i + 0.5 - camera["cx"]) / camera["fx"],
                             (j + 0.5 - camera["cy"]) / camera["fy"], k1, k2, p1, p2, k3)
            ray = rotation @ np.array([x, y, 1.0])
            if ray[1] >= 0:
                continue
            start, direction = refracted(eye, ray, refraction, rotation[:, 2])
            point = start - start[1] / direction[1] * direction  # where it meets y = 0
            z = float(rotation[:, 2] @ (point - eye))  # its camera depth
            if np.hypot(point[0], point[2]) < 0.9 * radius:
                out.append(abs(float(depth[j, i]) - z))
    return out


def check_webdataset(folder, coco, by_image):
    """The tar shards, read with Python's tarfile as WebDataset reads them (members grouped
    by the name's part before its first dot): one sample per image of coco.json, its
    picture, mask and depth byte for byte the dataset's files, its JSON the image's entry
    and annotations."""
    import glob
    import tarfile
    paths = sorted(glob.glob(os.path.join(folder, "webdataset", "shard-*.tar")))
    if not paths:
        return ""
    samples = {}
    for path in paths:
        with tarfile.open(path) as tar:
            for member in tar.getmembers():
                key, extension = member.name.split(".", 1)
                samples.setdefault(key, {})[extension] = tar.extractfile(member).read()
    if len(samples) != len(coco["images"]):
        fail("webdataset: %d samples for %d images" % (len(samples), len(coco["images"])))
    for image in coco["images"]:
        key = os.path.splitext(os.path.basename(image["file_name"]))[0]
        sample = samples.get(key)
        if sample is None:
            fail("webdataset: no sample %s" % key)
        parts = {"png": image["file_name"], "mask.png": image["mask_file"]}
        if "depth_file" in image:
            parts["depth.npy"] = image["depth_file"]
        for extension, name in parts.items():
            with open(os.path.join(folder, name), "rb") as f:
                if sample.get(extension) != f.read():
                    fail("webdataset: %s.%s differs from %s" % (key, extension, name))
        entry = json.loads(sample["json"])
        wanted = [a["id"] for a in by_image.get(image["id"], [])]
        if entry["image"]["id"] != image["id"] or [a["id"] for a in entry["annotations"]] != wanted:
            fail("webdataset: %s.json is not image %d's entry and annotations" % (key, image["id"]))
    return "; webdataset: %d shard(s), %d samples equal to the files" % (len(paths), len(samples))


def check_stereo(folder, coco, by_image):
    """A stereo pair's views: each keypoint seen in both (its lens undone) on the same row,
    its disparity
    u_left - u_right = fx B / Z (Z its left camera depth) within 0.5 px; and the right
    picture is the right camera's: per fish seen in both, its mask's centre moves by the
    fish's disparity (median over the fish within 1 px)."""
    with open(os.path.join(folder, "camera.json")) as f:
        camera = json.load(f)
    if "stereo" not in camera:
        return ""
    from PIL import Image
    fx, baseline = camera["fx"], camera["stereo"]["baseline_m"]
    k = camera["distortion"]

    def ideal(u, v):  # a keypoint's pixel without the lens: where the pair is rectified
        x, y = undistort((u - camera["cx"]) / fx, (v - camera["cy"]) / camera["fy"], *k)
        return fx * x + camera["cx"], camera["fy"] * y + camera["cy"]

    images = {image["id"]: image for image in coco["images"]}
    worst, shifts, pairs = 0.0, [], 0
    for image in coco["images"]:
        if image.get("camera") != "left":
            continue
        right = images[image["stereo_pair_id"]]
        pairs += 1
        left_fish = {a["fish_id"]: a for a in by_image.get(image["id"], [])}
        right_fish = {a["fish_id"]: a for a in by_image.get(right["id"], [])}
        ids = [np.array(Image.open(os.path.join(folder, i["mask_file"])), dtype=np.int64)
               for i in (image, right)]
        for fish, a in left_fish.items():
            if fish not in right_fish:
                continue
            b = right_fish[fish]
            for n in range(len(a["keypoints"]) // 3):
                u, v, vis = a["keypoints"][3 * n:3 * n + 3]
                u2, v2, vis2 = b["keypoints"][3 * n:3 * n + 3]
                if vis == 0 or vis2 == 0:
                    continue
                z = a["keypoints_camera_m"][n][2]
                (u, v), (u2, v2) = ideal(u, v), ideal(u2, v2)
                if abs(v - v2) > 1e-6:
                    fail("stereo: fish %d keypoint %d on rows %.4f and %.4f" % (fish, n, v, v2))
                worst = max(worst, abs((u - u2) - fx * baseline / z))
            z = 0.5 * (a["keypoints_camera_m"][0][2] + a["keypoints_camera_m"][1][2])  # its middle
            columns = [np.nonzero(m == fish + 1)[1].mean() for m in ids]
            shifts.append((columns[0] - columns[1]) - fx * baseline / z)
    if worst > 0.5:
        fail("stereo: a keypoint's disparity is %.3f px off fx B / Z" % worst)
    if not shifts or abs(float(np.median(shifts))) > 1.0:
        fail("stereo: the right masks move %.2f px off the disparity (median of %d fish)"
             % (float(np.median(shifts or [99])), len(shifts)))
    return ("; stereo: %d pairs, disparities within %.1e px of fx B / Z, the masks moved by"
            " them to %.2f px (median)" % (pairs, worst, float(np.median(shifts))))


PURE_WATER_ABSORPTION = (0.2644, 0.0565, 0.0102)  # Pope and Fry 1997, per metre


def check_optics(coco):
    varied = coco["info"]["vary_optics"]
    by_frame = {}
    for image in coco["images"]:
        o = image.get("optics")
        if o is None:
            fail("image %d has no optics" % image["id"])
        ntu, cdom = o["turbidity_ntu"], o["dissolved_absorption_440_per_m"]
        for c, wavelength in enumerate(o["wavelengths_nm"]):
            a = PURE_WATER_ABSORPTION[c] + cdom * np.exp(-0.014 * (wavelength - 440.0))
            b = 0.0022 * (500.0 / wavelength) ** 4.32 + ntu * 550.0 / wavelength
            got = (o["absorption_per_m"][c], o["scattering_per_m"][c], o["attenuation_per_m"][c])
            if max(abs(p - q) for p, q in zip(got, (a, b, a + b))) > 1e-5 * (1 + a + b):
                fail("image %d: water %s, its composition gives a %.5f, b %.5f at %g nm"
                     % (image["id"], got, a, b, wavelength))
        elevation = np.degrees(np.arcsin(o["direction_to_light"][1]))
        if varied and not (0 <= ntu <= 5 and 0 <= cdom <= 3 and 0.5 <= o["light_scale"] <= 1.5
                           and 50 - 1e-3 <= elevation <= 90 + 1e-3):
            fail("image %d: optics outside the varied ranges: %s" % (image["id"], o))
        by_frame.setdefault(image["frame"], []).append(o)
    for frame, views in by_frame.items():
        if any(v != views[0] for v in views):
            fail("frame %d: its views have different optics" % frame)
    if not varied:
        if len({json.dumps(v[0]) for v in by_frame.values()}) != 1:
            fail("without --vary-optics, the frames have different water and light")
        return "; optics: the same in all %d frames" % len(by_frame)
    if len({json.dumps(v[0]) for v in by_frame.values()}) != len(by_frame):
        fail("with --vary-optics, frames share their water and light")
    return "; optics: %d frames, each its own water and light" % len(by_frame)


def main(folder):
    with open(os.path.join(folder, "coco.json")) as f:
        coco = json.load(f)
    categories = {c["id"]: c for c in coco["categories"]}
    by_image = {}
    for a in coco["annotations"]:
        by_image.setdefault(a["image_id"], []).append(a)
    for a in coco["annotations"]:
        relation = categories[a["category_id"]]["length_weight"]
        expected = relation["a"] * (100.0 * a["length_m"]) ** relation["b"] / 1000.0
        if abs(a["weight_kg"] - expected) > 1e-9 * max(1.0, expected):
            fail("annotation %d: weight %s kg, the relation gives %s" % (a["id"], a["weight_kg"],
                                                                       expected))
    spine_ratios = []
    for a in coco["annotations"]:
        spine = np.array(a["spine_camera_m"])
        snout, fork = a["keypoints_camera_m"][0], a["keypoints_camera_m"][1]
        if spine.shape != (16, 3) or np.abs(spine[0] - snout).max() > 1e-9 or \
                np.abs(spine[-1] - fork).max() > 1e-9:
            fail("annotation %d: the spine does not run from the snout to the tail fork" % a["id"])
        length = float(np.linalg.norm(np.diff(spine, axis=0), axis=1).sum())
        if abs(length - a["spine_length_m"]) > 1e-9:
            fail("annotation %d: spine_length_m %s, its points' %s" % (a["id"], a["spine_length_m"],
                                                                     length))
        spine_ratios.append(length / a["fork_length_m"])
    if not 1.0 <= min(spine_ratios) <= max(spine_ratios) <= 1.3:
        fail("spine lengths %.3f to %.3f of the fork length" % (min(spine_ratios),
                                                                max(spine_ratios)))
    lines = 0
    holes = 0
    for task in ("detect", "segment", "pose"):
        root = os.path.join(folder, "yolo", task)
        yaml = read_yaml(os.path.join(root, "dataset.yaml"))
        if yaml.get("train") != "images" or yaml.get("val") != "images":
            fail("%s/dataset.yaml: train %s, val %s" % (task, yaml.get("train"), yaml.get("val")))
        names = [categories[k]["name"] for k in sorted(categories)]
        if [yaml["names"][k] for k in sorted(yaml["names"])] != names:
            fail("%s/dataset.yaml: names %s, coco.json's %s" % (task, yaml["names"], names))
        if task == "pose" and yaml.get("kpt_shape") != "[6, 3]":
            fail("pose/dataset.yaml: kpt_shape %s" % yaml.get("kpt_shape"))
        for image in coco["images"]:
            stem = os.path.splitext(os.path.basename(image["file_name"]))[0]
            picture = os.path.join(root, "images", os.path.basename(image["file_name"]))
            if not os.path.isfile(picture):
                fail("%s: no image %s" % (task, picture))
            with open(os.path.join(root, "labels", stem + ".txt")) as f:
                rows = [list(map(float, line.split())) for line in f if line.strip()]
            entries = by_image.get(image["id"], [])
            if len(rows) != len(entries):
                fail("%s %s: %d lines for %d fish" % (task, stem, len(rows), len(entries)))
            w, h = image["width"], image["height"]
            for row, a in zip(rows, entries):
                lines += 1
                if int(row[0]) != a["category_id"] - 1:
                    fail("%s %s: class %s for category %d" % (task, stem, row[0], a["category_id"]))
                x, y, bw, bh = a["bbox"]
                box = [(x + bw / 2) / w, (y + bh / 2) / h, bw / w, bh / h]
                if task == "segment":
                    points = np.array(row[1:]).reshape(-1, 2) * [w, h]
                    if len(points) < 3:
                        fail("segment %s: fish %d has %d points" % (stem, a["fish_id"], len(points)))
                    area = shoelace(points)
                    # Six decimals of the image's size: a few hundredths of a pixel of area.
                    if area < a["area"] - 0.1:
                        fail("segment %s: fish %d's outline holds %.1f pixels, its mask %d"
                             % (stem, a["fish_id"], area, a["area"]))
                    holes += area > a["area"] + 0.1
                    continue
                if max(abs(p - q) for p, q in zip(row[1:5], box)) > 2e-6:
                    fail("%s %s: fish %d's box %s, COCO's %s" % (task, stem, a["fish_id"], row[1:5],
                                                               box))
                if task == "pose":
                    k = a["keypoints"]
                    for i in range(len(k) // 3):
                        u, v, vis = k[3 * i:3 * i + 3]
                        got = row[5 + 3 * i:8 + 3 * i]
                        want = [u / w, v / h, vis] if vis > 0 else [0.0, 0.0, 0]
                        if max(abs(p - q) for p, q in zip(got, want)) > 2e-6:
                            fail("pose %s: fish %d keypoint %d %s, COCO's %s"
                                 % (stem, a["fish_id"], i, got, want))
    if holes > 0.05 * lines / 3:
        fail("%d of %d outlines hold more than their masks" % (holes, lines // 3))

    errors = {0: [], 1: []}  # the snout's and the tail fork's
    floor = []
    for image in coco["images"]:
        depth = np.load(os.path.join(folder, image["depth_file"]))
        if depth.dtype != np.float32 or depth.shape != (image["height"], image["width"]):
            fail("%s: %s %s" % (image["depth_file"], depth.dtype, depth.shape))
        from PIL import Image
        ids = np.array(Image.open(os.path.join(folder, image["mask_file"])), dtype=np.int64)
        for a in by_image.get(image["id"], []):
            for i in range(2):
                u, v, vis = a["keypoints"][3 * i:3 * i + 3]
                if vis != 2 or ids[int(v), int(u)] != a["fish_id"] + 1:
                    continue
                errors[i].append(abs(float(depth[int(v), int(u)]) - a["keypoints_camera_m"][i][2]))
        floor.extend(floor_errors(folder, image, depth, ids))
    if not floor or max(floor) > 1e-3:
        fail("depth on the tank's floor: largest error %.3f mm over %d pixels"
             % (1e3 * max(floor or [0]), len(floor)))
    stereo = check_stereo(folder, coco, by_image)
    shards = check_webdataset(folder, coco, by_image)
    optics = check_optics(coco)
    medians = [float(np.median(errors[i])) if errors[i] else 0.0 for i in range(2)]
    with open(os.path.join(folder, "camera.json")) as f:
        bent = json.load(f).get("refraction")
    refraction = "; refracted at the %s" % bent.get("interface", "surface") if bent else ""
    print("check_truth: %d YOLO lines agree with coco.json (%d outlines with holes); depth on the "
          "floor within %.3f mm (%d pixels), at keypoints: snout median %.1f mm (%d), tail fork "
          "median %.1f mm (%d); weights follow their relation; spines %.3f to %.3f of the fork "
          "length%s%s%s%s"
          % (lines, holes, 1e3 * max(floor), len(floor), 1e3 * medians[0], len(errors[0]),
             1e3 * medians[1], len(errors[1]), min(spine_ratios), max(spine_ratios), stereo, shards,
             optics, refraction))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        fail("usage: check_truth.py DIR")
    main(sys.argv[1])
