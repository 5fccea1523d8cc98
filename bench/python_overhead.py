"""Python call overhead of one frame: Deformer.enqueue with 4,000 instances'
parameters in (a float32 numpy array, not copied, or a finflex.Parameters) and an
Event out, timed around the call with the device idle, against the same loop in C++
(bench/host_overhead.cpp: ClDeformer::enqueue, the same mesh, bend and normals, as
bench_deform's BM_HostOverhead). The difference is the Python overhead.

    PYTHONPATH=build/bindings/python python3 bench/python_overhead.py \
        [--frames 400] [--instances 4000] [--device NAME] [--cpp build/bench/bench_host_overhead]

The two loops alternate (--rounds, default 3) and each reports its median; prints one
JSON object.
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
        del done  # released outside the timed call, as the C++ loop's event
    return times


def cpp_enqueue_us(binary, frames, instances, device):
    mesh = str(ROOT / "data" / "blub" / "fish.obj")
    out = subprocess.run([binary, str(frames), str(instances), device, mesh],
                         check=True, capture_output=True, text=True).stdout
    return json.loads(out)["median_us"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--frames", type=int, default=400)
    parser.add_argument("--instances", type=int, default=4000)
    parser.add_argument("--device", default="")
    parser.add_argument("--cpp", help="bench_host_overhead, to run the C++ loop beside")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()

    result = {"instances": args.instances, "frames": args.frames,
              "device": finflex.Context(args.device).device.device_name,
              "python_array_median_us": [], "python_Parameters_median_us": []}
    if args.cpp:
        result["cpp_median_us"] = []
    for _ in range(args.rounds):
        if args.cpp:
            result["cpp_median_us"].append(
                cpp_enqueue_us(args.cpp, args.frames, args.instances, args.device))
        for source in ("array", "Parameters"):
            t = python_enqueue_seconds(args.frames, args.instances, args.device, source)
            result[f"python_{source}_median_us"].append(statistics.median(t) * 1e6)
    if args.cpp:
        result["python_overhead_us"] = [
            round(p - c, 2) for p, c in zip(result["python_array_median_us"], result["cpp_median_us"])]
    for key, value in result.items():
        if isinstance(value, list):
            result[key] = [round(v, 2) for v in value]
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
