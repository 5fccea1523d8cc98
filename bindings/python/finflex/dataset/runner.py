"""One worker: an OpenCL device (a GPU, or the CPU through PoCL with a share of the
cores) and the shards it writes, each by one `finflex swim` process."""

from __future__ import annotations

import ctypes
import dataclasses
import os
import pathlib
import shutil
import signal
import subprocess
import time

from .errors import ShardFailed
from .plan import Shard, swim_arguments
from .store import Store


@dataclasses.dataclass(frozen=True)
class Job:
    """What every shard of a run shares."""
    cli: str
    out: str
    config: dict
    formats: tuple
    config_hash: str
    version: str


@dataclasses.dataclass(frozen=True)
class DeviceChoice:
    kind: str  # "gpu" or "cpu"
    ordinal: int = 0  # which device of that kind (GPU index; for the CPU always 0)
    threads: int = 0  # CPU workers: the cores they may use (0: all)
    cores: tuple = ()  # CPU workers: the cores they run on (empty: any)


def _die_with_parent() -> None:
    # The swim ends when its worker does (a killed worker leaves no writer behind).
    libc = ctypes.CDLL("libc.so.6", use_errno=True)
    libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG


def opencl_devices(cli: str) -> list[tuple[str, str]]:
    """The node's OpenCL devices as ('P:D', 'GPU' or 'CPU'), from `finflex info`."""
    result = subprocess.run([cli, "info"], capture_output=True, text=True, timeout=120)
    devices = []
    for line in result.stdout.splitlines():
        fields = line.split()
        if len(fields) > 1 and ":" in fields[0] and fields[0].replace(":", "").isdigit():
            kind = "GPU" if "[GPU]" in line else "CPU" if "[CPU]" in line else "other"
            devices.append((fields[0], kind))
    return devices


def resolve_device(cli: str, choice: DeviceChoice) -> str:
    """The `--device` of a worker's swims: the chosen GPU, or the CPU device."""
    wanted = "GPU" if choice.kind == "gpu" else "CPU"
    matching = [index for index, kind in opencl_devices(cli) if kind == wanted]
    # A GPU worker that Ray gave one GPU sees only that one (CUDA_VISIBLE_DEVICES).
    ordinal = 0 if os.environ.get("CUDA_VISIBLE_DEVICES") else choice.ordinal
    if ordinal >= len(matching):
        raise ShardFailed(-1, f"this node has {len(matching)} OpenCL {wanted} device(s): "
                              f"no {choice.kind} {choice.ordinal}")
    return matching[ordinal]


def worker_environment(choice: DeviceChoice) -> dict[str, str]:
    env = dict(os.environ)
    if choice.kind == "cpu" and choice.threads > 0:
        threads = str(choice.threads)
        # PoCL's CPU device (both names of its thread count), llvmpipe's rasteriser.
        env.update(POCL_MAX_PTHREAD_COUNT=threads, POCL_CPU_MAX_CU_COUNT=threads,
                   LP_NUM_THREADS=threads)
    return env


class Worker:
    """Writes shards on one device. Used in-process (--workers 1 without Ray) and as
    the body of each Ray actor."""

    def __init__(self, job: Job, choice: DeviceChoice):
        self.job = job
        self.choice = choice
        self.store = Store(pathlib.Path(job.out))
        self.device = resolve_device(job.cli, choice)
        self.env = worker_environment(choice)

    def describe(self) -> dict:
        return {"kind": self.choice.kind, "device": self.device, "threads": self.choice.threads,
                "pid": os.getpid(), "host": os.uname().nodename}

    def _start(self) -> None:
        _die_with_parent()
        if self.choice.cores:
            os.sched_setaffinity(0, self.choice.cores)

    def run(self, shard: Shard) -> dict:
        """Writes `shard` into place; its record and times. ShardFailed when the swim
        fails (its staging files removed)."""
        start = time.perf_counter()
        attempt = self.store.attempt_folder(shard)
        args = [self.job.cli] + swim_arguments(self.job.config, shard, self.job.formats,
                                               str(attempt), self.device)
        process_start = time.perf_counter()
        result = subprocess.run(args, env=self.env, capture_output=True, text=True,
                                preexec_fn=self._start)
        process_seconds = time.perf_counter() - process_start
        if result.returncode != 0:
            shutil.rmtree(attempt, ignore_errors=True)
            for partial in self.store.staging.glob(f".{attempt.name}.partial-*"):
                shutil.rmtree(partial, ignore_errors=True)
            if result.returncode < 0:
                reason = f"the swim was killed by signal {-result.returncode}"
            else:
                lines = result.stderr.strip().splitlines() or ["(no message)"]
                reason = f"the swim exited with status {result.returncode}: {lines[-1]}"
            raise ShardFailed(shard.index, reason)
        committed = self.store.commit(shard, attempt, {
            "config_hash": self.job.config_hash, "formats": self.job.formats,
            "version": self.job.version})
        return {"index": shard.index, "frames": shard.frames, "committed": committed,
                "seconds": time.perf_counter() - start, "process_seconds": process_seconds,
                **self.describe()}
