"""Shared set-up of the Python tests: paths from the environment CTest gives, one
context, and the low-resolution Blub (945 vertices) with its rig."""

import os
import pathlib
import subprocess

import numpy as np
import pytest

import finflex

DATA = pathlib.Path(os.environ.get("FINFLEX_DATA_DIR", pathlib.Path(__file__).parents[2] / "data"))
MESH = DATA / "blub" / "fish_low_resolution.obj"
RIG = DATA / "rigs" / "blub_low_resolution.rig.json"


@pytest.fixture(scope="session")
def context():
    return finflex.Context()


@pytest.fixture(scope="session")
def mesh():
    return finflex.load_mesh(str(MESH))


@pytest.fixture(scope="session")
def bend(mesh):
    return finflex.Model.single_bend(mesh)


@pytest.fixture(scope="session")
def rigged(mesh):
    return finflex.Model(mesh, finflex.load_rig(str(RIG)))


@pytest.fixture
def tmp(tmp_path):
    return tmp_path


def spread_values(model, instances, seed=1):
    """Parameter rows within each parameter's limit (up to 0.95 of it, or 1)."""
    rng = np.random.default_rng(seed)
    values = np.zeros((instances, model.values_per_instance), np.float32)
    for p in model.parameters:
        bound = 0.95 * min(p.limit, 1.0)
        values[:, p.offset : p.offset + p.count] = rng.uniform(-bound, bound, (instances, p.count))
    return values


def oracle(tmp_path, model_rig, values, normals):
    """The C++ library's device and reference outputs for the same job:
    (device positions, device normals, reference positions, reference normals)."""
    values = np.ascontiguousarray(values, np.float32)
    values_file = tmp_path / "values.bin"
    values.tofile(values_file)
    out = tmp_path / "oracle"
    subprocess.run(
        [os.environ["FINFLEX_PYTHON_ORACLE"], str(MESH), model_rig, normals,
         str(values.shape[0]), str(values_file), str(out)],
        check=True)
    instances = values.shape[0]
    device = np.fromfile(str(out) + ".device", np.float32).reshape(2, instances, -1, 3)
    reference = np.fromfile(str(out) + ".reference", np.float64).reshape(2, instances, -1, 3)
    return device[0], device[1], reference[0], reference[1]
