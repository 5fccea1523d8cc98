"""Output layouts from Python: FinFlex's planes as an OutputLayout, an interleaved vertex
in the mesh's order, previous positions, and the errors that name a layout's field."""

import numpy as np
import pytest

import finflex
from conftest import spread_values


def mesh_order_vertex(deformer, normal_format, stride, normal_stride=None):
    """A vertex struct in the mesh's order: a float32x3 position at 0, the normal at 12."""
    vertices = deformer.output_vertices("mesh")
    layout = finflex.OutputLayout()
    layout.order = "mesh"
    layout.positions = finflex.AttributeLayout.packed("float32x3", vertices, stride, 0)
    layout.normals = finflex.AttributeLayout.packed(normal_format, vertices,
                                                    normal_stride or stride, 12)
    return layout


def test_planes_layout_is_what_allocate_writes(context, rigged):
    deformer = finflex.Deformer(context, rigged)
    layout = deformer.layout(3)
    slots = deformer.output_vertices()
    assert layout.order == "slots" and slots == deformer.output_vertices("slots")
    assert layout.positions.format == "float32x3" and layout.positions.arrangement == "planes"
    assert layout.positions.plane_stride >= slots and layout.tangents is None
    assert layout.previous_positions is None
    assert deformer.layout(3, "half").normals.format == "float16x3"
    batch = deformer.allocate(3)
    assert batch.layout == layout and batch.plane_stride == layout.positions.plane_stride
    assert "finflex.OutputLayout(order=slots" in repr(layout)


def test_interleaved_mesh_order_matches_the_planes(context, rigged):
    deformer = finflex.Deformer(context, rigged)
    values = spread_values(rigged, 4, seed=7)
    planes = deformer.allocate(4)
    deformer.enqueue(values, planes).wait()
    want = deformer.read(planes)

    assert deformer.output_vertices("mesh") == rigged.vertex_count
    layout = mesh_order_vertex(deformer, "float32x3", 24)
    assert layout.positions.vertex_stride == 24 and layout.normals.offset == 12
    interleaved = deformer.allocate(4, layout)
    assert interleaved.layout == layout
    deformer.enqueue(values, interleaved).wait()
    got = deformer.read(interleaved)
    np.testing.assert_array_equal(got.positions, want.positions)
    np.testing.assert_array_equal(got.normals, want.normals)
    assert interleaved.cl_buffer("positions") != 0


def test_compact_normals_within_their_precision(context, rigged):
    deformer = finflex.Deformer(context, rigged)
    values = spread_values(rigged, 2, seed=3)
    reference = finflex.deform_reference(rigged, values)
    layout = mesh_order_vertex(deformer, "octahedral16x2", 16)
    batch = deformer.allocate(2, layout)
    deformer.enqueue(values, batch).wait()
    got = deformer.read(batch)
    assert np.abs(got.positions - reference.positions).max() < 1e-4
    # Two snorm16 of the octahedral map: a few 1e-5 of angle.
    assert np.abs(got.normals - reference.normals).max() < 1e-3


def test_previous_positions_hold_the_frame_before(context, rigged):
    deformer = finflex.Deformer(context, rigged)
    layout = deformer.layout(2)
    layout.previous_positions = layout.positions
    batch = deformer.allocate(2, layout)
    assert batch.cl_buffer("previous_positions") != 0
    first, second = spread_values(rigged, 2, seed=1), spread_values(rigged, 2, seed=2)
    deformer.enqueue(first, batch).wait()
    one = deformer.read(batch)
    deformer.enqueue(second, batch).wait()
    two = deformer.read(batch)
    np.testing.assert_array_equal(two.previous_positions, one.positions)


def test_layout_errors_name_the_field(context, rigged):
    deformer = finflex.Deformer(context, rigged)
    vertices = deformer.output_vertices("mesh")
    layout = mesh_order_vertex(deformer, "float32x3", 24, normal_stride=8)
    with pytest.raises(finflex.Error) as error:
        deformer.allocate(2, layout)
    assert error.value.field == "outputs.normals.vertex_stride"
    with pytest.raises(finflex.Error) as error:
        layout.order = "columns"
    assert error.value.field == "order"
    with pytest.raises(finflex.Error) as error:
        finflex.AttributeLayout.packed("float64x3", vertices)
    assert error.value.field == "format"
    layout.tangents = layout.normals  # the low-resolution Blub has no tangents
    layout.normals = finflex.AttributeLayout.packed("float32x3", vertices, 24, 12)
    with pytest.raises(finflex.Error) as error:
        deformer.allocate(2, layout)
    assert error.value.field == "outputs.tangents"
    with pytest.raises(finflex.Error) as error:
        deformer.allocate(2, deformer.layout(2)).cl_buffer("tangents")
    assert error.value.field == "attribute"


def test_rig_frame_deforms_two_models_in_one_frame(context, bend, rigged):
    blub_rig = finflex.Deformer(context, rigged)
    blub_bend = finflex.Deformer(context, bend)
    frame = finflex.RigFrame()
    first = frame.add(blub_rig, 3)
    second = frame.add(blub_bend, 2, "half")
    assert (first, second, len(frame)) == (0, 1, 2)
    rig_values, bend_values = spread_values(rigged, 3, seed=4), spread_values(bend, 2, seed=5)
    frame.values(first)[:] = rig_values
    frame.values(second)[:] = bend_values
    events = frame.enqueue(normals="jacobian")
    assert len(events) == 2
    for event in events:
        event.wait()
    alone = blub_rig.allocate(3)
    blub_rig.enqueue(rig_values, alone, normals="jacobian").wait()
    np.testing.assert_array_equal(blub_rig.read(frame.batch(first)).positions,
                                  blub_rig.read(alone).positions)
    assert frame.batch(second).normal_format == "half"
    reference = finflex.deform_reference(bend, bend_values, normals="jacobian")
    assert np.abs(blub_bend.read(frame.batch(second)).positions - reference.positions).max() < 1e-4
    frame.values(first)[0, 0] = 1e6  # outside body_m's limit: nothing is enqueued
    with pytest.raises(finflex.Error):
        frame.enqueue()
    with pytest.raises(finflex.Error) as error:
        frame.batch(2)
    assert error.value.field == "entry"
