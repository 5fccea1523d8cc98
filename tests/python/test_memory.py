"""No growth in resident memory over 10,000 iterations of the frame calls (parameters
in, event out: enqueue with an array, with Parameters, a Job; a refused call), with
reads and reference runs among them."""

import gc
import os

import numpy as np

import finflex
from conftest import spread_values


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def frame_calls(deformer, job, batch, values, params):
    deformer.enqueue(values, batch).wait()
    params.values[:] = values
    deformer.enqueue(params, batch, normals="jacobian").wait()
    job.enqueue(values).wait()
    try:
        deformer.enqueue(values * 100, batch)
    except finflex.Error:
        pass


def test_resident_memory_is_flat_over_10000_calls(context, rigged):
    deformer = finflex.Deformer(context, rigged)
    batch = deformer.allocate(8)
    values = spread_values(rigged, 8)
    params = finflex.Parameters(rigged, 8)
    job = deformer.job(batch)
    for _ in range(500):  # warm-up: programs, staging buffers, allocator pools
        frame_calls(deformer, job, batch, values, params)
    deformer.read(batch)
    finflex.deform_reference(rigged, values[:1])
    gc.collect()
    before = resident_bytes()
    for k in range(10_000):
        frame_calls(deformer, job, batch, values, params)
        if k % 100 == 0:
            out = deformer.read(batch)
            assert out.positions.shape == (8, 945, 3)
            finflex.deform_reference(rigged, values[:1])
    del out
    gc.collect()
    growth = resident_bytes() - before
    print(f"resident memory growth over 10,000 iterations: {growth / 1e6:.2f} MB")
    assert growth < 4e6, f"resident memory grew by {growth / 1e6:.1f} MB"
