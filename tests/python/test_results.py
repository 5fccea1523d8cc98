"""Results equal the C++ library's for the same inputs (tests/python/oracle.cpp)."""

import numpy as np
import pytest

import finflex
from conftest import RIG, oracle, spread_values


@pytest.mark.parametrize("normals", ["rotate", "jacobian"])
@pytest.mark.parametrize("rigged_model", [False, True])
def test_device_and_reference_equal_cpp(context, bend, rigged, tmp, normals, rigged_model):
    model = rigged if rigged_model else bend
    values = spread_values(model, 6)
    deformer = finflex.Deformer(context, model)
    batch = deformer.allocate(6)
    deformer.enqueue(values, batch, normals=normals).wait()
    device = deformer.read(batch)
    reference = finflex.deform_reference(model, values, normals=normals)

    cpp = oracle(tmp, str(RIG) if rigged_model else "-", values, normals)
    # The same device and kernels, the same double-precision reference: equal bits.
    np.testing.assert_array_equal(device.positions, cpp[0])
    np.testing.assert_array_equal(device.normals, cpp[1])
    np.testing.assert_array_equal(reference.positions, cpp[2])
    np.testing.assert_array_equal(reference.normals, cpp[3])
    assert device.positions.dtype == np.float32 and reference.positions.dtype == np.float64
    assert device.positions.shape == (6, model.vertex_count, 3)
    # And the backends agree within the accuracy bounds (docs/accuracy.md).
    assert np.abs(device.positions - reference.positions).max() < 1e-4


def test_parameters_object_slices_and_arrays_agree(context, rigged):
    values = spread_values(rigged, 5, seed=3)
    params = finflex.Parameters(rigged, 5)
    params.values[:] = values
    wide = np.zeros((5, 9), np.float32)
    wide[:, 2:6] = values  # rows 36 bytes apart: a view, not a copy
    a = finflex.deform_reference(rigged, values)
    b = finflex.deform_reference(rigged, params)
    c = finflex.deform_reference(rigged, wide[:, 2:6])
    np.testing.assert_array_equal(a.positions, b.positions)
    np.testing.assert_array_equal(a.positions, c.positions)


def test_half_normals_close(context, bend):
    values = spread_values(bend, 3)
    deformer = finflex.Deformer(context, bend)
    full, half = deformer.allocate(3), deformer.allocate(3, normal_format="half")
    assert half.normal_format == "half"
    deformer.enqueue(values, full)
    deformer.enqueue(values, half).wait()
    a, b = deformer.read(full), deformer.read(half)
    np.testing.assert_array_equal(a.positions, b.positions)
    assert np.abs(a.normals - b.normals).max() < 2e-3


def test_outputs_are_views(context, bend):
    values = spread_values(bend, 4)
    deformer = finflex.Deformer(context, bend)
    batch = deformer.allocate(4)
    deformer.enqueue(values, batch).wait()
    out = deformer.read(batch)
    positions = out.positions
    assert not positions.flags.owndata  # a view of the read-back planes
    assert positions.strides[1] == 4 and positions.strides[2] == 4 * batch.plane_stride
    del out  # the array keeps its memory alive
    assert np.isfinite(positions).all()
