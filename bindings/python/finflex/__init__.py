"""FinFlex: secant-surface deformation of static meshes (scanned fish) in OpenCL, for
thousands of instances per frame.

    import numpy as np, finflex
    mesh = finflex.load_mesh("data/blub/fish.obj")
    model = finflex.Model.single_bend(mesh)            # parameter "m"
    deformer = finflex.Deformer(finflex.Context(), model)
    batch = deformer.allocate(100)
    m = np.linspace(-0.8, 0.8, 100, dtype=np.float32).reshape(100, 1)
    deformer.enqueue(m, batch).wait()
    outputs = deformer.read(batch)                     # outputs.positions: (100, V, 3)
    outputs.save(7, "bent.obj")

Errors raise finflex.Error, with the library's message, its code ("out_of_range",
...) and the field at fault ("m[3]").
"""

from ._finflex import *  # noqa: F401,F403
from ._finflex import __version__  # noqa: F401
from ._pyopencl import PyOpenCLBatch, pyopencl_batch  # noqa: F401
