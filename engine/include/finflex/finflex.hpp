// FinFlex: secant-surface deformation of static meshes in OpenCL, for thousands of
// instances per frame. One include for the whole public API.
//
// Layers, each header including only those above it:
//   error, export                     the error type; the shared-library export macro
//   mesh, mesh_io, subdivide          triangle meshes and their files
//   body_frame                        the local frame of a transform (METHOD.md 3)
//   deformer_type                     the deformer registry (bend, hinge, ...)
//   rig                               rig files and rigs resolved against a mesh
//   model                             a mesh with its rig: what a job deforms
//   parameters                        per-instance parameter values and their checks
//   job                               the job both backends run
//   batch                             deformed batches on the host; the planes layout
//   placement                         world placement of an instance
//   reference, accuracy, instance_mesh    the CPU reference and its diagnostics
//   swim                              swimming: kinematics and the CPU driver
//   context, device_batch, cl_deformer, cl_swim   the OpenCL backend (needs CL/opencl.hpp)
#pragma once

#include "finflex/accuracy.hpp"
#include "finflex/batch.hpp"
#include "finflex/body_frame.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/cl_swim.hpp"
#include "finflex/context.hpp"
#include "finflex/deformer_type.hpp"
#include "finflex/device_batch.hpp"
#include "finflex/error.hpp"
#include "finflex/file_kind.hpp"
#include "finflex/frame_gate.hpp"
#include "finflex/instance_mesh.hpp"
#include "finflex/job.hpp"
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
