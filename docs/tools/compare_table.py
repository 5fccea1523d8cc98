#!/usr/bin/env python3
"""Table of bench/compare_builds.sh output: per case, builds A and B side by side
(vertices/s and fraction of the write-only kernel, min-max over the rounds).

    python3 docs/tools/compare_table.py results.jsonl
"""
import json
import sys
from collections import defaultdict


def main(path):
    rows = defaultdict(lambda: defaultdict(list))
    for line in open(path):
        line = line.strip()
        if not line.startswith("{"):
            continue
        d = json.loads(line)
        case = f"{d['deformation']} {d['normal_format']}"
        rows[case][d["build"]].append((d["vertices_per_second"], d["write_fraction"]))
    print("| case | A: G vertices/s | A: write fraction | B: G vertices/s | B: write fraction |")
    print("|---|---|---|---|---|")
    for case, builds in rows.items():
        cells = []
        for build in ("A", "B"):
            values = builds.get(build, [])
            if not values:
                cells += ["-", "-"]
                continue
            rates = [v / 1e9 for v, _ in values]
            fractions = [f for _, f in values]
            cells.append(f"{min(rates):.3g}-{max(rates):.3g}")
            cells.append(f"{min(fractions):.2f}-{max(fractions):.2f}")
        print(f"| {case} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main(sys.argv[1])
