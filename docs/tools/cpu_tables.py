#!/usr/bin/env python3
"""The tables of docs/benchmarks.md's CPU sections from a run of
scripts/device/pocl_cpu_bench.sh (its OUT_DIR, or the committed files of one run):

    python3 docs/tools/cpu_tables.py OUT_DIR
    python3 docs/tools/cpu_tables.py --cases C.jsonl --one-run O.jsonl --scaling S.jsonl

Every ratio is between figures of one process: a `finflex bench` case against the
write-only kernel it ran next to (write_fraction), and in the one-process table the
kernels against the OpenMP baselines and the write-only kernel of the same
bench_deform run."""
import argparse
import json
import os
import re


def lines(path):
    with open(path) as f:
        return [json.loads(line) for line in f if line.strip()]


def giga(value):
    return "%.3g" % (value / 1e9)


def cases_table(path):
    rows = lines(path)
    print("| instances | case | lanes | G vertices/s | of write-only | write-only GB/s |")
    print("|---|---|---|---|---|---|")
    for row in rows:
        r = row["result"]
        if r is None:
            print("| | %s | | failed | | |" % row["case"])
            continue
        lanes = "%d%s" % (r["lanes"], ", streaming" if r.get("streaming_stores") else "")
        print("| %d | %s | %s | %s | %.2f | %.1f |" % (
            r["instances"], row["case"], lanes, giga(r["vertices_per_second"]),
            r["write_fraction"], r["write_bandwidth_bytes_per_second"] / 1e9))


def benchmarks(report):
    """name -> benchmark of a bench_deform JSON report (names without the
    /min_time/manual_time suffixes)."""
    out = {}
    for b in report["benchmarks"] if report else []:
        name = re.sub(r"/min_time:[^/]*|/manual_time", "", b["name"])
        out[name] = b
    return out


def one_run_table(path):
    print("| instances | write-only (fastest shape) | bend paper | rig fused | OpenMP float3 "
          "| OpenMP planes + simd | bend / simd baseline |")
    print("|---|---|---|---|---|---|---|")
    for row in lines(path):
        b = benchmarks(row["report"])
        if not b:
            print("| | failed | | | | | |")
            continue
        instances = next(int(v["instances"]) for v in b.values())
        writes = [v for k, v in b.items() if k.startswith("BM_WriteOnly/")]
        best = max(writes, key=lambda v: v["bytes/s"])
        shape = best["name"].split("/")[1]

        def rate(prefix):
            found = [v for k, v in b.items() if k.startswith(prefix)]
            return found[0]["vertices/s"] if found else float("nan")

        bend, rig = rate("BM_Bend/paper_rotate"), rate("BM_Rig/fused")
        aos, simd = rate("BM_OpenMPBaseline"), rate("BM_OpenMPSimdBaseline")
        write_rate = best["vertices/s"]
        print("| %d | %s G/s, %.1f GB/s (%s) | %s G (%.2f) | %s G (%.2f) | %s G | %s G | %.2fx |" % (
            instances, giga(write_rate), best["bytes/s"] / 1e9, shape, giga(bend),
            bend / write_rate, giga(rig), rig / write_rate, giga(aos), giga(simd),
            bend / simd))


def scaling_table(path):
    rows = lines(path)
    by_threads = {}
    for row in rows:
        by_threads.setdefault(row["threads"], {})[row["case"]] = row
    first = None
    print("| threads | bend paper G vertices/s | of write-only | write-only GB/s | speed-up "
          "| rig fused G/s | of write-only | OpenMP float3 | OpenMP planes + simd |")
    print("|---|---|---|---|---|---|---|---|---|")
    for threads in sorted(by_threads):
        cases = by_threads[threads]
        bend = cases.get("bend paper", {}).get("result")
        rig = cases.get("rig fused", {}).get("result")
        omp = benchmarks(cases.get("OpenMP baselines", {}).get("report"))
        if bend and first is None:
            first = bend["vertices_per_second"]

        def omp_rate(name):
            found = [v for k, v in omp.items() if k.startswith(name + "/")]
            return giga(found[0]["vertices/s"]) if found else ""

        print("| %d | %s | %s | %s | %s | %s | %s | %s | %s |" % (
            threads,
            giga(bend["vertices_per_second"]) if bend else "failed",
            "%.2f" % bend["write_fraction"] if bend else "",
            "%.1f" % (bend["write_bandwidth_bytes_per_second"] / 1e9) if bend else "",
            "%.1fx" % (bend["vertices_per_second"] / first) if bend and first else "",
            giga(rig["vertices_per_second"]) if rig else "failed",
            "%.2f" % rig["write_fraction"] if rig else "",
            omp_rate("BM_OpenMPBaseline"), omp_rate("BM_OpenMPSimdBaseline")))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out_dir", nargs="?")
    parser.add_argument("--cases")
    parser.add_argument("--one-run")
    parser.add_argument("--scaling")
    args = parser.parse_args()
    if args.out_dir:
        args.cases = args.cases or os.path.join(args.out_dir, "cases.jsonl")
        args.one_run = args.one_run or os.path.join(args.out_dir, "one_run.jsonl")
        args.scaling = args.scaling or os.path.join(args.out_dir, "scaling.jsonl")
    for title, path, table in (("Cases", args.cases, cases_table),
                               ("One process", args.one_run, one_run_table),
                               ("Threads", args.scaling, scaling_table)):
        if path and os.path.exists(path):
            print("\n%s (%s)\n" % (title, path))
            table(path)


if __name__ == "__main__":
    main()
