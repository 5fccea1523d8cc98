"""Device outputs as pyopencl objects, without a copy (needs pyopencl, on the same
OpenCL ICD loader: e.g. Debian's python3-pyopencl)."""

from typing import Any, NamedTuple, Optional


class PyOpenCLBatch(NamedTuple):
    """A batch's buffers on the context's own cl_context and queue. Each buffer holds
    element (instance i, component c, slot s) at (i * 3 + c) * batch.plane_stride + s:
    float32 positions; normals and tangents in batch.normal_format."""

    context: Any
    queue: Any
    positions: Any
    normals: Any
    tangents: Optional[Any]


def pyopencl_batch(context, batch) -> PyOpenCLBatch:
    """Wraps `context`'s cl_context and queue and `batch`'s buffers as pyopencl objects
    (each retains its OpenCL object: they stay valid after the finflex objects go).
    Work enqueued on the returned queue is ordered after the deformer's frames."""
    import pyopencl

    return PyOpenCLBatch(
        pyopencl.Context.from_int_ptr(context.cl_context),
        pyopencl.CommandQueue.from_int_ptr(context.cl_queue),
        pyopencl.Buffer.from_int_ptr(batch.cl_buffer("positions")),
        pyopencl.Buffer.from_int_ptr(batch.cl_buffer("normals")),
        pyopencl.Buffer.from_int_ptr(batch.cl_buffer("tangents")) if batch.has_tangents else None,
    )
