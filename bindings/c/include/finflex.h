/* FinFlex C API: the secant-surface deformation of static meshes (the finflex/ C++ headers) behind
 * opaque handles, for C and for the languages that call C (C#, Rust, Julia, Go).
 * C99. No C++ exception crosses this boundary: every failing call returns a status
 * and records the error (code, message, field) on its handle and on the calling thread.
 *
 *   finflex_mesh* mesh;     finflex_mesh_load("data/blub/fish.obj", &mesh);
 *   finflex_model* model;   finflex_model_create_single_bend(mesh, NULL, FINFLEX_BEND_EXACT,
 * &model); finflex_context* ctx;   finflex_context_create(NULL, &ctx); finflex_deformer* def;
 * finflex_deformer_create(ctx, model, &def); finflex_batch* batch;   finflex_deformer_allocate(def,
 * 100, FINFLEX_FORMAT_FLOAT32, &batch); finflex_parameters* p;  finflex_parameters_create(model,
 * 100, &p); finflex_parameters_set(p, 7, "m", 0.5f); finflex_job job; finflex_job_init(&job);
 *   finflex_parameters_view(p, &job);
 *   finflex_event* done;    finflex_deformer_enqueue(def, &job, batch, NULL, 0, &done);
 *   finflex_event_wait(done);
 *   ... finflex_deformer_read(def, batch, &outputs), or hand
 *       finflex_batch_cl_buffer(batch, FINFLEX_POSITIONS) to OpenCL ...
 *
 * Conventions:
 *  - Functions return finflex_status (FINFLEX_OK is 0); outputs come back through
 *    pointer arguments, written only on success. Simple getters return their value
 *    (0 for a NULL handle).
 *  - Handles are created by finflex_*_create / _load / _parse / _allocate and freed by
 *    the matching finflex_*_destroy (NULL is accepted and ignored). A handle keeps
 *    what it was made from alive (a deformer its context and model, a model a copy of
 *    its mesh), so handles may be destroyed in any order.
 *  - Errors: finflex_last_error() is the calling thread's last failure (any function,
 *    including a create that returned no handle). finflex_<handle>_error() is the
 *    result of the last call that took that handle as its first argument: no error
 *    (FINFLEX_OK, "" and "") after a success. The message names the field and its
 *    value, as the C++ library's finflex::Error does ("m[3] = 2.5 is outside ...",
 *    field "m[3]"). Strings stay valid until the next call on that handle (or thread).
 *  - Threads: a handle is used by one thread at a time; different deformers of one
 *    context may be used from different threads (then read finflex_last_error()).
 *  - Sizes are size_t counts; strides are bytes; host outputs are float32.
 */
#ifndef FINFLEX_H
#define FINFLEX_H

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32) && !defined(FINFLEX_C_STATIC)
#if defined(FINFLEX_C_BUILDING)
#define FINFLEX_C_API __declspec(dllexport)
#else
#define FINFLEX_C_API __declspec(dllimport)
#endif
#elif defined(__GNUC__)
#define FINFLEX_C_API __attribute__((visibility("default")))
#else
#define FINFLEX_C_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ status, errors */

typedef enum finflex_status {
  FINFLEX_OK = 0,
  FINFLEX_ERROR_INVALID_ARGUMENT = 1,  /* a value outside its domain, a NULL handle, a size */
  FINFLEX_ERROR_OUT_OF_RANGE = 2,      /* a deformation parameter outside its valid range */
  FINFLEX_ERROR_INVALID_MESH = 3,      /* empty, inconsistent or non-finite mesh data */
  FINFLEX_ERROR_IO = 4,                /* a file could not be read or written */
  FINFLEX_ERROR_FORMAT = 5,            /* a file's content is not a supported mesh or rig */
  FINFLEX_ERROR_DEVICE = 6,            /* no OpenCL device, or the named one does not exist */
  FINFLEX_ERROR_OPENCL = 7,            /* an OpenCL call failed */
  FINFLEX_ERROR_OUT_OF_MEMORY = 8,     /* a host allocation failed */
  FINFLEX_ERROR_INTERNAL = 9,          /* anything else (a bug: please report it) */
  FINFLEX_STATUS_MAX_ENUM = 0x7fffffff /* every int is a value (named "unknown"), not a status */
} finflex_status;

/* A short stable name: "ok", "invalid_argument", "out_of_range", ... (the C++
 * error_code_name for the library's codes); "unknown" for other values. */
FINFLEX_C_API const char* finflex_status_name(finflex_status status);
/* The library's version, "MAJOR.MINOR.PATCH". */
FINFLEX_C_API const char* finflex_version(void);

typedef struct finflex_error finflex_error;
/* The calling thread's last failure; never NULL (no error: FINFLEX_OK). */
FINFLEX_C_API const finflex_error* finflex_last_error(void);
/* Readers of an error record; a NULL record reads as no error. */
FINFLEX_C_API finflex_status finflex_error_status(const finflex_error* error);
FINFLEX_C_API const char* finflex_error_message(const finflex_error* error);
FINFLEX_C_API const char* finflex_error_field(const finflex_error* error);

/* ----------------------------------------------------------------------- devices */

typedef struct finflex_device_info {
  size_t platform_index; /* "P:D" selects platform P, device D in finflex_context_create */
  size_t device_index;
  char platform_name[128]; /* truncated to fit, always NUL-terminated */
  char device_name[128];
  char type[16]; /* "GPU", "CPU", "accelerator" or "other" */
  char version[128];
  uint64_t global_memory_bytes;
  uint64_t max_allocation_bytes;
  int is_default; /* the device an empty name selects: the first GPU, else the first CPU */
} finflex_device_info;

/* Every OpenCL device of every platform: writes min(capacity, n) descriptions to
 * `devices` (may be NULL when capacity is 0) and n to *count. n is 0 when no OpenCL
 * platform exists (not an error). */
FINFLEX_C_API finflex_status finflex_list_devices(finflex_device_info* devices, size_t capacity,
                                                  size_t* count);

/* ----------------------------------------------------------------------- context */

typedef struct finflex_context finflex_context;
/* `device`: NULL or "" for the default device, "P:D", or a case-insensitive part of
 * the device's or platform's name ("pocl", "H100"). FINFLEX_ERROR_DEVICE naming it
 * when nothing matches. */
FINFLEX_C_API finflex_status finflex_context_create(const char* device, finflex_context** context);
/* Waits for the work enqueued on the context (opening its frame gates still closed
 * first), then frees it. */
FINFLEX_C_API void finflex_context_destroy(finflex_context* context);
FINFLEX_C_API const finflex_error* finflex_context_error(const finflex_context* context);
FINFLEX_C_API finflex_status finflex_context_device(finflex_context* context,
                                                    finflex_device_info* info);
/* Blocks until every command enqueued on the context's queue is done. */
FINFLEX_C_API finflex_status finflex_context_finish(finflex_context* context);
/* The OpenCL objects (cl_context, cl_command_queue) as void*, owned by the context:
 * for interoperation (e.g. pyopencl), not to be released. NULL for a NULL handle. */
FINFLEX_C_API void* finflex_context_cl_context(const finflex_context* context);
FINFLEX_C_API void* finflex_context_cl_queue(const finflex_context* context);

/* -------------------------------------------------------------------------- mesh */

typedef struct finflex_mesh finflex_mesh;
/* Formats follow the extension: .obj .ply .off .stl .gltf .glb (finflex/mesh_io.hpp).
 * FINFLEX_ERROR_IO / _FORMAT / _INVALID_MESH with the path in the message. */
FINFLEX_C_API finflex_status finflex_mesh_load(const char* path, finflex_mesh** mesh);
/* A mesh from arrays: vertex_count xyz positions, index_count triangle corners
 * (a multiple of 3), and xyz unit normals or NULL (then area-weighted ones are
 * computed). Validated: FINFLEX_ERROR_INVALID_MESH naming e.g. "positions[12].y". */
FINFLEX_C_API finflex_status finflex_mesh_create(const float* positions, size_t vertex_count,
                                                 const uint32_t* indices, size_t index_count,
                                                 const float* normals, finflex_mesh** mesh);
FINFLEX_C_API void finflex_mesh_destroy(finflex_mesh* mesh);
FINFLEX_C_API const finflex_error* finflex_mesh_error(const finflex_mesh* mesh);
/* Writes the mesh; on error `path` is neither created nor changed. */
FINFLEX_C_API finflex_status finflex_mesh_save(finflex_mesh* mesh, const char* path);
FINFLEX_C_API size_t finflex_mesh_vertex_count(const finflex_mesh* mesh);
FINFLEX_C_API size_t finflex_mesh_triangle_count(const finflex_mesh* mesh);
/* Copies the vertex positions / unit normals (3 floats a vertex) or the indices (3 a
 * triangle); `count` must be exactly that many values (FINFLEX_ERROR_INVALID_ARGUMENT
 * naming "count" otherwise). */
FINFLEX_C_API finflex_status finflex_mesh_get_positions(finflex_mesh* mesh, float* positions,
                                                        size_t count);
FINFLEX_C_API finflex_status finflex_mesh_get_normals(finflex_mesh* mesh, float* normals,
                                                      size_t count);
FINFLEX_C_API finflex_status finflex_mesh_get_indices(finflex_mesh* mesh, uint32_t* indices,
                                                      size_t count);

/* The local frame of a transform (finflex/body_frame.hpp): spine e_x towards the
 * head, dorsal e_y, lateral e_z, the pivot `origin`, the body's extent `length`. */
typedef struct finflex_body_frame {
  double origin[3];
  double axis_x[3];
  double axis_y[3];
  double axis_z[3];
  double length;
} finflex_body_frame;
/* The frame found from the mesh (principal axes, head, dorsal side, pivot, length). */
FINFLEX_C_API finflex_status finflex_mesh_find_body_frame(finflex_mesh* mesh,
                                                          finflex_body_frame* frame);
/* The identity frame: the mesh coordinates already are the body frame. */
FINFLEX_C_API void finflex_body_frame_identity(finflex_body_frame* frame);

/* --------------------------------------------------------------------------- rig */

typedef struct finflex_rig finflex_rig; /* a rig file, not yet resolved against a mesh */
/* A rig file (JSON, docs/rigs.md): FINFLEX_ERROR_IO, _FORMAT (malformed JSON, line and
 * column), _INVALID_ARGUMENT naming the place ("components[1] 'tail'.select.box.min"). */
FINFLEX_C_API finflex_status finflex_rig_load(const char* path, finflex_rig** rig);
FINFLEX_C_API finflex_status finflex_rig_parse(const char* json, finflex_rig** rig);
FINFLEX_C_API void finflex_rig_destroy(finflex_rig* rig);
FINFLEX_C_API const finflex_error* finflex_rig_error(const finflex_rig* rig);

/* ------------------------------------------------------------------------- model */

typedef enum finflex_bend_mode {
  FINFLEX_BEND_PAPER = 0,                 /* the paper's 4th-order series (15)-(17) */
  FINFLEX_BEND_EXACT = 1,                 /* the closed form: the spine keeps its length exactly */
  FINFLEX_BEND_MODE_MAX_ENUM = 0x7fffffff /* every int is a value (checked), not a mode */
} finflex_bend_mode;

typedef struct finflex_model finflex_model; /* a mesh with its rig (finflex::RiggedMesh) */
/* The paper's whole-body bend: one component, one bend stage reading parameter "m".
 * `frame`: NULL for the frame found from the mesh. */
FINFLEX_C_API finflex_status finflex_model_create_single_bend(const finflex_mesh* mesh,
                                                              const finflex_body_frame* frame,
                                                              finflex_bend_mode mode,
                                                              finflex_model** model);
/* A rig resolved against a mesh (components, frames, stages; errors name the place). */
FINFLEX_C_API finflex_status finflex_model_create(const finflex_mesh* mesh, const finflex_rig* rig,
                                                  finflex_model** model);
FINFLEX_C_API void finflex_model_destroy(finflex_model* model);
FINFLEX_C_API const finflex_error* finflex_model_error(const finflex_model* model);
FINFLEX_C_API size_t finflex_model_vertex_count(const finflex_model* model);
/* Floats one instance's parameter row holds. */
FINFLEX_C_API size_t finflex_model_values_per_instance(const finflex_model* model);
FINFLEX_C_API size_t finflex_model_parameter_count(const finflex_model* model);

typedef struct finflex_parameter_info {
  const char* name; /* owned by the model */
  size_t offset;    /* of its first value in an instance's row */
  size_t count;     /* values (1 for a bend's m or a hinge's angle) */
  double limit;     /* the largest |value| accepted */
} finflex_parameter_info;
FINFLEX_C_API finflex_status finflex_model_parameter(finflex_model* model, size_t index,
                                                     finflex_parameter_info* info);
/* The index of a parameter by name: FINFLEX_ERROR_INVALID_ARGUMENT naming an unknown
 * one (the message lists the rig's). */
FINFLEX_C_API finflex_status finflex_model_find_parameter(finflex_model* model, const char* name,
                                                          size_t* index);

/* -------------------------------------------------------------------- parameters */

typedef struct finflex_job finflex_job;
typedef struct finflex_parameters finflex_parameters; /* instances x values, zeros at first */
FINFLEX_C_API finflex_status finflex_parameters_create(const finflex_model* model,
                                                       size_t instance_count,
                                                       finflex_parameters** parameters);
FINFLEX_C_API void finflex_parameters_destroy(finflex_parameters* parameters);
FINFLEX_C_API const finflex_error* finflex_parameters_error(const finflex_parameters* parameters);
FINFLEX_C_API size_t finflex_parameters_instance_count(const finflex_parameters* parameters);
/* Sets a one-value parameter by name (values are checked against their limits when a
 * job uses them). FINFLEX_ERROR_INVALID_ARGUMENT naming an unknown name or an
 * instance out of range. */
FINFLEX_C_API finflex_status finflex_parameters_set(finflex_parameters* parameters, size_t instance,
                                                    const char* name, float value);
/* Sets every value of a parameter (count must be the parameter's count). */
FINFLEX_C_API finflex_status finflex_parameters_set_values(finflex_parameters* parameters,
                                                           size_t instance, const char* name,
                                                           const float* values, size_t count);
/* The first value of a parameter by name. */
FINFLEX_C_API finflex_status finflex_parameters_get(finflex_parameters* parameters, size_t instance,
                                                    const char* name, float* value);
/* The values, row-major (instance_count rows of values_per_instance floats), for
 * filling a frame directly; valid while the handle lives. NULL for a NULL handle. */
FINFLEX_C_API float* finflex_parameters_data(finflex_parameters* parameters);
/* Points job->parameters, ->instance_count and ->parameter_stride at the values. */
FINFLEX_C_API finflex_status finflex_parameters_view(finflex_parameters* parameters,
                                                     finflex_job* job);

/* --------------------------------------------------------------------------- job */

typedef enum finflex_normal_mode {
  FINFLEX_NORMALS_ROTATE = 0,   /* the paper's (8) */
  FINFLEX_NORMALS_JACOBIAN = 1, /* exact, through the deformation's Jacobian */
  FINFLEX_NORMAL_MODE_MAX_ENUM = 0x7fffffff
} finflex_normal_mode;

typedef enum finflex_rig_path {
  FINFLEX_PATH_AUTO = 0,   /* fused where it applies */
  FINFLEX_PATH_FUSED = 1,  /* one pass, each vertex's whole path in registers */
  FINFLEX_PATH_PASSES = 2, /* one pass per hierarchy level and chain position */
  FINFLEX_RIG_PATH_MAX_ENUM = 0x7fffffff
} finflex_rig_path;

/* One frame's deformation (finflex/job.hpp, BasicDeformJob): the parameter rows of
 * instance_count instances, row i at parameters + i * parameter_stride (0: the
 * model's values_per_instance). The values are read during the call only. */
struct finflex_job {
  const float* parameters;
  size_t instance_count;
  size_t parameter_stride; /* floats */
  finflex_normal_mode normals;
  int clamp; /* nonzero: out-of-range values are clamped instead of an error */
  finflex_rig_path path;
};
/* Zeros, rotate normals, no clamp, the automatic path. */
FINFLEX_C_API void finflex_job_init(finflex_job* job);

/* ------------------------------------------------------------------ host outputs */

typedef enum finflex_format {
  FINFLEX_FORMAT_FLOAT32 = 0, /* 4 bytes a component */
  FINFLEX_FORMAT_HALF = 1,    /* IEEE half, device batches only (finflex_deformer_allocate) */
  FINFLEX_FORMAT_MAX_ENUM = 0x7fffffff
} finflex_format;

/* Where one attribute (positions, normals or tangents) goes in the caller's memory:
 * component c (x, y, z) of vertex v of instance i is the float at
 *   (char*)data + i * instance_stride + v * vertex_stride + 4 * c,
 * v in the mesh's own vertex order. `capacity` bytes from `data` must hold every
 * element: instance_stride * (instances - 1) + vertex_stride * (vertices - 1) + 12.
 * Interleaved (positions at +0, normals at +12, vertex_stride 24) and separate arrays
 * are both described. data NULL: the attribute is not written. */
typedef struct finflex_attribute_layout {
  void* data;
  size_t vertex_stride;   /* bytes; >= 12, a multiple of 4 */
  size_t instance_stride; /* bytes; >= vertex_stride * vertices, a multiple of 4 */
  size_t capacity;        /* bytes */
  finflex_format format;  /* FINFLEX_FORMAT_FLOAT32 */
} finflex_attribute_layout;

typedef struct finflex_host_outputs {
  finflex_attribute_layout positions;
  finflex_attribute_layout normals;
  finflex_attribute_layout tangents; /* data NULL unless the mesh has tangents */
} finflex_host_outputs;

/* Fills `layout` for a tightly packed float32 array of shape (instances, vertices, 3). */
FINFLEX_C_API void finflex_attribute_layout_packed(void* data, size_t instances, size_t vertices,
                                                   finflex_attribute_layout* layout);

/* ------------------------------------------------------------- reference backend */

/* The CPU reference (double precision, the oracle): deforms the job's instances of
 * `model` and writes them, rounded to float32, to `outputs`. Every layout is checked
 * before anything runs (field "outputs.positions.capacity", ...); on error nothing
 * is written. */
FINFLEX_C_API finflex_status finflex_reference_deform(finflex_model* model, const finflex_job* job,
                                                      const finflex_host_outputs* outputs);
/* Instance `instance` of host outputs laid out for `instance_count` instances of
 * `model` as a whole mesh (the rest mesh's faces and texcoords), e.g. to save it. */
FINFLEX_C_API finflex_status finflex_model_instance_mesh(finflex_model* model,
                                                         const finflex_host_outputs* outputs,
                                                         size_t instance_count, size_t instance,
                                                         finflex_mesh** mesh);

/* ---------------------------------------------------------------- OpenCL backend */

typedef struct finflex_deformer finflex_deformer; /* a model uploaded to a context's device */
typedef struct finflex_batch finflex_batch;       /* device outputs of a number of instances */
typedef struct finflex_event finflex_event;       /* the completion of enqueued work */

FINFLEX_C_API finflex_status finflex_deformer_create(finflex_context* context,
                                                     const finflex_model* model,
                                                     finflex_deformer** deformer);
FINFLEX_C_API void finflex_deformer_destroy(finflex_deformer* deformer);
FINFLEX_C_API const finflex_error* finflex_deformer_error(const finflex_deformer* deformer);
/* Device outputs for `instance_count` instances, normals and tangents in `format`.
 * FINFLEX_ERROR_OUT_OF_RANGE naming "instances" above the device's largest allocation. */
FINFLEX_C_API finflex_status finflex_deformer_allocate(finflex_deformer* deformer,
                                                       size_t instance_count, finflex_format format,
                                                       finflex_batch** batch);
/* Checks the job (its parameters against the rig's limits, the batch against the
 * model and the instance count: field "job.outputs"), enqueues the parameter upload
 * and the kernels after the `wait_count` events of `wait`, and returns without
 * waiting. `done` (may be NULL) receives the frame's event, to wait for or destroy.
 * Nothing is enqueued on error. */
FINFLEX_C_API finflex_status finflex_deformer_enqueue(finflex_deformer* deformer,
                                                      const finflex_job* job, finflex_batch* batch,
                                                      finflex_event* const* wait, size_t wait_count,
                                                      finflex_event** done);
/* Blocking copy of every instance of `batch` from the device planes into `outputs`
 * (the caller's memory, mesh vertex order, float32; half values are widened). */
FINFLEX_C_API finflex_status finflex_deformer_read(finflex_deformer* deformer,
                                                   const finflex_batch* batch,
                                                   const finflex_host_outputs* outputs);
/* Blocking: writes instance `instance` of `batch` as a mesh file. */
FINFLEX_C_API finflex_status finflex_deformer_save_instance(finflex_deformer* deformer,
                                                            const finflex_batch* batch,
                                                            size_t instance, const char* path);
/* The slot of every mesh vertex in the device planes (vertex_count values). */
FINFLEX_C_API finflex_status finflex_deformer_slot_of_vertex(finflex_deformer* deformer,
                                                             uint32_t* slots, size_t count);

FINFLEX_C_API void finflex_batch_destroy(finflex_batch* batch);
FINFLEX_C_API size_t finflex_batch_instance_count(const finflex_batch* batch);

typedef enum finflex_attribute {
  FINFLEX_POSITIONS = 0,
  FINFLEX_NORMALS = 1,
  FINFLEX_TANGENTS = 2,
  FINFLEX_ATTRIBUTE_MAX_ENUM = 0x7fffffff
} finflex_attribute;
/* The device layout of a batch (finflex/batch.hpp): component c of slot s of instance
 * i at element (i * 3 + c) * plane_stride + s of the attribute's buffer. */
typedef struct finflex_batch_layout {
  size_t vertex_count;
  size_t instance_count;
  size_t plane_stride; /* elements */
  int tangents;        /* nonzero when the batch has tangents */
  finflex_format normal_format;
} finflex_batch_layout;
FINFLEX_C_API void finflex_batch_get_layout(const finflex_batch* batch,
                                            finflex_batch_layout* layout);
/* The attribute's cl_mem as void*, owned by the batch (not to be released); NULL for
 * a NULL handle. */
FINFLEX_C_API void* finflex_batch_cl_buffer(const finflex_batch* batch,
                                            finflex_attribute attribute);

/* Blocks until the event's work is done (FINFLEX_ERROR_OPENCL if it failed). */
FINFLEX_C_API finflex_status finflex_event_wait(finflex_event* event);
/* *complete = 1 once the work is done, 0 before, without blocking. */
FINFLEX_C_API finflex_status finflex_event_is_complete(finflex_event* event, int* complete);
FINFLEX_C_API void finflex_event_destroy(finflex_event* event);
FINFLEX_C_API const finflex_error* finflex_event_error(const finflex_event* event);

/* ------------------------------------------------------------------- swimming */

/* Swimming fish (finflex/swim.hpp, finflex/cl_swim.hpp): a swim rig made ready to
 * swim, and the driver kernel that turns each fish's pose, speed and turning rate
 * into its rig parameters and world placement on the device, for a deformer's frames:
 *
 *   finflex_swim_model_create(model, &swim);  finflex_swim_model_get_model(swim, &own);
 *   finflex_deformer_create(ctx, own, &def);  (the swim model's own model)
 *   finflex_swim_driver_create(ctx, swim, lengths, fish, NULL, &driver);
 *   every frame: finflex_swim_driver_enqueue(driver, inputs, fish, dt, NULL, 0, NULL);
 *                finflex_deformer_enqueue_swim(def, driver, batch, FINFLEX_NORMALS_ROTATE,
 *                                              NULL, 0, &done);  (world space)
 * or, the frame handed to the device whole (finflex_frame_gate, below):
 *                finflex_frame_gate_create(ctx, &gate);
 *                finflex_swim_driver_enqueue(driver, inputs, fish, dt,
 *                                            finflex_frame_gate_event_list(gate), 1, NULL);
 *                finflex_deformer_enqueue_swim(...);  finflex_frame_gate_destroy(gate); */
typedef struct finflex_swim_model finflex_swim_model;
typedef struct finflex_swim_driver finflex_swim_driver;

/* One fish's frame (finflex::SwimInput, the same 7 floats). */
typedef struct finflex_swim_input {
  float position[3]; /* the pivot, metres, y up */
  float yaw;         /* about +y, radians: 0 towards +x, pi/2 towards -z */
  float pitch;       /* nose up, radians */
  float speed;       /* through the water, m/s, >= 0 */
  float turn_rate;   /* rad/s, > 0 turns to the fish's left */
} finflex_swim_input;

/* FINFLEX_ERROR_INVALID_ARGUMENT naming "swim.wave" when the rig has no spine on its
 * body (its parameter "body_wave"); the fins ("tail_angle", "right_pectoral_angle",
 * "left_pectoral_angle") are driven when the rig has them. */
FINFLEX_C_API finflex_status finflex_swim_model_create(const finflex_model* model,
                                                       finflex_swim_model** swim);
FINFLEX_C_API void finflex_swim_model_destroy(finflex_swim_model* swim);
FINFLEX_C_API const finflex_error* finflex_swim_model_error(const finflex_swim_model* swim);
/* The swim model's own model (a new handle, sharing it): the deformer of its frames is
 * made from this one. */
FINFLEX_C_API finflex_status finflex_swim_model_get_model(const finflex_swim_model* swim,
                                                          finflex_model** model);
/* Angles in the spine's table (0 for a NULL handle). */
FINFLEX_C_API size_t finflex_swim_model_samples(const finflex_swim_model* swim);

/* One fish per length (metres, > 0: field "lengths[i]"); phases (cycles, fish_count
 * values) or NULL for 0. */
FINFLEX_C_API finflex_status finflex_swim_driver_create(finflex_context* context,
                                                        const finflex_swim_model* swim,
                                                        const float* lengths, size_t fish_count,
                                                        const float* phases,
                                                        finflex_swim_driver** driver);
FINFLEX_C_API void finflex_swim_driver_destroy(finflex_swim_driver* driver);
FINFLEX_C_API const finflex_error* finflex_swim_driver_error(const finflex_swim_driver* driver);
FINFLEX_C_API size_t finflex_swim_driver_fish_count(const finflex_swim_driver* driver);
/* One frame of dt seconds (> 0: field "dt"): `count` inputs, one per fish ("inputs"
 * otherwise; "inputs[i].speed" etc. for a bad value). Nothing is enqueued on error.
 * `done` (may be NULL) receives the driver kernel's event. */
FINFLEX_C_API finflex_status finflex_swim_driver_enqueue(finflex_swim_driver* driver,
                                                         const finflex_swim_input* inputs,
                                                         size_t count, float dt,
                                                         finflex_event* const* wait,
                                                         size_t wait_count, finflex_event** done);
/* Blocking reads of the last frame: the rig parameters (fish x values_per_instance
 * floats) and the placement records (fish x 16 floats: the columns of L Q, the
 * position, 1 / L; finflex/placement.hpp). `capacity` in floats, checked. */
FINFLEX_C_API finflex_status finflex_swim_driver_read_parameters(finflex_swim_driver* driver,
                                                                 float* values, size_t capacity);
FINFLEX_C_API finflex_status finflex_swim_driver_read_placements(finflex_swim_driver* driver,
                                                                 float* records, size_t capacity);
/* The deformation of the driver's last frame into `batch` (at least fish_count
 * instances), reading its parameters and placements on the device: outputs in world
 * space. The deformer must be made from the swim model's own model (field "driver").
 * Enqueue it after finflex_swim_driver_enqueue (the queue is in order). */
FINFLEX_C_API finflex_status finflex_deformer_enqueue_swim(finflex_deformer* deformer,
                                                           finflex_swim_driver* driver,
                                                           finflex_batch* batch,
                                                           finflex_normal_mode normals,
                                                           finflex_event* const* wait,
                                                           size_t wait_count, finflex_event** done);

/* A gate that holds a frame's device work back until all of it is enqueued
 * (finflex::FrameGate): put its event in the wait list of the frame's first command
 * (finflex_frame_gate_event_list: an array of one), enqueue the rest, then open it or
 * destroy it (which opens it). On NVIDIA's OpenCL the frame then goes to the device
 * whole: no wait between its kernels, and shorter enqueue calls. Nothing may wait for
 * the device (finflex_event_wait, a blocking read) while it is closed: that would
 * wait for ever. The gate's event belongs to the gate. */
typedef struct finflex_frame_gate finflex_frame_gate;
FINFLEX_C_API finflex_status finflex_frame_gate_create(finflex_context* context,
                                                       finflex_frame_gate** gate);
FINFLEX_C_API finflex_event* const* finflex_frame_gate_event_list(finflex_frame_gate* gate);
FINFLEX_C_API finflex_status finflex_frame_gate_open(finflex_frame_gate* gate);
FINFLEX_C_API int finflex_frame_gate_is_open(const finflex_frame_gate* gate);
FINFLEX_C_API void finflex_frame_gate_destroy(finflex_frame_gate* gate); /* opens it if closed */
FINFLEX_C_API const finflex_error* finflex_frame_gate_error(const finflex_frame_gate* gate);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* FINFLEX_H */
