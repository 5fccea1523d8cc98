#!/usr/bin/env python3
"""Scaling plots from a sweep (`scripts/device/run.sh ... sweep`: one run a line, its
`finflex bench --json` object under "result"; bare objects a line are read too):
vertices/s against instances, one panel per mesh, one line per deformation and output
format, and the write-only kernel's rate for float32 outputs measured in the same runs.

A documentation tool (numpy-free; needs matplotlib):

    python3 docs/tools/plot_bench.py docs/results/vm-2-core/sweep.jsonl \\
        --title "PoCL, 2 cores" --out docs/images/scaling_pocl.png
"""
import argparse
import json
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results")
    parser.add_argument("--title", default="")
    parser.add_argument("--out", required=True)
    args = parser.parse_args()

    with open(args.results) as f:
        lines = [json.loads(line) for line in f if line.strip().startswith("{")]
    rows = [r.get("result", r) for r in lines]
    rows = [r for r in rows if r]
    meshes = sorted({r["vertices"] for r in rows})
    fig, axes = plt.subplots(1, len(meshes), figsize=(4.2 * len(meshes), 3.8), squeeze=False)
    for ax, vertices in zip(axes[0], meshes):
        lines = defaultdict(list)
        for r in rows:
            if r["vertices"] != vertices:
                continue
            half = r.get("normal_format") == "half"
            name = r["deformation"] + (", half normals" if half else "")
            lines[name].append((r["instances"], r["vertices_per_second"]))
            if not half:  # bytes/s over the bytes each vertex writes
                bytes_per_vertex = r["output_bytes_per_second"] / r["vertices_per_second"]
                lines["write-only kernel"].append(
                    (r["instances"], r["write_bandwidth_bytes_per_second"] / bytes_per_vertex))
        for name, points in sorted(lines.items()):
            best = {}
            for instances, rate in points:  # the write-only kernel: best of its runs
                best[instances] = max(best.get(instances, 0.0), rate)
            xs = sorted(best)
            style = dict(linestyle="--", color="black") if name == "write-only kernel" else {}
            ax.plot(xs, [best[x] for x in xs], marker="o", markersize=3, label=name, **style)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("instances")
        ax.set_title(f"{vertices:,} vertices", fontsize=9)
        ax.grid(True, which="both", linewidth=0.3)
    axes[0][0].set_ylabel("vertices / s")
    axes[0][0].legend(fontsize=7)
    device = rows[0]["device"] if rows else ""
    fig.suptitle(f"{args.title} ({device})", fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=80)
    print(f"{len(rows)} results -> {os.path.abspath(args.out)}")


if __name__ == "__main__":
    main()
