"""Device outputs handed to pyopencl without a copy (skipped without pyopencl)."""

import numpy as np
import pytest

import finflex
from conftest import MESH

cl = pytest.importorskip("pyopencl")


def test_batch_buffers_are_the_deformers():
    context = finflex.Context()
    model = finflex.Model.single_bend(finflex.load_mesh(str(MESH)))
    deformer = finflex.Deformer(context, model)
    batch = deformer.allocate(3)
    deformer.enqueue(np.array([[0.1], [-0.2], [0.3]], np.float32), batch).wait()
    view = finflex.pyopencl_batch(context, batch)
    assert view.tangents is None
    assert view.context.int_ptr == context.cl_context
    assert view.positions.int_ptr == batch.cl_buffer("positions")
    assert view.positions.size == 4 * 3 * 3 * batch.plane_stride
    planes = np.empty(3 * 3 * batch.plane_stride, np.float32)
    cl.enqueue_copy(view.queue, planes, view.positions).wait()
    positions = planes.reshape(3, 3, batch.plane_stride)[:, :, : batch.vertex_count]
    np.testing.assert_array_equal(positions.transpose(0, 2, 1), deformer.read(batch).positions)
