"""The Python API: devices, contexts, meshes, rigs, models, parameters, deformers,
batches, events and files."""

import numpy as np

import finflex
from conftest import MESH, RIG, spread_values


def test_devices_and_context(context):
    devices = finflex.list_devices()
    assert devices and sum(d.is_default for d in devices) == 1
    assert context.device.device_name == next(d for d in devices if d.is_default).device_name
    assert context.device.type in ("GPU", "CPU", "accelerator", "other")
    assert context.cl_context != 0 and context.cl_queue != 0
    context.finish()
    assert "finflex.Device" in repr(devices[0])


def test_mesh_load_arrays_and_save(mesh, tmp):
    assert mesh.vertex_count == 945 and mesh.triangle_count > 0
    assert mesh.positions.shape == (945, 3) and mesh.positions.dtype == np.float32
    assert mesh.normals.shape == (945, 3) and mesh.indices.dtype == np.uint32
    assert not mesh.positions.flags.writeable and mesh.tangents is None
    copy = finflex.Mesh(mesh.positions, mesh.indices, mesh.normals)
    np.testing.assert_array_equal(copy.positions, mesh.positions)
    computed = finflex.Mesh(mesh.positions, mesh.indices)  # normals from the faces
    assert np.abs(np.linalg.norm(computed.normals, axis=1) - 1).max() < 1e-5
    path = tmp / "copy.ply"
    copy.save(str(path))
    again = finflex.load_mesh(str(path))
    np.testing.assert_array_equal(again.positions, mesh.positions)
    finflex.save_mesh(str(tmp / "copy.obj"), mesh)
    assert finflex.load_mesh(str(tmp / "copy.obj")).vertex_count == 945
    assert repr(mesh) == f"finflex.Mesh(945 vertices, {mesh.triangle_count} triangles)"


def test_body_frame(mesh):
    frame = finflex.find_body_frame(mesh)
    assert frame.length > 0 and abs(np.linalg.norm(frame.axis_x) - 1) < 1e-9
    frame.validate()
    flipped = finflex.find_body_frame(mesh, head_direction=tuple(-np.array(frame.axis_x)))
    assert np.allclose(flipped.axis_x, -np.array(frame.axis_x))
    identity = finflex.BodyFrame.identity()
    assert identity.axis_y == (0.0, 1.0, 0.0) and identity.length == 1.0
    identity.origin = (1.0, 2.0, 3.0)
    assert identity.origin == (1.0, 2.0, 3.0)
    model = finflex.Model.single_bend(mesh, frame=frame, mode="paper")
    assert model.is_single_bend


def test_rig_model_and_parameters(mesh, rigged):
    rig = finflex.load_rig(str(RIG))
    assert rig.component_names[0] == "body"
    assert finflex.parse_rig(RIG.read_text()).component_names == rig.component_names
    assert rigged.vertex_count == 945 and rigged.values_per_instance == 4
    assert rigged.parameter_names == ["body_m", "tail_angle", "right_pectoral_angle",
                                      "left_pectoral_angle"]
    assert rigged.parameter_index("tail_angle") == 1
    assert [p.offset for p in rigged.parameters] == [0, 1, 2, 3]
    assert "tail_angle" in repr(rigged.parameters[1])
    assert rigged.mesh.vertex_count == 945 and not rigged.is_single_bend
    params = finflex.Parameters(rigged, 3)
    assert params.instance_count == 3 and params.values.shape == (3, 4)
    params.set(1, "tail_angle", 0.25)
    params.set(2, "body_m", [0.5])
    assert params.get(1, "tail_angle") == 0.25 and params.values[2, 0] == 0.5
    params.values[0, 3] = -0.125  # a writable view
    assert params.get(0, "left_pectoral_angle") == -0.125


def test_deformer_frames_events_and_files(context, bend, rigged, tmp):
    deformer = finflex.Deformer(context, rigged)
    assert not deformer.uses_single_bend_kernel
    batch = deformer.allocate(4)
    assert (batch.instance_count, batch.vertex_count) == (4, 945)
    assert batch.plane_stride >= 945 and batch.normal_format == "float32"
    assert not batch.has_tangents
    assert batch.cl_buffer("positions") != 0 and batch.cl_buffer("normals") != 0
    values = spread_values(rigged, 4)
    first = deformer.enqueue(values, batch, normals="jacobian", path="passes")
    second = deformer.enqueue(values, batch, normals="jacobian", path="fused", wait=[first])
    second.wait()
    assert first.complete and second.complete
    out = deformer.read(batch)
    # A job described once gives the same frames.
    job = deformer.job(batch, normals="jacobian", path="fused")
    assert job.batch is batch
    assert first.enqueue_seconds > 0
    job.enqueue(np.zeros_like(values)).wait()
    assert not np.array_equal(deformer.read(batch).positions, out.positions)
    job.enqueue(values, wait=[second]).wait()
    np.testing.assert_array_equal(deformer.read(batch).positions, out.positions)
    assert out.instance_count == 4 and out.vertex_count == 945 and out.tangents is None
    slots = deformer.slot_of_vertex
    assert len(slots) == 945 and len(set(slots)) == 945
    assert len(deformer.remapped_indices) == 3 * rigged.mesh.triangle_count

    # Saving an instance, from the device and from host outputs.
    deformer.save_instance(batch, 2, str(tmp / "device.obj"))
    saved = finflex.load_mesh(str(tmp / "device.obj"))
    assert np.abs(saved.positions - out.positions[2]).max() < 1e-5
    out.save(2, str(tmp / "host.ply"))
    np.testing.assert_array_equal(finflex.load_mesh(str(tmp / "host.ply")).positions,
                                  out.positions[2])
    instance = out.instance_mesh(3)
    np.testing.assert_array_equal(instance.positions, out.positions[3])
    np.testing.assert_array_equal(instance.normals, out.normals[3])
    np.testing.assert_array_equal(instance.indices, rigged.mesh.indices)

    reference = finflex.deform_reference(rigged, values, normals="jacobian", clamp=True)
    assert np.abs(reference.positions - out.positions).max() < 1e-4


def test_readme_example_shape(context):
    mesh = finflex.load_mesh(str(MESH.parent / "fish.obj"))
    model = finflex.Model.single_bend(mesh)
    deformer = finflex.Deformer(context, model)
    batch = deformer.allocate(100)
    m = np.linspace(-0.8, 0.8, 100, dtype=np.float32).reshape(100, 1)
    deformer.enqueue(m, batch).wait()
    assert deformer.read(batch).positions.shape == (100, 10786, 3)
