"""Where the workers run: in this process (one worker, no Ray), or as Ray actors (one
per GPU, CPU actors on PoCL with their share of the cores), on this machine or a
cluster; and the loop that hands them shards, retries failed ones and reports
progress."""

from __future__ import annotations

import collections
import concurrent.futures
import logging
import os
import socket
import sys
import time
from typing import Any

from .errors import DatasetError, ShardFailed
from .runner import DeviceChoice, Job, Worker

# Attempts at one shard before the run fails (a killed or crashed worker's shard is
# retried on a fresh worker).
MAX_ATTEMPTS = 3


def ray_module():
    """Ray, its local clusters with token authentication (Ray reads the mode when it is
    first imported)."""
    if "ray" not in sys.modules:
        os.environ.setdefault("RAY_AUTH_MODE", "token")
    try:
        import ray
    except ImportError:
        raise DatasetError("--workers", "--workers: more than one worker needs Ray, which is not "
                           "installed: pip install 'finflex[dataset]' (or run with --workers 1)")
    return ray


def check_reachable(address: str) -> None:
    """A TCP connection to ADDRESS (host:port or ray://host:port) within 3 s, so that
    an unreachable cluster is an error now rather than a long wait in ray.init."""
    if address == "auto":
        return
    hostport = address.split("://", 1)[-1]
    host, _, port = hostport.rpartition(":")
    if not host or not port.isdigit():
        raise DatasetError("--address", f"--address '{address}' is not HOST:PORT or ray://HOST:PORT")
    try:
        socket.create_connection((host.strip("[]"), int(port)), timeout=3).close()
    except OSError as error:
        raise DatasetError("--address", f"--address {address}: cannot be reached ({error})")


class LocalPool:
    """One worker in this process (its swims are child processes)."""

    def __init__(self, job: Job, choices: list[DeviceChoice]):
        self.job = job
        self.executor = concurrent.futures.ThreadPoolExecutor(1)
        self.workers = [Worker(job, choices[0])]

    def describe(self, worker) -> dict:
        return worker.describe()

    def submit(self, worker, shard):
        return self.executor.submit(worker.run, shard)

    def wait(self, handles, timeout):
        done, _ = concurrent.futures.wait(handles, timeout=timeout,
                                          return_when=concurrent.futures.FIRST_COMPLETED)
        return list(done)

    def result(self, handle):
        return handle.result()

    def replace(self, worker):
        return worker

    def close(self):
        self.executor.shutdown(wait=True)


class ActorBody:
    """A Ray actor: a Worker that stays on its device for the run."""

    def __init__(self, job: Job, choice: DeviceChoice):
        self.worker = Worker(job, choice)

    def describe(self) -> dict:
        return self.worker.describe()

    def run(self, shard) -> dict:
        return self.worker.run(shard)


class _Actor:
    """A Ray actor with what it was made for and what it reported."""

    def __init__(self, handle, choice: DeviceChoice, info: dict):
        self.handle, self.choice, self.info = handle, choice, info


class WorkerDied(RuntimeError):
    pass


class RayPool:
    """Ray actors. Local by default: a private cluster of this machine listening on
    127.0.0.1 only, with the dashboard (and with it the job-submission endpoint) off."""

    def __init__(self, job: Job, address: str | None, workers: int, cpu_workers: int | None,
                 cpu_threads: int | None = None):
        ray = ray_module()
        self.ray = ray
        self.job = job
        os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")
        cores = sorted(os.sched_getaffinity(0))
        if address is None:
            gpus = sum(1 for _, kind in _devices(job.cli) if kind == "GPU")
            ray.init(num_cpus=len(cores), num_gpus=gpus, include_dashboard=False,
                     _node_ip_address="127.0.0.1", log_to_driver=False,
                     logging_level=logging.ERROR)
        else:
            ray.init(address=address, log_to_driver=False, logging_level=logging.ERROR)
            gpus = int(ray.cluster_resources().get("GPU", 0))
            cores = list(range(int(ray.cluster_resources().get("CPU", 1))))
        try:
            choices = choose_devices(workers, cpu_workers, gpus, cores, local=address is None,
                                     cpu_threads=cpu_threads)
            self.actor = ray.remote(ActorBody)
            self.workers = [self._make(choice) for choice in choices]
        except BaseException:
            ray.shutdown()
            raise

    def _make(self, choice: DeviceChoice) -> _Actor:
        if choice.kind == "gpu":
            resources = {"num_gpus": 1, "num_cpus": 1}
        else:
            resources = {"num_cpus": max(1, choice.threads)}
        handle = self.actor.options(max_restarts=0, **resources).remote(self.job, choice)
        try:
            info = self.ray.get(handle.describe.remote(), timeout=300)
        except self.ray.exceptions.RayActorError as error:
            raise ShardFailed(-1, f"a {choice.kind} worker could not start: {_cause(error)}")
        return _Actor(handle, choice, info)

    def describe(self, worker: _Actor) -> dict:
        return worker.info

    def submit(self, worker: _Actor, shard):
        return worker.handle.run.remote(shard)

    def wait(self, handles, timeout):
        done, _ = self.ray.wait(handles, num_returns=1, timeout=timeout)
        return done

    def result(self, handle):
        try:
            return self.ray.get(handle)
        except self.ray.exceptions.RayTaskError as error:
            if isinstance(error.cause, ShardFailed):
                raise error.cause
            raise ShardFailed(-1, str(error.cause))
        except self.ray.exceptions.RayActorError as error:
            raise WorkerDied(f"its worker died ({_cause(error)})")

    def replace(self, worker: _Actor) -> _Actor:
        self.ray.kill(worker.handle, no_restart=True)
        return self._make(worker.choice)

    def close(self):
        self.ray.shutdown()


def _cause(error) -> str:
    lines = [line for line in str(error).splitlines() if line.strip()]
    return lines[-1] if lines else type(error).__name__


def _devices(cli):
    from .runner import opencl_devices
    return opencl_devices(cli)


def choose_devices(workers: int, cpu_workers: int | None, gpus: int, cores: list[int],
                   local: bool, cpu_threads: int | None = None) -> list[DeviceChoice]:
    """The workers' devices: GPU workers first (one per GPU), then CPU workers, each
    with `cpu_threads` cores (default an equal share of the cores left; locally, pinned
    to them)."""
    if cpu_workers is None:
        cpu_workers = max(0, workers - gpus)
    if cpu_workers > workers:
        raise DatasetError("--cpu-workers",
                           f"--cpu-workers {cpu_workers} is more than --workers {workers}")
    gpu_workers = workers - cpu_workers
    if gpu_workers > gpus:
        raise DatasetError("--workers", f"--workers {workers} with --cpu-workers {cpu_workers} "
                           f"asks for {gpu_workers} GPU workers, but there are {gpus} GPUs")
    choices = [DeviceChoice("gpu", ordinal=g) for g in range(gpu_workers)]
    free = cores[gpu_workers:] if len(cores) > gpu_workers else cores
    if cpu_workers:
        share = cpu_threads or max(1, len(free) // cpu_workers)
        if len(free) < cpu_workers * share:
            raise DatasetError("--cpu-workers", f"--cpu-workers {cpu_workers} of {share} cores "
                               f"each: only {len(free)} cores are left for CPU workers")
        for c in range(cpu_workers):
            mine = tuple(free[c * share:(c + 1) * share]) if local else ()
            choices.append(DeviceChoice("cpu", threads=share, cores=mine))
    return choices


def run_shards(pool, shards, progress) -> list[dict]:
    """Runs every shard on the pool's workers; their results in shard order.
    ShardFailed when a shard failed MAX_ATTEMPTS times."""
    pending = collections.deque(shards)
    attempts: dict[int, int] = collections.Counter()
    running: dict[Any, tuple] = {}
    idle = list(pool.workers)
    results = {}
    while pending or running:
        while idle and pending:
            worker, shard = idle.pop(0), pending.popleft()
            attempts[shard.index] += 1
            running[pool.submit(worker, shard)] = (worker, shard, time.perf_counter())
            progress.started(shard, pool.describe(worker))
        for handle in pool.wait(list(running), timeout=0.5):
            worker, shard, submitted = running.pop(handle)
            try:
                result = pool.result(handle)
            except (ShardFailed, WorkerDied) as error:
                if attempts[shard.index] >= MAX_ATTEMPTS:
                    raise ShardFailed(shard.index, f"failed {attempts[shard.index]} times, "
                                                   f"last: {error}")
                progress.retrying(shard, str(error))
                pending.appendleft(shard)
                if isinstance(error, WorkerDied):
                    worker = pool.replace(worker)
            else:
                result["attempts"] = attempts[shard.index]
                result["task_seconds"] = time.perf_counter() - submitted
                results[shard.index] = result
                progress.finished(shard, result)
            idle.append(worker)
        progress.poll([shard for _, shard, _ in running.values()])
    return [results[s.index] for s in shards]
