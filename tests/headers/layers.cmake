# The layers of FinFlex's public headers (engine/include/finflex/), bottom-up: a header
# includes only headers of its own layer and of the layers before it. This is the one
# table of them; finflex.hpp's comment and docs/architecture.md's Layers section follow
# it. tests/headers/CMakeLists.txt compiles each header alone with only those layers on
# the include path (target finflex_header_layers, part of the tests' build), and the
# test Headers.LayerTableListsEveryHeader fails on a header of the folder that is not
# listed here, or listed here but not in the folder.
#
# Paths are relative to engine/include/finflex/. A new header goes into the lowest layer
# that holds everything it includes.

set(FINFLEX_HEADER_LAYERS
  core         # errors, regular-file checks, the export macro
  meshes       # triangle meshes, their files, subdivision
  frames       # the body frame of a transform
  deformers    # the deformer registry
  rigs         # rig files and rigs resolved against a mesh
  models       # a mesh with its rig
  lod          # levels of detail of a rigged mesh
  parameters   # per-instance parameter values and their checks
  placement    # world placement of an instance
  outputs      # output layouts; deformed batches on the host
  jobs         # the job both backends run
  reference    # the CPU reference and its diagnostics
  swim         # swimming: kinematics and the CPU driver
  opencl       # the OpenCL backend
  all          # the one include of the public API
  internal     # not installed: what only the benchmarks and tests use
)

set(FINFLEX_LAYER_core error.hpp export.hpp file_kind.hpp)
set(FINFLEX_LAYER_meshes mesh.hpp mesh_io.hpp subdivide.hpp)
set(FINFLEX_LAYER_frames body_frame.hpp)
set(FINFLEX_LAYER_deformers deformer_type.hpp)
set(FINFLEX_LAYER_rigs rig.hpp)
set(FINFLEX_LAYER_models model.hpp)
set(FINFLEX_LAYER_lod detail_levels.hpp)
set(FINFLEX_LAYER_parameters parameters.hpp)
set(FINFLEX_LAYER_placement placement.hpp wall_occlusion.hpp)
set(FINFLEX_LAYER_outputs output_layout.hpp batch.hpp)
set(FINFLEX_LAYER_jobs job.hpp)
set(FINFLEX_LAYER_reference reference.hpp accuracy.hpp instance_mesh.hpp)
set(FINFLEX_LAYER_swim swim.hpp)
set(FINFLEX_LAYER_opencl
  context.hpp frame_gate.hpp device_batch.hpp cl_deformer.hpp cl_swim.hpp level_choice.hpp
  level_deformer.hpp)
set(FINFLEX_LAYER_all finflex.hpp)
set(FINFLEX_LAYER_internal internal/cl_tuning.hpp internal/cl_outputs.hpp)

# The first layer whose headers may include OpenCL's (CL/...): every layer before it
# compiles without them.
set(FINFLEX_HEADER_OPENCL_LAYER opencl)
# Headers the build writes (engine/CMakeLists.txt: generate_export_header), not in the
# source folder.
set(FINFLEX_GENERATED_HEADERS export.hpp)
# The folder of headers that are not installed (engine/CMakeLists.txt) and that the
# umbrella header finflex.hpp leaves out.
set(FINFLEX_INTERNAL_HEADER_DIR internal)
