#!/usr/bin/env python3
"""Pictures of a rig for the documentation: a mesh's vertices coloured by rig
component, from the side and from above in the root's body frame, and the fish posed
with some rig parameters.

A documentation tool, not part of the build or the tests. It needs numpy and
matplotlib (pip install numpy matplotlib) and the finflex tool, whose own selection
(`finflex rig-info --labels`) and deformation (`finflex deform --rig`) it draws, so the
picture shows exactly what the library does:

    python3 docs/tools/render_rig.py --finflex build/apps/finflex \\
        --mesh data/blub/fish.obj --rig data/rigs/blub.rig.json \\
        --pose body_m=0.5 --pose tail_angle=-0.7 --pose left_pectoral_angle=0.6 \\
        --out docs/images/rig_blub.png
"""
import argparse
import os
import subprocess
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def read_labels(path):
    names, points = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                continue
            name, x, y, z = line.split()
            names.append(name)
            points.append((float(x), float(y), float(z)))
    return np.array(names), np.array(points)


def read_obj_positions(path):
    with open(path) as f:
        return np.array([[float(v) for v in line.split()[1:4]] for line in f if line.startswith("v ")])


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--finflex", required=True)
    parser.add_argument("--mesh", required=True)
    parser.add_argument("--rig", required=True)
    parser.add_argument("--pose", action="append", default=[], help="NAME=VALUE, repeatable")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()

    with tempfile.TemporaryDirectory() as scratch:
        labels_path = os.path.join(scratch, "labels.txt")
        posed_path = os.path.join(scratch, "posed.obj")
        subprocess.run([args.finflex, "rig-info", "--in", args.mesh, "--rig", args.rig,
                        "--labels", labels_path], check=True, stdout=subprocess.DEVNULL)
        sets = [a for pose in args.pose for a in ("--set", pose)]
        subprocess.run([args.finflex, "deform", "--in", args.mesh, "--rig", args.rig, *sets,
                        "--normals", "jacobian", "--out", posed_path], check=True,
                       stdout=subprocess.DEVNULL)
        names, local = read_labels(labels_path)
        posed_mesh = read_obj_positions(posed_path)

    # The posed fish in the same body frame: rest mesh coordinates map to `local`
    # affinely, so fit that map once and apply it to the posed positions.
    rest_mesh = read_obj_positions_from_rest(args, names)
    affine, *_ = np.linalg.lstsq(np.c_[rest_mesh, np.ones(len(rest_mesh))], local, rcond=None)
    posed = np.c_[posed_mesh, np.ones(len(posed_mesh))] @ affine

    components = list(dict.fromkeys(names))
    colours = plt.cm.tab10(np.arange(len(components)) % 10)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2))
    views = [(local, 0, 1, "side (x, y): rest"), (local, 0, 2, "top (x, z): rest"),
             (posed, 0, 2, "top (x, z): posed")]
    for ax, (points, i, j, title) in zip(axes, views):
        for component, colour in zip(components, colours):
            mask = names == component
            ax.scatter(points[mask, i], points[mask, j], s=0.6, color=colour, label=component)
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("x (head +)")
        ax.grid(True, linewidth=0.3)
    axes[0].legend(markerscale=12, fontsize=8, loc="upper left")
    fig.suptitle(f"{os.path.basename(args.rig)} on {os.path.basename(args.mesh)}; posed: "
                 + ", ".join(args.pose), fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=80)


def read_obj_positions_from_rest(args, names):
    """The rest positions in mesh coordinates, as finflex writes them (same order)."""
    with tempfile.TemporaryDirectory() as scratch:
        rest_path = os.path.join(scratch, "rest.obj")
        subprocess.run([args.finflex, "deform", "--in", args.mesh, "--rig", args.rig,
                        "--out", rest_path], check=True, stdout=subprocess.DEVNULL)
        positions = read_obj_positions(rest_path)
    assert len(positions) == len(names)
    return positions


if __name__ == "__main__":
    main()
