"""Swimming fish from Python: SwimModel, SwimDriver, Deformer.swim_job. The placed
outputs equal the C++ library's for the same frames (tests/python/oracle.cpp swim),
and bad inputs are refused with the field named."""

import os
import subprocess

import numpy as np
import pytest

import finflex
from conftest import DATA, MESH

SWIM_RIG = DATA / "rigs" / "blub_low_resolution_swim.rig.json"
LENGTHS = np.array([0.3, 0.45, 0.25], np.float32)
DT = 1.0 / 30.0


@pytest.fixture(scope="module")
def swim(mesh):
    return finflex.SwimModel(finflex.Model(mesh, finflex.load_rig(str(SWIM_RIG))))


def inputs():
    """Per fish x, y, z, yaw, pitch, speed, turning rate."""
    rows = np.zeros((len(LENGTHS), 7), np.float32)
    rows[:, 0] = [0.0, 1.0, -1.0]
    rows[:, 1] = [0.5, 0.6, 0.7]
    rows[:, 3] = [0.0, 1.2, -2.0]
    rows[:, 4] = [0.0, 0.1, -0.05]
    rows[:, 5] = LENGTHS * np.array([1.0, 0.6, 2.0], np.float32)
    rows[:, 6] = [0.0, 0.4, -0.3]
    return rows


def run_frames(context, swim, frames):
    deformer = finflex.Deformer(context, swim.model)
    batch = deformer.allocate(len(LENGTHS))
    driver = finflex.SwimDriver(context, swim, LENGTHS)
    job = deformer.swim_job(batch, driver)
    for _ in range(frames):
        driver.enqueue(inputs(), DT)
        job.enqueue().wait()
    return deformer, batch, driver


def test_placed_outputs_equal_the_cpp_library(context, swim, tmp):
    deformer, batch, _ = run_frames(context, swim, 5)
    out = deformer.read(batch)
    LENGTHS.tofile(tmp / "lengths.bin")
    inputs().tofile(tmp / "inputs.bin")
    subprocess.run([os.environ["FINFLEX_PYTHON_ORACLE"], "swim", str(MESH), str(SWIM_RIG), "5",
                    str(tmp / "lengths.bin"), str(tmp / "inputs.bin"), str(tmp / "swim")],
                   check=True)
    cpp = np.fromfile(str(tmp / "swim.device"), np.float32).reshape(2, len(LENGTHS), -1, 3)
    np.testing.assert_array_equal(out.positions, cpp[0])
    np.testing.assert_array_equal(out.normals, cpp[1])


def test_fish_are_placed_where_the_inputs_say(context, swim):
    deformer, batch, driver = run_frames(context, swim, 3)
    out = deformer.read(batch)
    rows = inputs()
    for i, length in enumerate(LENGTHS):
        centre = out.positions[i].mean(axis=0)
        assert np.linalg.norm(centre - rows[i, :3]) < length  # the pivot lies on the body
        extent = out.positions[i].max(axis=0) - out.positions[i].min(axis=0)
        assert 0.8 * length < extent.max() < 1.2 * length  # scaled to the fish's length
        np.testing.assert_allclose(np.linalg.norm(out.normals[i], axis=1), 1.0, atol=1e-4)
    placements = driver.read_placements()
    assert placements.shape == (len(LENGTHS), 16)
    np.testing.assert_allclose(placements[:, 9:12], rows[:, :3])
    np.testing.assert_allclose(placements[:, 12], 1.0 / LENGTHS, rtol=1e-6)
    phases = driver.read_wave_phases()
    assert phases.shape == (len(LENGTHS),) and np.all((phases >= 0) & (phases < 1))
    values = driver.read_parameters()
    assert values.shape == (len(LENGTHS), swim.model.values_per_instance)
    assert np.all(np.isfinite(values)) and np.any(values != 0)
    assert driver.fish_count == len(LENGTHS)
    assert driver.limited_segments() >= 0


def test_a_frame_behind_a_gate_runs_when_it_opens(context, swim):
    deformer, batch, _ = run_frames(context, swim, 3)
    expected = deformer.read(batch).positions
    gated_deformer = finflex.Deformer(context, swim.model)
    gated_batch = gated_deformer.allocate(len(LENGTHS))
    driver = finflex.SwimDriver(context, swim, LENGTHS)
    job = gated_deformer.swim_job(gated_batch, driver)
    for frame in range(3):
        gate = finflex.FrameGate(context)
        driven = driver.enqueue(inputs(), DT, wait=[gate.event])
        done = job.enqueue()
        assert not driven.complete and not gate.is_open
        if frame == 2:
            with gate:  # opened on leaving
                pass
        else:
            gate.open()
        assert gate.is_open
        done.wait()
    np.testing.assert_array_equal(gated_deformer.read(gated_batch).positions, expected)


def test_inputs_in_any_memory_order_drive_alike(context, swim):
    # C-ordered rows are read in place, others copied first: the frames are the same.
    in_place = finflex.SwimDriver(context, swim, LENGTHS)
    copied = finflex.SwimDriver(context, swim, LENGTHS)
    for frame in range(4):
        rows = inputs()
        rows[:, 3] += 0.1 * frame
        wide = np.zeros((len(LENGTHS), 9), np.float32)
        wide[:, 1:8] = rows
        other_order = np.asfortranarray(rows) if frame % 2 else wide[:, 1:8]
        assert not other_order.flags.c_contiguous
        in_place.enqueue(rows, DT).wait()
        copied.enqueue(other_order, DT).wait()
        np.testing.assert_array_equal(in_place.read_parameters(), copied.read_parameters())
        placed = (in_place.read_placements(), copied.read_placements())
        np.testing.assert_array_equal(placed[0][:, :13], placed[1][:, :13])  # 3 unused
    with pytest.raises(finflex.Error) as e:
        in_place.enqueue(inputs()[:2], DT)  # C-ordered, one fish short
    assert e.value.field == "inputs"


def test_bad_inputs_name_their_field(context, swim, mesh):
    driver = finflex.SwimDriver(context, swim, LENGTHS)
    with pytest.raises(finflex.Error) as e:
        driver.enqueue(inputs()[:, :6], DT)
    assert e.value.field == "inputs"
    negative = inputs()
    negative[1, 5] = -1.0
    with pytest.raises(finflex.Error) as e:
        driver.enqueue(negative, DT)
    assert e.value.field == "inputs[1].speed"
    with pytest.raises(finflex.Error) as e:
        driver.enqueue(inputs(), 0.0)
    assert e.value.field == "dt"
    with pytest.raises(finflex.Error) as e:
        finflex.SwimDriver(context, swim, np.array([0.3, -0.2], np.float32))
    assert e.value.field == "lengths[1]"
    # A deformer of another model than the swim model's own.
    other = finflex.Deformer(context, finflex.Model(mesh, finflex.load_rig(str(SWIM_RIG))))
    with pytest.raises(finflex.Error) as e:
        other.swim_job(other.allocate(len(LENGTHS)), driver)
    assert e.value.field == "driver"
    # A rig without a spine on its body.
    with pytest.raises(finflex.Error) as e:
        finflex.SwimModel(finflex.Model.single_bend(mesh))
    assert e.value.field == "swim.wave"
