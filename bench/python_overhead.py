"""Python call overhead of one frame: Deformer.enqueue with 4,000 instances'
parameters in (a float32 numpy array, not copied) and an Event out, timed around the
call with the device idle, as bench_deform's BM_HostOverhead times ClDeformer::enqueue
in C++ (the same mesh, bend and normals). The difference is the Python overhead.

    PYTHONPATH=build/bindings/python python3 bench/python_overhead.py \
        [--frames 400] [--instances 4000] [--device NAME] [--cpp build/bench/bench_deform]

With --cpp, also runs BM_HostOverhead (median of its repetitions) in a child process.
Prints one JSON object.
"""

import argparse
import json
import pathlib
import statistics
import subprocess
import time

import numpy as np

import finflex

ROOT = pathlib.Path(__file__).resolve().parents[1]


def python_enqueue_seconds(frames, instances, device, source):
    mesh = finflex.load_mesh(str(ROOT / "data" / "blub" / "fish.obj"))
    model = finflex.Model.single_bend(mesh, mode="paper")
    deformer = finflex.Deformer(finflex.Context(device), model)
    batch = deformer.allocate(instances)
    if source == "array":
        parameters = np.full((instances, 1), 0.1, np.float32)
    else:
        parameters = finflex.Parameters(model, instances)
        parameters.values[:] = 0.1
    deformer.enqueue(parameters, batch).wait()
    times = []
    for _ in range(frames):
        start = time.perf_counter()
        done = deformer.enqueue(parameters, batch)
        times.append(time.perf_counter() - start)
        done.wait()
    return times


def cpp_enqueue_seconds(binary, repetitions):
    out = subprocess.run(
        [binary, "--benchmark_filter=BM_HostOverhead/4000", "--benchmark_format=json",
         f"--benchmark_repetitions={repetitions}", "--benchmark_report_aggregates_only=true"],
        check=True, capture_output=True, text=True).stdout
    runs = json.loads(out)["benchmarks"]
    median = next(b for b in runs if b.get("aggregate_name") == "median")
    mean = next(b for b in runs if b.get("aggregate_name") == "mean")
    scale = {"us": 1e-6, "ms": 1e-3, "ns": 1e-9, "s": 1.0}[median["time_unit"]]
    return median["real_time"] * scale, mean["real_time"] * scale


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--frames", type=int, default=400)
    parser.add_argument("--instances", type=int, default=4000)
    parser.add_argument("--device", default="")
    parser.add_argument("--cpp", help="bench_deform, to run BM_HostOverhead/4000 beside")
    parser.add_argument("--repetitions", type=int, default=10)
    args = parser.parse_args()

    result = {"instances": args.instances, "frames": args.frames,
              "device": finflex.Context(args.device).device.device_name}
    for source in ("array", "Parameters"):
        t = python_enqueue_seconds(args.frames, args.instances, args.device, source)
        result[f"python_{source}_median_us"] = statistics.median(t) * 1e6
        result[f"python_{source}_mean_us"] = statistics.fmean(t) * 1e6
    if args.cpp:
        median, mean = cpp_enqueue_seconds(args.cpp, args.repetitions)
        result["cpp_median_us"] = median * 1e6
        result["cpp_mean_us"] = mean * 1e6
        result["python_overhead_median_us"] = result["python_array_median_us"] - median * 1e6
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
