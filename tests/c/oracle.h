/* The C++ library's answers for the C API test (oracle.cpp): the same inputs through
 * finflex::run_reference. C99. */
#ifndef FINFLEX_TEST_ORACLE_H
#define FINFLEX_TEST_ORACLE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Deforms the mesh at `mesh_path` (with the rig file `rig_path`, or the single exact
 * bend with the automatic frame when it is NULL) for `instances` rows of `values`
 * (packed) and writes positions and normals as (instances, vertices, 3) float32.
 * Returns 0 on success, 1 with the message on stderr otherwise. */
int oracle_reference(const char* mesh_path, const char* rig_path, size_t instances,
                     const float* values, int jacobian_normals, float* positions, float* normals);

/* `frames` frames of 1/30 s of the C++ swim driver (one fish per length, the same
 * 7-float inputs per fish every frame) and the placed deformation of the swim rig
 * `rig_path` on the default device: positions and normals as (fish, vertices, 3)
 * float32, mesh order. Returns 0 on success, 1 with the message on stderr otherwise. */
int oracle_swim(const char* mesh_path, const char* rig_path, size_t fish, const float* lengths,
                const float* inputs, size_t frames, float* positions, float* normals);

#ifdef __cplusplus
}
#endif

#endif
