"""The run's progress on stderr: frames and shards done, frames per second per worker
and overall, and the time left. On a terminal one line redrawn twice a second; else a
line per finished shard."""

from __future__ import annotations

import sys
import time


def _duration(seconds: float) -> str:
    seconds = int(round(seconds))
    if seconds >= 3600:
        return f"{seconds // 3600} h {seconds % 3600 // 60:02d} min"
    if seconds >= 60:
        return f"{seconds // 60} min {seconds % 60:02d} s"
    return f"{seconds} s"


class Progress:
    def __init__(self, store, total_frames: int, total_shards: int, skipped_frames: int,
                 skipped_shards: int, stream=None, quiet: bool = False):
        self.store = store
        self.total_frames = total_frames
        self.total_shards = total_shards
        self.done_frames = skipped_frames
        self.done_shards = skipped_shards
        self.skipped_frames = skipped_frames
        self.stream = stream or sys.stderr
        self.quiet = quiet
        self.tty = self.stream.isatty()
        self.start = time.perf_counter()
        self.workers: dict[str, dict] = {}  # per worker: frames and busy seconds
        self.running_frames = 0
        self.retries = 0
        self.last_draw = 0.0

    @staticmethod
    def _name(info: dict) -> str:
        return f"{info.get('kind', '?')} {info.get('device', '?')} pid {info.get('pid', '?')}"

    def started(self, shard, info: dict) -> None:
        self.workers.setdefault(self._name(info), {"frames": 0, "seconds": 0.0})

    def finished(self, shard, result: dict) -> None:
        worker = self.workers.setdefault(self._name(result), {"frames": 0, "seconds": 0.0})
        worker["frames"] += result["frames"]
        worker["seconds"] += result["seconds"]
        self.done_frames += result["frames"]
        self.done_shards += 1
        if not self.tty:
            self._write(self.line() + "\n")

    def retrying(self, shard, reason: str) -> None:
        self.retries += 1
        self._write(("\n" if self.tty else "") + f"finflex.dataset: {shard.name} again: {reason}\n")

    def poll(self, running) -> None:
        now = time.perf_counter()
        if not self.tty or now - self.last_draw < 0.5:
            return
        self.last_draw = now
        self.running_frames = sum(self.store.running_frames(s) for s in running)
        self._write("\r" + self.line() + "\033[K")

    def frames_per_second(self) -> float:
        made = self.done_frames - self.skipped_frames + self.running_frames
        elapsed = time.perf_counter() - self.start
        return made / elapsed if elapsed > 0 and made > 0 else 0.0

    def line(self) -> str:
        frames = min(self.total_frames, self.done_frames + self.running_frames)
        share = frames / self.total_frames if self.total_frames else 1.0
        width = 24
        bar = "#" * int(share * width) + "." * (width - int(share * width))
        rate = self.frames_per_second()
        left = (self.total_frames - frames) / rate if rate > 0 else None
        per_worker = ", ".join(f"{w['frames'] / w['seconds']:.1f}" for w in self.workers.values()
                               if w["seconds"] > 0)
        text = (f"[{bar}] frames {frames}/{self.total_frames}  shards "
                f"{self.done_shards}/{self.total_shards}  {rate:.1f} frames/s")
        if per_worker:
            text += f" (per worker {per_worker})"
        if left is not None:
            text += f"  {_duration(left)} left"
        return text

    def _write(self, text: str) -> None:
        if not self.quiet:
            self.stream.write(text)
            self.stream.flush()

    def close(self) -> None:
        if self.tty:
            self._write("\r" + self.line() + "\033[K\n")
