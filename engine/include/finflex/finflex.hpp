// FinFlex: secant-surface deformation of static meshes in OpenCL, for thousands of
// instances per frame. One include for the whole public API.
//
// Layers, lowest first: a header includes only headers of its own layer and of the layers
// listed before it, and every layer before opencl compiles without OpenCL's headers.
// The table is tests/headers/layers.cmake; the tests' build compiles each header alone
// with only its layer and those before it (target finflex_header_layers), and the test
// Headers.LayerTableListsEveryHeader fails on a header the table does not list.
//   core        error, export, file_kind      the error type; the shared-library export
//                                             macro; what kind of file a stat() mode names
//   meshes      mesh, mesh_io, subdivide      triangle meshes, their files, subdivision
//   frames      body_frame                    the local frame of a transform (METHOD.md 3)
//   deformers   deformer_type                 the deformer registry (bend, hinge, ...)
//   rigs        rig                           rig files and rigs resolved against a mesh
//   models      model                         a mesh with its rig: what a job deforms
//   lod         detail_levels                 levels of detail of a rigged mesh
//   parameters  parameters                    per-instance parameter values and their checks
//   placement   placement, wall_occlusion     placement of an instance; walls that hide it
//   outputs     output_layout, batch          where outputs are written; batches on the host
//   jobs        job                           the job both backends run
//   reference   reference, accuracy, instance_mesh
//                                             the CPU reference and its diagnostics
//   swim        swim                          swimming: kinematics and the CPU driver
//   opencl      context, frame_gate, device_batch, cl_deformer, cl_swim, level_choice,
//               level_deformer                the OpenCL backend (needs CL/opencl.hpp), the
//                                             level choice and a species at its levels
//   all         finflex                       this header: every header listed before it
//   internal    internal/*                    not installed, not included here: what only
//                                             the benchmarks and tests use
#pragma once

#include "finflex/accuracy.hpp"
#include "finflex/batch.hpp"
#include "finflex/body_frame.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/cl_swim.hpp"
#include "finflex/context.hpp"
#include "finflex/deformer_type.hpp"
#include "finflex/detail_levels.hpp"
#include "finflex/device_batch.hpp"
#include "finflex/error.hpp"
#include "finflex/file_kind.hpp"
#include "finflex/frame_gate.hpp"
#include "finflex/instance_mesh.hpp"
#include "finflex/job.hpp"
#include "finflex/level_choice.hpp"
#include "finflex/level_deformer.hpp"
#include "finflex/mesh.hpp"
#include "finflex/mesh_io.hpp"
#include "finflex/model.hpp"
#include "finflex/output_layout.hpp"
#include "finflex/parameters.hpp"
#include "finflex/placement.hpp"
#include "finflex/reference.hpp"
#include "finflex/rig.hpp"
#include "finflex/subdivide.hpp"
#include "finflex/swim.hpp"
#include "finflex/wall_occlusion.hpp"
