// The extension module finflex._finflex: the package finflex re-exports it.
#include "bindings.hpp"

NB_MODULE(_finflex, m) {
  using namespace finflex::python;
  m.doc() =
      "FinFlex: secant-surface deformation of static meshes in OpenCL, for thousands of "
      "instances per frame (the package finflex re-exports this module).";
  m.attr("__version__") = FINFLEX_VERSION;
  bind_errors(m);
  bind_mesh(m);
  bind_model(m);
  bind_layout(m);
  bind_outputs(m);
  bind_device(m);
  bind_job(m);
  bind_frame(m);
  bind_swim(m);
}
