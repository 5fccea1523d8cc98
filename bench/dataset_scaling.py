"""Frames per second of `python -m finflex.dataset` by workers, side by side in one run
(the shards' phase; the workers' start and the merge are their own columns).

1. The GPU's workload, 1,000 fish at 1280 x 720 in shards of 100: the GPU worker in
   this process and as a Ray actor (the difference is Ray's cost per shard).
2. The CPU workers' workload, the README's tank (200 fish at 640 x 360) in as many
   shards as the most workers: 1, 2, 4 and 8 CPU workers of the same cores each (their
   share of linear scaling from one), the GPU worker alone and the GPU with 8 CPU
   workers.

    python bench/dataset_scaling.py --finflex build/apps/finflex --out /tmp/scaling \
        > docs/results/DEVICE/dataset_scaling.txt

Columns: frames per second of the shards' phase, its share of linear scaling from one
CPU worker, the generator's time per shard beyond the swim's (Ray, hashing, records)
and its share of the shard, the workers' start, the merge, a drawn frame's wall, CPU
and draw-call milliseconds (the median over shards of the swims' own summaries), and
each worker's frames per second.

Rows whose workers the machine lacks (no GPU, no CPU device, too few cores) are left
out and say so."""

import argparse
import glob
import json
import os
import shutil
import statistics
import sys

from finflex.dataset import generate
from finflex.dataset.runner import opencl_devices


def config(fish, width, height):
    return {"tank": {"fish": fish}, "camera": {"width": width, "height": height},
            "annotation": {"depth": False}}


def frame_costs(out):
    """The median over the shards of a drawn frame's wall, CPU and draw milliseconds
    (the swims' summaries)."""
    rows = []
    for path in glob.glob(os.path.join(out, "logs", "*.summary.json")):
        with open(path) as f:
            rendering = json.load(f).get("rendering") or {}
        if "seconds_per_frame_mean" in rendering:
            ms = rendering["seconds_per_frame_mean"]
            rows.append((ms["frame"], rendering["cpu_seconds_per_frame_mean"], ms["draw"]))
    if not rows:
        return "-"
    return "/".join(f"{1000 * statistics.median(r[i] for r in rows):.0f}" for i in range(3))


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--finflex", required=True)
    p.add_argument("--out", required=True, help="a scratch folder (emptied)")
    p.add_argument("--gpu-frames", type=int, default=400)
    p.add_argument("--shard-frames", type=int, default=100)
    p.add_argument("--cpu-shard-frames", type=int, default=25)
    p.add_argument("--cpu-workers", default="1,2,4,8")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    devices = opencl_devices(args.finflex)
    gpus = sum(1 for _, kind in devices if kind == "GPU")
    has_cpu = any(kind == "CPU" for _, kind in devices)
    cores = len(os.sched_getaffinity(0))
    counts = [int(c) for c in args.cpu_workers.split(",")]
    counts = [c for c in counts if c + (1 if gpus else 0) <= cores] or [1]
    threads = max(1, (cores - (1 if gpus else 0)) // max(counts))
    cpu_frames = max(counts) * args.cpu_shard_frames
    gpu_load = dict(frames=args.gpu_frames, shard_frames=args.shard_frames,
                    config=config(1000, 1280, 720))
    cpu_load = dict(frames=cpu_frames, shard_frames=args.cpu_shard_frames,
                    config=config(200, 640, 360))
    # Kernels and shaders built once, before any timed run (the drivers cache them).
    warm = os.path.join(args.out, "warm")
    for wanted, load, cpu_workers in ((gpus, gpu_load, 0), (has_cpu, cpu_load, 1)):
        if wanted:
            generate(warm, frames=1, shard_frames=1, seed=1, cli=args.finflex, quiet=True,
                     config=load["config"], workers=1, cpu_workers=cpu_workers,
                     cpu_threads=threads if cpu_workers else None, use_ray=False)
            shutil.rmtree(warm, ignore_errors=True)
    runs = []
    if gpus:
        runs += [("GPU, in process", gpu_load, dict(workers=1, cpu_workers=0, use_ray=False)),
                 ("GPU, Ray actor", gpu_load, dict(workers=1, cpu_workers=0, use_ray=True))]
    if has_cpu:
        runs += [(f"CPU x{c}", cpu_load, dict(workers=c, cpu_workers=c, cpu_threads=threads,
                                              use_ray=True)) for c in counts]
    if gpus:
        runs.append(("GPU alone", cpu_load, dict(workers=1, cpu_workers=0, use_ray=True)))
    if gpus and has_cpu:
        c = max(counts)
        runs.append((f"GPU + CPU x{c}", cpu_load, dict(workers=1 + c, cpu_workers=c,
                                                      cpu_threads=threads, use_ray=True)))
    print(f"# {cores} cores, {gpus} GPU(s), OpenCL CPU device: {'yes' if has_cpu else 'no'}; "
          f"Python {sys.version.split()[0]}. COCO, optics varied, 30 warm-up frames a shard.")
    print(f"# GPU workload: {args.gpu_frames} frames of 1,000 fish at 1280x720 in shards of "
          f"{args.shard_frames}. CPU workload: {cpu_frames} frames of 200 fish at 640x360 in "
          f"shards of {args.cpu_shard_frames}; CPU workers of {threads} core"
          f"{'s' if threads > 1 else ''} each")
    if not has_cpu:
        print("# no OpenCL CPU device here: the CPU rows are left out")
    print(f"{'workers':<18} {'workload':<9} {'frames/s':>9} {'of linear':>9} "
          f"{'overhead/shard':>15} {'share':>6} {'start s':>8} {'merge s':>8} "
          f"{'frame/CPU/draw ms':>17}  per worker")
    one_cpu = None
    for name, load, options in runs:
        out = os.path.join(args.out, "run")
        shutil.rmtree(out, ignore_errors=True)
        s = generate(out, seed=1, cli=args.finflex, quiet=True, **load, **options)
        fps = s["frames_per_second"]
        if name == "CPU x1":
            one_cpu = fps
        linear = (f"{fps / (options['cpu_workers'] * one_cpu):.2f}"
                  if one_cpu and name.startswith("CPU") else "-")
        per = ", ".join(f"{w['frames_per_second']:.1f}" for w in s["per_worker"])
        workload = "GPU" if load is gpu_load else "CPU"
        print(f"{name:<18} {workload:<9} {fps:>9.2f} {linear:>9} "
              f"{1000 * s['overhead_per_shard_s']:>12.0f} ms {100 * s['overhead_share']:>5.1f}% "
              f"{s['start_seconds']:>8.1f} {s['merge_seconds']:>8.1f} {frame_costs(out):>17}  "
              f"{per}", flush=True)
        shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    main()
