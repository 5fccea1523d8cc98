"""Python call overhead of one frame: Deformer.enqueue with 4,000 instances'
parameters in (a float32 numpy array, not copied, or a finflex.Parameters) and an
Event out, through Deformer.enqueue and through a Job (Deformer.job, described once), timed around the call with the device idle, against the same loop in C++
(bench/host_overhead.cpp: ClDeformer::enqueue, the same mesh, bend and normals, as
bench_deform's BM_HostOverhead). The difference is the Python overhead.

    PYTHONPATH=build/bindings/python python3 bench/python_overhead.py \
        [--frames 400] [--instances 4000] [--device NAME] [--cpp build/bench/bench_host_overhead]

The loops alternate (--rounds, default 3) and each reports its median. The overhead
is also measured per frame, without the noise between loops: the Python call's time
minus the library enqueue's own time inside it (Event.enqueue_seconds). Prints one
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


def python_enqueue_seconds(frames, instances, device, source, call):
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
    job = deformer.job(batch)
    times, overheads = [], []
    for _ in range(frames):
        if call == "job":
            start = time.perf_counter()
            done = job.enqueue(parameters)
            seconds = time.perf_counter() - start
        else:
            start = time.perf_counter()
            done = deformer.enqueue(parameters, batch)
            seconds = time.perf_counter() - start
        times.append(seconds)
        overheads.append(seconds - done.enqueue_seconds)  # the same frame's C++ enqueue
        done.wait()
        del done  # released outside the timed call, as the C++ loop's event
    return times, overheads


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
              **{f"python_{call}_{source}_median_us": [] for call in ("enqueue", "job")
                 for source in ("array", "Parameters")}}
    if args.cpp:
        result["cpp_median_us"] = []
    for _ in range(args.rounds):
        if args.cpp:
            result["cpp_median_us"].append(
                cpp_enqueue_us(args.cpp, args.frames, args.instances, args.device))
        for call in ("enqueue", "job"):
            for source in ("array", "Parameters"):
                t, over = python_enqueue_seconds(args.frames, args.instances, args.device, source,
                                                 call)
                result[f"python_{call}_{source}_median_us"].append(statistics.median(t) * 1e6)
                result.setdefault(f"overhead_{call}_{source}_median_us", []).append(
                    statistics.median(over) * 1e6)
    for key, value in result.items():
        if isinstance(value, list):
            result[key] = [round(v, 2) for v in value]
    print(json.dumps(result, indent=1))


if __name__ == "__main__":
    main()
