"""Host time of SwimDriver.enqueue from Python by the inputs' memory order: C-ordered
rows (read in place into the upload's staging memory) against rows the binding must
copy first (Fortran order, and rows of 8 floats with 7 taken). The three alternate
call by call in one process; each frame is waited for outside the timed call.

    PYTHONPATH=build/bindings/python python3 bench/python_swim_inputs.py \
        [--fish 10000] [--frames 400] [--device NAME]

Prints one JSON object: per order, the median microseconds of a call.
"""

import argparse
import json
import pathlib
import statistics
import time

import numpy as np

import finflex

ROOT = pathlib.Path(__file__).resolve().parents[1]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--fish", type=int, default=10000)
    parser.add_argument("--frames", type=int, default=400)
    parser.add_argument("--device", default="")
    args = parser.parse_args()
    mesh = finflex.load_mesh(str(ROOT / "data" / "blub" / "fish.obj"))
    rig = finflex.load_rig(str(ROOT / "data" / "rigs" / "blub_swim.rig.json"))
    swim = finflex.SwimModel(finflex.Model(mesh, rig))
    driver = finflex.SwimDriver(finflex.Context(args.device), swim,
                                np.full(args.fish, 0.3, np.float32))
    rows = np.zeros((args.fish, 7), np.float32)
    rows[:, 5] = 0.3  # speed, m/s
    wide = np.zeros((args.fish, 8), np.float32)
    wide[:, :7] = rows
    orders = {"C order, in place": rows, "Fortran order, copied": np.asfortranarray(rows),
              "rows of 8 floats, 7 taken, copied": wide[:, :7]}
    times = {name: [] for name in orders}
    warm_up = 20
    for frame in range(warm_up + args.frames):
        for name, inputs in orders.items():
            start = time.perf_counter()
            done = driver.enqueue(inputs, 1.0 / 30.0)
            seconds = time.perf_counter() - start
            done.wait()
            if frame >= warm_up:
                times[name].append(seconds)
    print(json.dumps({"fish": args.fish, "frames": args.frames,
                      "median_us": {name: round(statistics.median(t) * 1e6, 1)
                                    for name, t in times.items()}}))


if __name__ == "__main__":
    main()
