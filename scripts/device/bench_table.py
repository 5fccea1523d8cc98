#!/usr/bin/env python3
"""Prints a device script's runs (FILE: one JSON line per run, each with a
`finflex bench --json` result) as a table: the run's label (its "case", or its
"binary" and "round"), ms a frame, the fraction of the write-only kernel's bandwidth,
the host's microseconds a frame and each kernel's median (ms).

    bench_table.py FILE
"""
import json
import sys


def label(run):
    if "case" in run:
        return run["case"]
    return f"{run['binary']}, round {run['round']}"


print(f"{'run':44} {'ms/frame':>9} {'of write-only':>13} {'host us':>8}  kernels (ms)")
for line in open(sys.argv[1]):
    run = json.loads(line)
    r = run["result"]
    if r is None:
        print(f"{label(run):44} failed")
        continue
    kernels = " ".join(f"{k * 1e3:.4f}" for k in r["kernel_seconds_median"])
    print(f"{label(run):44} {r['seconds_per_frame_median'] * 1e3:9.3f} "
          f"{r['write_fraction']:13.3f} {r['host_enqueue_seconds_median'] * 1e6:8.0f}  {kernels}")
