"""python -m finflex.dataset --out DIR --frames N --shard-frames M --seed S
[--workers W] [--cpu-workers C] [--cpu-threads T] [--address ADDR] [--formats coco,yolo,webdataset]
[--config FILE] [--finflex PATH]

Exit status 0 when the dataset is complete, 2 for bad input (one line naming the option
or field; nothing written), 1 when a shard failed every attempt (the complete shards
stay; a rerun completes the rest)."""

from __future__ import annotations

import argparse
import sys

from . import DatasetError, ShardFailed, generate


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, exit status 2, as for every bad input
        sys.stderr.write(f"finflex.dataset: {message}\n")
        raise SystemExit(2)


def _count(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a whole number")


def parser() -> argparse.ArgumentParser:
    p = _Parser(prog="python -m finflex.dataset",
                description="An annotated dataset of the virtual RAS tank, in shards written "
                            "by workers that each hold one OpenCL device (Ray actors).")
    p.add_argument("--out", required=True, help="the dataset's folder (made, or completed)")
    p.add_argument("--frames", required=True, type=_count, help="frames in the dataset")
    p.add_argument("--shard-frames", required=True, type=_count, help="frames per shard")
    p.add_argument("--seed", type=_count, default=0, help="the dataset's seed (default 0)")
    p.add_argument("--workers", type=_count,
                   help="workers (default: one per GPU, else one on the CPU); more than one "
                        "runs on Ray")
    p.add_argument("--cpu-workers", type=_count,
                   help="how many of the workers use the CPU through PoCL (default: the "
                        "workers beyond one per GPU)")
    p.add_argument("--cpu-threads", type=_count,
                   help="cores of each CPU worker (default: an equal share of those left)")
    p.add_argument("--address", help="a Ray cluster's HOST:PORT (default: a private local one)")
    p.add_argument("--ray", action="store_true", help="Ray even for one local worker")
    p.add_argument("--formats", default="coco", help="coco (always), yolo, webdataset")
    p.add_argument("--config", help="the tank, species, camera, optics and swim (JSON or "
                                    "TOML; docs/dataset-at-scale.md)")
    p.add_argument("--finflex", help="the finflex program (default: $FINFLEX_CLI, then PATH)")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr")
    return p


def main(argv=None) -> int:
    args = parser().parse_args(argv)
    try:
        summary = generate(args.out, frames=args.frames, shard_frames=args.shard_frames,
                           seed=args.seed, workers=args.workers, address=args.address,
                           formats=args.formats, config=args.config,
                           cpu_workers=args.cpu_workers, cpu_threads=args.cpu_threads,
                           cli=args.finflex,
                           use_ray=True if args.ray else None, quiet=args.quiet)
    except DatasetError as error:
        sys.stderr.write(f"finflex.dataset: {error}\n")
        return 2
    except ShardFailed as error:
        sys.stderr.write(f"finflex.dataset: {error} (the complete shards stay; run again to "
                         "finish)\n")
        return 1
    print(f"wrote {summary['out']}: {summary['images']} images, {summary['annotations']} "
          f"annotations in {summary['shards']} shards ({summary['shards_written']} written, "
          f"{summary['shards_skipped']} already complete, {summary['retries']} retried)")
    print(f"  {summary['frames_written']} frames in {summary['shards_seconds']:.1f} s: "
          f"{summary['frames_per_second']:.2f} frames/s (and {summary['start_seconds']:.1f} s "
          f"starting the workers, {summary['merge_seconds']:.1f} s merging; "
          f"{summary['seconds']:.1f} s in all)")
    for w in summary["per_worker"]:
        print(f"  {w['kind']} worker on {w['device']}: {w['shards']} shards, "
              f"{w['frames_per_second']:.2f} frames/s")
    if summary["shards_written"]:
        print(f"  overhead per shard {summary['overhead_per_shard_s'] * 1000:.0f} ms "
              f"({100 * summary['overhead_share']:.1f} % of the shards' time)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
