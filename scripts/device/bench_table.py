#!/usr/bin/env python3
"""Prints a run.sh suite's runs (FILE: one JSON line per run) as one table: each
`finflex bench --json` result by its case, side (A/B), thread count and round, in ms a
frame, the fraction of the write-only kernel's bandwidth (measured in the same run),
the host's microseconds a frame and each kernel's median (ms); each bench_deform report
(the OpenMP baselines) by its benchmarks' ms. With two sides (an A/B), then the median
of every case's rounds per side, and B over A.

    bench_table.py FILE
"""
import json
import statistics
import sys


def label(run):
    parts = [run.get("case", "")]
    if run.get("side"):
        parts.append(run["side"])
    if run.get("threads") is not None:
        parts.append(f"{run['threads']} threads")
    parts.append(f"round {run.get('round', 1)}")
    return ", ".join(p for p in parts if p)


def bench_row(name, r):
    kernels = " ".join(f"{k * 1e3:.4f}" for k in r["kernel_seconds_median"])
    return (f"{name:60} {r['seconds_per_frame_median'] * 1e3:9.3f} "
            f"{r['write_fraction']:13.3f} {r['host_enqueue_seconds_median'] * 1e6:8.0f}  {kernels}")


def farm_row(name, r):
    """A `finflex bench --farm` result: with levels and at full detail, side by side."""
    levels, full = r["with_levels"], r["full_detail"]
    fish = "/".join(str(level["fish"]) for level in r["levels"])
    return (f"{name:60} {levels['frame_seconds_median'] * 1e3:9.3f} ms with levels "
            f"({levels['vertices_per_frame'] / 1e6:.1f} M vertices, fish per level {fish}, "
            f"choice {levels['level_choice_seconds_median'] * 1e3:.3f} ms = "
            f"{levels['level_choice_share']:.3f}); {full['frame_seconds_median'] * 1e3:.3f} ms "
            f"at full detail ({full['vertices_per_frame'] / 1e6:.1f} M vertices): "
            f"{r['speedup']:.2f}x")


def main(path):
    runs = [json.loads(line) for line in open(path) if line.strip()]
    print(f"{'run':60} {'ms/frame':>9} {'of write-only':>13} {'host us':>8}  kernels (ms)")
    for run in runs:
        if "report" in run:
            report = run["report"]
            if report is None:
                print(f"{label(run):60} failed")
                continue
            for b in report["benchmarks"]:
                ms = b["real_time"] * {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b["time_unit"]]
                print(f"{label(run) + ': ' + b['name']:60} {ms:9.3f}")
            continue
        if run["result"] is None:
            print(f"{label(run):60} failed")
            continue
        if "with_levels" in run["result"]:
            print(farm_row(label(run), run["result"]))
            continue
        print(bench_row(label(run), run["result"]))

    sides = sorted({run.get("side", "") for run in runs if "result" in run})
    if len(sides) != 2:
        return
    # Per case and thread count: each side's median over the rounds.
    cases = {}
    for run in runs:
        if run.get("result") is None or "with_levels" in run["result"]:
            continue
        key = (run["case"], run.get("threads"))
        cases.setdefault(key, {}).setdefault(run["side"], []).append(run["result"])
    print()
    print(f"{'case (medians of the rounds)':60} {'A ms':>9} {'B ms':>9} {'B/A':>6} "
          f"{'A of w-o':>9} {'B of w-o':>9}")
    for (case, threads), by_side in cases.items():
        if len(by_side) != 2:
            continue
        a, b = (by_side[s] for s in sides)
        ms = [statistics.median(r["seconds_per_frame_median"] for r in side) * 1e3
              for side in (a, b)]
        fraction = [statistics.median(r["write_fraction"] for r in side) for side in (a, b)]
        name = case if threads is None else f"{case}, {threads} threads"
        print(f"{name:60} {ms[0]:9.3f} {ms[1]:9.3f} {ms[1] / ms[0]:6.3f} "
              f"{fraction[0]:9.3f} {fraction[1]:9.3f}")
    print(f"A: {sides[0]}\nB: {sides[1]}")


if __name__ == "__main__":
    main(sys.argv[1])
