"""Errors arrive as finflex.Error with the library's message, code and field; arrays
with the wrong shape, dtype or strides are refused with a message that says so."""

import numpy as np
import pytest

import finflex
from conftest import spread_values


def raises(code, field, *fragments):
    """pytest.raises for finflex.Error, then checks its code, field and message."""

    class Check:
        def __enter__(self):
            self.context = pytest.raises(finflex.Error)
            self.info = self.context.__enter__()
            return self.info

        def __exit__(self, *exc):
            suppressed = self.context.__exit__(*exc)
            error = self.info.value
            assert error.code == code, str(error)
            assert error.field == field, str(error)
            for fragment in fragments:
                assert fragment in str(error), str(error)
            return suppressed

    return Check()


def test_library_errors(context, mesh, bend, rigged, tmp):
    assert issubclass(finflex.Error, Exception)
    with raises("io", "path", "nowhere.obj"):
        finflex.load_mesh(str(tmp / "nowhere.obj"))
    with raises("format", "path"):
        mesh.save(str(tmp / "mesh.xyz"))
    with raises("device", "device", "no-such-device"):
        finflex.Context("no-such-device")
    with raises("invalid_argument", "mode", "wobbly"):
        finflex.Model.single_bend(mesh, mode="wobbly")
    with raises("format", "rig"):
        finflex.parse_rig("{")
    with raises("invalid_argument", "tail", "'tail' is not a parameter of the rig"):
        rigged.parameter_index("tail")
    params = finflex.Parameters(rigged, 2)
    with raises("invalid_argument", "tail", "body_m, tail_angle"):
        params.set(0, "tail", 0.1)
    with raises("invalid_argument", "instance"):
        params.set(2, "tail_angle", 0.1)
    with raises("invalid_argument", "tail_angle", "takes 1 values, not 2"):
        params.set(0, "tail_angle", [0.1, 0.2])
    with raises("invalid_argument", "instances"):
        finflex.Parameters(rigged, 0)

    deformer = finflex.Deformer(context, bend)
    batch = deformer.allocate(3)
    with raises("invalid_argument", "instances"):
        deformer.allocate(0)
    with raises("invalid_argument", "normal_format", "quarter"):
        deformer.allocate(1, normal_format="quarter")
    with raises("out_of_range", "m[1]", "m[1] = 5", "out of range"):
        deformer.enqueue(np.array([[0.1], [5.0], [0.2]], np.float32), batch)
    with raises("invalid_argument", "m[2]", "NaN"):
        finflex.deform_reference(bend, np.array([[0.1], [0.0], [np.nan]], np.float32))
    with raises("invalid_argument", "normals", "sideways"):
        deformer.enqueue(np.zeros((3, 1), np.float32), batch, normals="sideways")
    with raises("invalid_argument", "path", "twisty"):
        deformer.enqueue(np.zeros((3, 1), np.float32), batch, path="twisty")
    with raises("invalid_argument", "job.outputs"):
        deformer.enqueue(np.zeros((4, 1), np.float32), batch)  # the batch holds 3
    other = finflex.Deformer(context, rigged).allocate(3)
    with raises("invalid_argument", "job.outputs"):
        deformer.enqueue(np.zeros((3, 1), np.float32), other)
    with raises("invalid_argument", "normals", "sideways"):
        deformer.job(batch, normals="sideways")
    job = deformer.job(batch)
    with raises("out_of_range", "m[0]"):
        job.enqueue(np.full((3, 1), 9.0, np.float32))
    with raises("invalid_argument", "parameters", "float64"):
        job.enqueue(np.zeros((3, 1)))
    with raises("invalid_argument", "attribute", "tangents"):
        batch.cl_buffer("tangents")
    with raises("invalid_argument", "instance"):
        deformer.read(batch).save(3, str(tmp / "x.obj"))
    assert not (tmp / "x.obj").exists()
    # Clamped instead of refused.
    out = finflex.deform_reference(bend, np.array([[5.0]], np.float32), clamp=True)
    assert np.isfinite(out.positions).all()


BAD_PARAMETERS = {
    "float64": (np.zeros((3, 1)), "got float64 array of shape (3, 1)", "astype(numpy.float32)"),
    "1-D": (np.zeros(3, np.float32), "got float32 array of shape (3,)", "1 values per instance"),
    "columns": (np.zeros((3, 2), np.float32), "shape (3, 2)", "shape (instances, 1)"),
    "3-D": (np.zeros((3, 1, 1), np.float32), "shape (3, 1, 1)", "shape (instances, 1)"),
    "list": ([[0.1], [0.2], [0.3]], "got list", "float32 array"),
    "negative stride": (np.zeros((3, 1), np.float32)[::-1], "byte strides (-4, 4)",
                        "rows must not overlap"),
    "broadcast rows": (np.broadcast_to(np.zeros((1, 1), np.float32), (3, 1)),
                       "byte strides (0, 0)", "rows must not overlap"),
}


@pytest.mark.parametrize("case", sorted(BAD_PARAMETERS))
def test_bad_parameter_arrays(context, bend, case):
    array, *fragments = BAD_PARAMETERS[case]
    deformer = finflex.Deformer(context, bend)
    batch = deformer.allocate(3)
    with raises("invalid_argument", "parameters", "parameters: expected", *fragments):
        deformer.enqueue(array, batch)
    with raises("invalid_argument", "parameters", *fragments):
        finflex.deform_reference(bend, array)


def test_bad_strides_of_rig_parameters(rigged):
    columns = np.asfortranarray(spread_values(rigged, 3))  # values of a row not adjacent
    with raises("invalid_argument", "parameters", "each row's values must be adjacent",
                "byte strides (4, 12)"):
        finflex.deform_reference(rigged, columns)
    misaligned = np.frombuffer(bytes(4 * 12 + 1), np.uint8)[1:].view(np.float32).reshape(3, 4)
    with raises("invalid_argument", "parameters", "not aligned"):
        finflex.deform_reference(rigged, misaligned)
    other = finflex.Parameters(finflex.Model.single_bend(rigged.mesh), 3)
    with raises("invalid_argument", "parameters", "1 values per instance, the model reads 4"):
        finflex.deform_reference(rigged, other)


def test_bad_mesh_arrays(mesh):
    positions = np.array(mesh.positions)
    with raises("invalid_argument", "positions", "float32 array of shape (n, 3)", "float64"):
        finflex.Mesh(positions.astype(np.float64), mesh.indices)
    with raises("invalid_argument", "indices", "uint32 array of shape (n, 3)", "int64"):
        finflex.Mesh(positions, mesh.indices.astype(np.int64))
    with raises("invalid_argument", "normals", "shape (945, 4)"):
        finflex.Mesh(positions, mesh.indices, np.zeros((945, 4), np.float32))
    positions[12, 1] = np.nan
    with raises("invalid_mesh", "positions[12].y", "is NaN"):
        finflex.Mesh(positions, mesh.indices)
    # Any strides are accepted here: the arrays are copied.
    strided = np.zeros((945, 6), np.float32)
    strided[:, ::2] = mesh.positions
    assert finflex.Mesh(strided[:, ::2], mesh.indices).vertex_count == 945
