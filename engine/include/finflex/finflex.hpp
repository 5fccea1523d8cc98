// FinFlex: secant-surface deformation of static meshes in OpenCL, for thousands of
// instances per frame. One include for the whole public API.
#pragma once

#include "finflex/accuracy.hpp"
#include "finflex/batch.hpp"
#include "finflex/bend.hpp"
#include "finflex/body_frame.hpp"
#include "finflex/cl_context.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/error.hpp"
#include "finflex/instance_mesh.hpp"
#include "finflex/local_mesh.hpp"
#include "finflex/mesh.hpp"
#include "finflex/mesh_io.hpp"
#include "finflex/reference_deformer.hpp"
#include "finflex/rig.hpp"
#include "finflex/rig_deformer.hpp"
#include "finflex/subdivide.hpp"
