"""Frames per second of `python -m finflex.dataset` by workers (the shards' phase:
the workers' start and the merge are their own columns), side by side in one run:
the GPU worker alone (in this process, and as a Ray actor: the difference is Ray's
cost), CPU workers alone (1, 2, 4, 8 where the cores allow) and the GPU with CPU
workers; CPU rows' share of linear scaling from one CPU worker and the overhead per shard (a
shard's task time beyond its swim process's).

    python bench/dataset_scaling.py --finflex build/apps/finflex --out /tmp/scaling \
        --frames 400 --shard-frames 100 > docs/results/DEVICE/dataset_scaling.txt

Rows whose workers the machine lacks (no GPU, no CPU device, too few cores) are
left out and say so."""

import argparse
import os
import shutil
import sys

from finflex.dataset import generate
from finflex.dataset.runner import opencl_devices

# The dataset.md benchmark's frame: 1,000 fish at 1280x720, COCO, varied optics.
CONFIG = {"tank": {"fish": 1000}, "camera": {"width": 1280, "height": 720},
          "annotation": {"depth": False}}


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--finflex", required=True)
    p.add_argument("--out", required=True, help="a scratch folder (emptied)")
    p.add_argument("--frames", type=int, default=400)
    p.add_argument("--shard-frames", type=int, default=100)
    p.add_argument("--fish", type=int, default=CONFIG["tank"]["fish"])
    p.add_argument("--size", default="1280x720")
    p.add_argument("--cpu-workers", default="1,2,4,8")
    args = p.parse_args()
    width, height = map(int, args.size.split("x"))
    config = {**CONFIG, "tank": {"fish": args.fish}, "camera": {"width": width, "height": height}}
    os.makedirs(args.out, exist_ok=True)
    devices = opencl_devices(args.finflex)
    gpus = sum(1 for _, kind in devices if kind == "GPU")
    has_cpu = any(kind == "CPU" for _, kind in devices)
    cores = len(os.sched_getaffinity(0))
    runs = []
    if gpus:
        runs += [("GPU alone, in process", dict(workers=1, cpu_workers=0, use_ray=False)),
                 ("GPU alone, Ray actor", dict(workers=1, cpu_workers=0, use_ray=True))]
    counts = [int(c) for c in args.cpu_workers.split(",")]
    if has_cpu:
        runs += [(f"CPU x{c}", dict(workers=c, cpu_workers=c, use_ray=True))
                 for c in counts if c + (1 if gpus else 0) <= cores]
        if gpus:
            c = max(c for c in counts if c + 1 <= cores)
            runs.append((f"GPU + CPU x{c}", dict(workers=1 + c, cpu_workers=c, use_ray=True)))
    print(f"# {args.frames} frames in shards of {args.shard_frames}, {args.fish} fish, "
          f"{args.size}, COCO; {cores} cores, {gpus} GPU(s), OpenCL CPU device: "
          f"{'yes' if has_cpu else 'no'}; {sys.version.split()[0]}")
    if not has_cpu:
        print("# no OpenCL CPU device here: the CPU rows are left out")
    print(f"{'workers':<24} {'frames/s':>9} {'of linear':>9} {'per worker':>11} "
          f"{'overhead/shard':>15} {'share':>6} {'start s':>8} {'merge s':>8}")
    one_cpu = None
    for name, options in runs:
        out = os.path.join(args.out, name.replace(" ", "_").replace(",", ""))
        shutil.rmtree(out, ignore_errors=True)
        s = generate(out, frames=args.frames, shard_frames=args.shard_frames, seed=1,
                     config=config, cli=args.finflex, quiet=True, **options)
        fps = s["frames_per_second"]
        if name == "CPU x1":
            one_cpu = fps
        workers = options["cpu_workers"]
        ratio = (f"{fps / (workers * one_cpu):.2f}" if one_cpu and name.startswith("CPU")
                 else "-")
        per = ", ".join(f"{w['frames_per_second']:.1f}" for w in s["per_worker"])
        print(f"{name:<24} {fps:>9.2f} {ratio:>9} {per:>11} "
              f"{1000 * s['overhead_per_shard_s']:>12.0f} ms {100 * s['overhead_share']:>5.1f}% "
              f"{s['start_seconds']:>8.1f} {s['merge_seconds']:>8.1f}", flush=True)
        shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    main()
