/* The C API (bindings/c/include/finflex.h) from C: every function, error paths
 * included, with results checked against the C++ library (oracle.cpp).
 * Usage: test_c_api SECTION   (errors, mesh, model, parameters, reference, device, swim)
 * Prints "N passed, N failed" and exits nonzero on any failure. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <finflex.h>

#include "oracle.h"

static int passed = 0;
static int failed = 0;

#define CHECK(condition)                                                            \
  do {                                                                              \
    if (condition) {                                                                \
      ++passed;                                                                     \
    } else {                                                                        \
      ++failed;                                                                     \
      fprintf(stderr, "%s:%d: CHECK(%s) failed\n", __FILE__, __LINE__, #condition); \
    }                                                                               \
  } while (0)

/* A call that must succeed. */
#define OK(call)                                                                          \
  do {                                                                                    \
    finflex_status status_ = (call);                                                      \
    if (status_ == FINFLEX_OK) {                                                          \
      ++passed;                                                                           \
    } else {                                                                              \
      ++failed;                                                                           \
      fprintf(stderr, "%s:%d: %s returned %s: %s\n", __FILE__, __LINE__, #call,           \
              finflex_status_name(status_), finflex_error_message(finflex_last_error())); \
    }                                                                                     \
  } while (0)

/* A call that must fail with `expected`, naming `field` (NULL: any) on the thread and,
 * when `handle_error` is not NULL, on that handle; the message must contain `text`. */
static void expect_error(const char* where, int line, finflex_status status,
                         finflex_status expected, const finflex_error* handle_error,
                         const char* field, const char* text) {
  const finflex_error* last = finflex_last_error();
  int ok = status == expected && finflex_error_status(last) == expected;
  if (field != NULL) ok = ok && strcmp(finflex_error_field(last), field) == 0;
  if (text != NULL) ok = ok && strstr(finflex_error_message(last), text) != NULL;
  if (handle_error != NULL) {
    ok = ok && finflex_error_status(handle_error) == expected &&
         strcmp(finflex_error_message(handle_error), finflex_error_message(last)) == 0 &&
         strcmp(finflex_error_field(handle_error), finflex_error_field(last)) == 0;
  }
  if (ok) {
    ++passed;
  } else {
    ++failed;
    fprintf(stderr, "%s:%d: expected %s (field '%s', text '%s'), got %s field '%s': %s\n", where,
            line, finflex_status_name(expected), field ? field : "*", text ? text : "*",
            finflex_status_name(status), finflex_error_field(last), finflex_error_message(last));
  }
}
#define FAILS(call, expected, handle_error, field, text) \
  expect_error(__FILE__, __LINE__, (call), (expected), (handle_error), (field), (text))

#define MESH_PATH FINFLEX_DATA_DIR "/blub/fish_low_resolution.obj"
#define RIG_PATH FINFLEX_DATA_DIR "/rigs/blub_low_resolution.rig.json"
#define INVALID FINFLEX_ERROR_INVALID_ARGUMENT

static char tmp_path[512];
static const char* temp_file(const char* name) {
  snprintf(tmp_path, sizeof tmp_path, "%s/c_api_%s", FINFLEX_TEST_TMP_DIR, name);
  return tmp_path;
}

static double max_difference(const float* a, const float* b, size_t n) {
  double worst = 0.0;
  size_t k;
  for (k = 0; k < n; ++k) {
    const double d = fabs((double)a[k] - (double)b[k]);
    if (!(d <= worst)) worst = d; /* NaN counts as the worst */
  }
  return worst;
}

/* ------------------------------------------------------------------------ errors */

static void test_errors(void) {
  finflex_mesh* mesh = NULL;
  CHECK(strcmp(finflex_status_name(FINFLEX_OK), "ok") == 0);
  CHECK(strcmp(finflex_status_name(FINFLEX_ERROR_OUT_OF_RANGE), "out_of_range") == 0);
  CHECK(strcmp(finflex_status_name(FINFLEX_ERROR_INVALID_MESH), "invalid_mesh") == 0);
  CHECK(strcmp(finflex_status_name(FINFLEX_ERROR_IO), "io") == 0);
  CHECK(strcmp(finflex_status_name(FINFLEX_ERROR_FORMAT), "format") == 0);
  CHECK(strcmp(finflex_status_name(FINFLEX_ERROR_DEVICE), "device") == 0);
  CHECK(strcmp(finflex_status_name(FINFLEX_ERROR_OPENCL), "opencl") == 0);
  CHECK(strcmp(finflex_status_name(FINFLEX_ERROR_OUT_OF_MEMORY), "out_of_memory") == 0);
  CHECK(strcmp(finflex_status_name(FINFLEX_ERROR_INTERNAL), "internal") == 0);
  CHECK(strcmp(finflex_status_name((finflex_status)99), "unknown") == 0);
  CHECK(strcmp(finflex_version(), "0.1.0") == 0);

  /* No error yet on this thread; NULL records read as no error. */
  CHECK(finflex_error_status(finflex_last_error()) == FINFLEX_OK);
  CHECK(finflex_error_status(NULL) == FINFLEX_OK);
  CHECK(strcmp(finflex_error_message(NULL), "") == 0);
  CHECK(strcmp(finflex_error_field(NULL), "") == 0);

  /* Every handle's error reader takes NULL. */
  CHECK(finflex_context_error(NULL) == NULL);
  CHECK(finflex_mesh_error(NULL) == NULL);
  CHECK(finflex_rig_error(NULL) == NULL);
  CHECK(finflex_model_error(NULL) == NULL);
  CHECK(finflex_parameters_error(NULL) == NULL);
  CHECK(finflex_deformer_error(NULL) == NULL);
  CHECK(finflex_event_error(NULL) == NULL);

  /* NULL handles and outputs: an error naming the argument, never a crash. */
  FAILS(finflex_mesh_load(NULL, &mesh), INVALID, NULL, "path", "path is NULL");
  FAILS(finflex_mesh_load(MESH_PATH, NULL), INVALID, NULL, "mesh", "mesh is NULL");
  FAILS(finflex_mesh_save(NULL, "x.obj"), INVALID, NULL, "mesh", NULL);
  FAILS(finflex_context_device(NULL, NULL), INVALID, NULL, "context", NULL);
  FAILS(finflex_context_finish(NULL), INVALID, NULL, "context", NULL);
  FAILS(finflex_model_create_single_bend(NULL, NULL, FINFLEX_BEND_EXACT, NULL), INVALID, NULL,
        "model", NULL);
  FAILS(finflex_parameters_set(NULL, 0, "m", 0.1f), INVALID, NULL, "parameters", NULL);
  FAILS(finflex_deformer_enqueue(NULL, NULL, NULL, NULL, 0, NULL), INVALID, NULL, "deformer", NULL);
  FAILS(finflex_event_wait(NULL), INVALID, NULL, "event", NULL);
  FAILS(finflex_reference_deform(NULL, NULL, NULL), INVALID, NULL, "model", NULL);
  FAILS(finflex_list_devices(NULL, 0, NULL), INVALID, NULL, "count", NULL);
  {
    size_t count = 0;
    FAILS(finflex_list_devices(NULL, 2, &count), INVALID, NULL, "devices", NULL);
  }
  CHECK(finflex_mesh_vertex_count(NULL) == 0);
  CHECK(finflex_mesh_triangle_count(NULL) == 0);
  CHECK(finflex_model_vertex_count(NULL) == 0);
  CHECK(finflex_model_values_per_instance(NULL) == 0);
  CHECK(finflex_model_parameter_count(NULL) == 0);
  CHECK(finflex_parameters_instance_count(NULL) == 0);
  CHECK(finflex_parameters_data(NULL) == NULL);
  CHECK(finflex_batch_instance_count(NULL) == 0);
  CHECK(finflex_batch_cl_buffer(NULL, FINFLEX_POSITIONS) == NULL);
  CHECK(finflex_context_cl_context(NULL) == NULL);
  CHECK(finflex_context_cl_queue(NULL) == NULL);
  finflex_job_init(NULL);
  finflex_body_frame_identity(NULL);
  finflex_attribute_layout_packed(NULL, 1, 1, NULL);
  finflex_batch_get_layout(NULL, NULL);
  /* Destroying NULL is allowed. */
  finflex_context_destroy(NULL);
  finflex_mesh_destroy(NULL);
  finflex_rig_destroy(NULL);
  finflex_model_destroy(NULL);
  finflex_parameters_destroy(NULL);
  finflex_deformer_destroy(NULL);
  finflex_batch_destroy(NULL);
  finflex_event_destroy(NULL);
}

/* -------------------------------------------------------------------------- mesh */

static const float kTriangle[9] = {-0.5f, 0.0f, 0.0f, 0.5f, 0.0f, 0.0f, 0.0f, 0.1f, 0.05f};
static const uint32_t kTriangleIndices[3] = {0, 1, 2};

static void test_mesh(void) {
  finflex_mesh* mesh = NULL;
  finflex_mesh* made = NULL;
  finflex_mesh* again = NULL;
  float* positions;
  float* normals;
  uint32_t* indices;
  size_t vertices, triangles;
  float bad[9];
  float normal_out[9];
  finflex_body_frame frame;

  OK(finflex_mesh_load(MESH_PATH, &mesh));
  vertices = finflex_mesh_vertex_count(mesh);
  triangles = finflex_mesh_triangle_count(mesh);
  CHECK(vertices == 945);
  CHECK(triangles > 0);
  CHECK(finflex_error_status(finflex_mesh_error(mesh)) == FINFLEX_OK);

  positions = (float*)malloc(vertices * 3 * sizeof(float));
  normals = (float*)malloc(vertices * 3 * sizeof(float));
  indices = (uint32_t*)malloc(triangles * 3 * sizeof(uint32_t));
  OK(finflex_mesh_get_positions(mesh, positions, vertices * 3));
  OK(finflex_mesh_get_normals(mesh, normals, vertices * 3));
  OK(finflex_mesh_get_indices(mesh, indices, triangles * 3));
  FAILS(finflex_mesh_get_positions(mesh, positions, vertices * 3 - 1), INVALID,
        finflex_mesh_error(mesh), "count", "expected 2835 values (945 vertices x 3)");
  FAILS(finflex_mesh_get_normals(mesh, normals, 3), INVALID, finflex_mesh_error(mesh), "count",
        NULL);
  FAILS(finflex_mesh_get_indices(mesh, indices, 0), INVALID, finflex_mesh_error(mesh), "count",
        NULL);
  FAILS(finflex_mesh_get_positions(mesh, NULL, 3), INVALID, finflex_mesh_error(mesh), "positions",
        NULL);
  /* A success clears the handle's error but not the thread's. */
  OK(finflex_mesh_get_indices(mesh, indices, triangles * 3));
  CHECK(finflex_error_status(finflex_mesh_error(mesh)) == FINFLEX_OK);
  CHECK(finflex_error_status(finflex_last_error()) == INVALID);

  /* The same mesh from arrays, with and without normals. */
  OK(finflex_mesh_create(positions, vertices, indices, triangles * 3, normals, &made));
  CHECK(finflex_mesh_vertex_count(made) == vertices);
  finflex_mesh_destroy(made);
  OK(finflex_mesh_create(kTriangle, 3, kTriangleIndices, 3, NULL, &made));
  OK(finflex_mesh_get_normals(made, normal_out, 9));
  CHECK(fabsf(normal_out[2]) > 0.4f); /* computed from the face */
  memcpy(bad, kTriangle, sizeof bad);
  bad[4] = (float)NAN;
  FAILS(finflex_mesh_create(bad, 3, kTriangleIndices, 3, NULL, &again), FINFLEX_ERROR_INVALID_MESH,
        NULL, "positions[1].y", NULL);
  CHECK(again == NULL);
  {
    const uint32_t out_of_range[3] = {0, 1, 7};
    FAILS(finflex_mesh_create(kTriangle, 3, out_of_range, 3, NULL, &again),
          FINFLEX_ERROR_INVALID_MESH, NULL, NULL, NULL);
  }
  FAILS(finflex_mesh_create(kTriangle, 3, kTriangleIndices, 2, NULL, &again),
        FINFLEX_ERROR_INVALID_MESH, NULL, NULL, NULL);
  FAILS(finflex_mesh_create(NULL, 3, kTriangleIndices, 3, NULL, &again), INVALID, NULL, "positions",
        NULL);
  FAILS(finflex_mesh_create(kTriangle, 0, NULL, 0, NULL, &again), FINFLEX_ERROR_INVALID_MESH, NULL,
        NULL, NULL);

  /* Files: save, load back, errors leave no file. */
  OK(finflex_mesh_save(made, temp_file("triangle.obj")));
  OK(finflex_mesh_load(temp_file("triangle.obj"), &again));
  CHECK(finflex_mesh_vertex_count(again) == 3);
  finflex_mesh_destroy(again);
  again = NULL;
  FAILS(finflex_mesh_save(made, temp_file("triangle.xyz")), FINFLEX_ERROR_FORMAT,
        finflex_mesh_error(made), NULL, NULL);
  FAILS(finflex_mesh_save(made, "/nonexistent-folder/x.obj"), FINFLEX_ERROR_IO,
        finflex_mesh_error(made), NULL, NULL);
  FAILS(finflex_mesh_load("/nonexistent-folder/x.obj", &again), FINFLEX_ERROR_IO, NULL, NULL,
        "/nonexistent-folder/x.obj");
  CHECK(again == NULL);

  /* Body frames. */
  OK(finflex_mesh_find_body_frame(mesh, &frame));
  CHECK(frame.length > 0.0);
  CHECK(fabs(frame.axis_x[0] * frame.axis_x[0] + frame.axis_x[1] * frame.axis_x[1] +
             frame.axis_x[2] * frame.axis_x[2] - 1.0) < 1e-9);
  OK(finflex_mesh_create(kTriangle, 3, NULL, 0, NULL, &again)); /* no triangles, no area */
  FAILS(finflex_mesh_find_body_frame(again, &frame), FINFLEX_ERROR_INVALID_MESH,
        finflex_mesh_error(again), "mesh", NULL);
  finflex_mesh_destroy(again);
  again = NULL;
  FAILS(finflex_mesh_find_body_frame(mesh, NULL), INVALID, finflex_mesh_error(mesh), "frame", NULL);
  finflex_body_frame_identity(&frame);
  CHECK(frame.length == 1.0 && frame.axis_y[1] == 1.0 && frame.origin[0] == 0.0);

  free(positions);
  free(normals);
  free(indices);
  finflex_mesh_destroy(made);
  finflex_mesh_destroy(mesh);
}

/* ------------------------------------------------------------------------- model */

static void test_model(void) {
  finflex_mesh* mesh = NULL;
  finflex_rig* rig = NULL;
  finflex_rig* bad_rig = NULL;
  finflex_model* bend = NULL;
  finflex_model* rigged = NULL;
  finflex_model* none = NULL;
  finflex_parameter_info info;
  finflex_body_frame frame;
  size_t index = 99;

  OK(finflex_mesh_load(MESH_PATH, &mesh));
  OK(finflex_model_create_single_bend(mesh, NULL, FINFLEX_BEND_EXACT, &bend));
  CHECK(finflex_model_vertex_count(bend) == 945);
  CHECK(finflex_model_values_per_instance(bend) == 1);
  CHECK(finflex_model_parameter_count(bend) == 1);
  OK(finflex_model_parameter(bend, 0, &info));
  CHECK(strcmp(info.name, "m") == 0 && info.offset == 0 && info.count == 1 && info.limit > 0.5);
  FAILS(finflex_model_parameter(bend, 1, &info), INVALID, finflex_model_error(bend), "index",
        "out of range");
  FAILS(finflex_model_parameter(bend, 0, NULL), INVALID, finflex_model_error(bend), "info", NULL);
  OK(finflex_model_find_parameter(bend, "m", &index));
  CHECK(index == 0);
  FAILS(finflex_model_find_parameter(bend, "tail", &index), INVALID, finflex_model_error(bend),
        "tail", "its parameters: m");
  FAILS(finflex_model_create_single_bend(mesh, NULL, (finflex_bend_mode)5, &none), INVALID,
        finflex_mesh_error(mesh), "mode", "mode = 5");
  CHECK(none == NULL);

  /* An explicit frame: the identity, and a broken one. */
  finflex_body_frame_identity(&frame);
  OK(finflex_model_create_single_bend(mesh, &frame, FINFLEX_BEND_PAPER, &none));
  finflex_model_destroy(none);
  none = NULL;
  frame.length = -1.0;
  FAILS(finflex_model_create_single_bend(mesh, &frame, FINFLEX_BEND_PAPER, &none), INVALID, NULL,
        "frame.length", NULL);

  /* Rigs. */
  OK(finflex_rig_load(RIG_PATH, &rig));
  OK(finflex_model_create(mesh, rig, &rigged));
  CHECK(finflex_model_parameter_count(rigged) == 4);
  CHECK(finflex_model_values_per_instance(rigged) == 4);
  OK(finflex_model_find_parameter(rigged, "tail_angle", &index));
  CHECK(index == 1);
  FAILS(finflex_rig_load("/nonexistent-folder/r.json", &bad_rig), FINFLEX_ERROR_IO, NULL, "path",
        NULL);
  FAILS(finflex_rig_parse("{\"components\": [", &bad_rig), FINFLEX_ERROR_FORMAT, NULL, "rig", NULL);
  FAILS(finflex_rig_parse("{\"components\": [], \"colour\": 1}", &bad_rig), INVALID, NULL, NULL,
        "colour");
  FAILS(finflex_rig_parse(NULL, &bad_rig), INVALID, NULL, "json", NULL);
  CHECK(bad_rig == NULL);
  OK(finflex_rig_parse(
      "{\"components\": [{\"name\": \"body\", \"select\": \"all\", \"chain\": []},"
      " {\"name\": \"fin\", \"parent\": \"nobody\", \"select\": \"all\", \"chain\": []}]}",
      &bad_rig));
  CHECK(finflex_error_status(finflex_rig_error(bad_rig)) == FINFLEX_OK);
  FAILS(finflex_model_create(mesh, bad_rig, &none), INVALID, finflex_mesh_error(mesh),
        "components[1] 'fin'.parent", "nobody");
  FAILS(finflex_model_create(mesh, NULL, &none), INVALID, finflex_mesh_error(mesh), "rig", NULL);
  CHECK(none == NULL);

  /* A model keeps its own copy of the mesh. */
  finflex_mesh_destroy(mesh);
  CHECK(finflex_model_vertex_count(bend) == 945);

  finflex_rig_destroy(bad_rig);
  finflex_rig_destroy(rig);
  finflex_model_destroy(rigged);
  finflex_model_destroy(bend);
}

/* -------------------------------------------------------------------- parameters */

static void test_parameters(void) {
  finflex_mesh* mesh = NULL;
  finflex_rig* rig = NULL;
  finflex_model* model = NULL;
  finflex_parameters* p = NULL;
  finflex_parameters* none = NULL;
  finflex_job job;
  float value = 0.0f;
  float* data;

  OK(finflex_mesh_load(MESH_PATH, &mesh));
  OK(finflex_rig_load(RIG_PATH, &rig));
  OK(finflex_model_create(mesh, rig, &model));
  OK(finflex_parameters_create(model, 3, &p));
  CHECK(finflex_parameters_instance_count(p) == 3);
  FAILS(finflex_parameters_create(model, 0, &none), INVALID, finflex_model_error(model),
        "instances", NULL);
  CHECK(none == NULL);

  OK(finflex_parameters_set(p, 2, "tail_angle", 0.25f));
  OK(finflex_parameters_get(p, 2, "tail_angle", &value));
  CHECK(value == 0.25f);
  data = finflex_parameters_data(p);
  CHECK(data != NULL && data[2 * 4 + 1] == 0.25f);
  data[0] = 0.5f; /* body_m of instance 0, written directly */
  OK(finflex_parameters_get(p, 0, "body_m", &value));
  CHECK(value == 0.5f);
  {
    const float one = -0.125f;
    OK(finflex_parameters_set_values(p, 1, "left_pectoral_angle", &one, 1));
    OK(finflex_parameters_get(p, 1, "left_pectoral_angle", &value));
    CHECK(value == -0.125f);
    FAILS(finflex_parameters_set_values(p, 1, "left_pectoral_angle", &one, 0), INVALID,
          finflex_parameters_error(p), "left_pectoral_angle", "takes 1 values, not 0");
    FAILS(finflex_parameters_set_values(p, 1, "left_pectoral_angle", NULL, 1), INVALID,
          finflex_parameters_error(p), "values", NULL);
  }
  FAILS(finflex_parameters_set(p, 0, "tail", 0.1f), INVALID, finflex_parameters_error(p), "tail",
        "is not in the rig");
  FAILS(finflex_parameters_set(p, 3, "tail_angle", 0.1f), INVALID, finflex_parameters_error(p),
        "instance", NULL);
  FAILS(finflex_parameters_set(p, 0, NULL, 0.1f), INVALID, finflex_parameters_error(p), "name",
        NULL);
  FAILS(finflex_parameters_get(p, 0, "tail", &value), INVALID, finflex_parameters_error(p), "tail",
        "is not in the rig");
  FAILS(finflex_parameters_get(p, 9, "tail_angle", &value), INVALID, finflex_parameters_error(p),
        "instance", NULL);
  FAILS(finflex_parameters_get(p, 0, "tail_angle", NULL), INVALID, finflex_parameters_error(p),
        "value", NULL);

  finflex_job_init(&job);
  CHECK(job.parameters == NULL && job.instance_count == 0 &&
        job.normals == FINFLEX_NORMALS_ROTATE && job.clamp == 0 && job.path == FINFLEX_PATH_AUTO);
  OK(finflex_parameters_view(p, &job));
  CHECK(job.parameters == finflex_parameters_data(p) && job.instance_count == 3 &&
        job.parameter_stride == 4);
  FAILS(finflex_parameters_view(p, NULL), INVALID, finflex_parameters_error(p), "job", NULL);

  finflex_parameters_destroy(p);
  finflex_model_destroy(model);
  finflex_rig_destroy(rig);
  finflex_mesh_destroy(mesh);
}

/* --------------------------------------------------------------------- reference */

#define INSTANCES 4

/* Parameter rows for `model`: instance i gets fraction[i] of every parameter's limit. */
static float* make_values(finflex_model* model) {
  static const float fraction[INSTANCES] = {0.0f, 0.3f, -0.6f, 0.95f};
  const size_t per = finflex_model_values_per_instance(model);
  const size_t count = finflex_model_parameter_count(model);
  float* values = (float*)calloc(INSTANCES * per, sizeof(float));
  size_t i, k;
  for (i = 0; i < INSTANCES; ++i) {
    for (k = 0; k < count; ++k) {
      finflex_parameter_info info;
      finflex_model_parameter(model, k, &info);
      values[i * per + info.offset] = fraction[i] * (float)(info.limit < 1.0 ? info.limit : 1.0);
    }
  }
  return values;
}

static void packed_outputs(float* positions, float* normals, size_t vertices,
                           finflex_host_outputs* outputs) {
  memset(outputs, 0, sizeof *outputs);
  finflex_attribute_layout_packed(positions, INSTANCES, vertices, &outputs->positions);
  finflex_attribute_layout_packed(normals, INSTANCES, vertices, &outputs->normals);
}

static void check_reference_model(finflex_model* model, const char* rig_path) {
  const size_t vertices = finflex_model_vertex_count(model);
  const size_t n = INSTANCES * vertices * 3;
  float* values = make_values(model);
  float* positions = (float*)malloc(n * sizeof(float));
  float* normals = (float*)malloc(n * sizeof(float));
  float* expected_positions = (float*)malloc(n * sizeof(float));
  float* expected_normals = (float*)malloc(n * sizeof(float));
  float* interleaved = (float*)malloc(2 * n * sizeof(float));
  finflex_host_outputs outputs;
  finflex_job job;
  int jacobian;
  size_t k;

  for (jacobian = 0; jacobian < 2; ++jacobian) {
    finflex_job_init(&job);
    job.parameters = values;
    job.instance_count = INSTANCES;
    job.normals = jacobian ? FINFLEX_NORMALS_JACOBIAN : FINFLEX_NORMALS_ROTATE;
    packed_outputs(positions, normals, vertices, &outputs);
    OK(finflex_reference_deform(model, &job, &outputs));
    CHECK(oracle_reference(MESH_PATH, rig_path, INSTANCES, values, jacobian, expected_positions,
                           expected_normals) == 0);
    /* The same computation: equal to the last bit. */
    CHECK(memcmp(positions, expected_positions, n * sizeof(float)) == 0);
    CHECK(memcmp(normals, expected_normals, n * sizeof(float)) == 0);
  }

  /* Interleaved: position then normal per vertex, 24 bytes apart. */
  outputs.positions.data = interleaved;
  outputs.positions.vertex_stride = 24;
  outputs.positions.instance_stride = 24 * vertices;
  outputs.positions.capacity = 2 * n * sizeof(float);
  outputs.normals = outputs.positions;
  outputs.normals.data = interleaved + 3;
  outputs.normals.capacity -= 12;
  OK(finflex_reference_deform(model, &job, &outputs));
  for (k = 0; k < INSTANCES * vertices; ++k) {
    if (memcmp(interleaved + 6 * k, positions + 3 * k, 12) != 0 ||
        memcmp(interleaved + 6 * k + 3, normals + 3 * k, 12) != 0) {
      break;
    }
  }
  CHECK(k == INSTANCES * vertices);

  free(values);
  free(positions);
  free(normals);
  free(expected_positions);
  free(expected_normals);
  free(interleaved);
}

static void test_reference(void) {
  finflex_mesh* mesh = NULL;
  finflex_rig* rig = NULL;
  finflex_model* bend = NULL;
  finflex_model* rigged = NULL;
  finflex_mesh* instance = NULL;
  finflex_host_outputs outputs, bad;
  finflex_job job;
  float values[INSTANCES] = {0.1f, 0.2f, 0.3f, 0.4f};
  float* positions;
  float* normals;
  float* instance_positions;
  size_t vertices;

  OK(finflex_mesh_load(MESH_PATH, &mesh));
  OK(finflex_rig_load(RIG_PATH, &rig));
  OK(finflex_model_create_single_bend(mesh, NULL, FINFLEX_BEND_EXACT, &bend));
  OK(finflex_model_create(mesh, rig, &rigged));
  check_reference_model(bend, NULL);
  check_reference_model(rigged, RIG_PATH);

  vertices = finflex_model_vertex_count(bend);
  positions = (float*)malloc(INSTANCES * vertices * 12);
  normals = (float*)malloc(INSTANCES * vertices * 12);
  instance_positions = (float*)malloc(vertices * 12);
  finflex_job_init(&job);
  job.parameters = values;
  job.instance_count = INSTANCES;
  packed_outputs(positions, normals, vertices, &outputs);
  OK(finflex_reference_deform(bend, &job, &outputs));

  /* An instance as a mesh, saved. */
  OK(finflex_model_instance_mesh(bend, &outputs, INSTANCES, 2, &instance));
  OK(finflex_mesh_get_positions(instance, instance_positions, vertices * 3));
  CHECK(memcmp(instance_positions, positions + 2 * vertices * 3, vertices * 12) == 0);
  OK(finflex_mesh_save(instance, temp_file("reference_instance.ply")));
  finflex_mesh_destroy(instance);
  instance = NULL;
  FAILS(finflex_model_instance_mesh(bend, &outputs, INSTANCES, INSTANCES, &instance), INVALID,
        finflex_model_error(bend), "instance", "out of range");
  bad = outputs;
  bad.positions.data = NULL;
  FAILS(finflex_model_instance_mesh(bend, &bad, INSTANCES, 0, &instance), INVALID,
        finflex_model_error(bend), "outputs.positions.data", NULL);
  CHECK(instance == NULL);

  /* Layouts that cannot hold the outputs: refused before anything is written. */
  positions[0] = 12345.0f;
  bad = outputs;
  bad.positions.capacity -= 4;
  FAILS(finflex_reference_deform(bend, &job, &bad), INVALID, finflex_model_error(bend),
        "outputs.positions.capacity", "too small");
  bad = outputs;
  bad.normals.vertex_stride = 8;
  FAILS(finflex_reference_deform(bend, &job, &bad), INVALID, NULL, "outputs.normals.vertex_stride",
        NULL);
  bad = outputs;
  bad.positions.instance_stride = 12;
  FAILS(finflex_reference_deform(bend, &job, &bad), INVALID, NULL,
        "outputs.positions.instance_stride", NULL);
  bad = outputs;
  bad.positions.format = FINFLEX_FORMAT_HALF;
  FAILS(finflex_reference_deform(bend, &job, &bad), INVALID, NULL, "outputs.positions.format",
        NULL);
  bad = outputs;
  bad.positions.data = (char*)positions + 2;
  FAILS(finflex_reference_deform(bend, &job, &bad), INVALID, NULL, "outputs.positions.data",
        "aligned");
  bad = outputs;
  bad.tangents = outputs.normals;
  FAILS(finflex_reference_deform(bend, &job, &bad), INVALID, NULL, "outputs.tangents.data",
        "no tangents");
  FAILS(finflex_reference_deform(bend, &job, NULL), INVALID, NULL, "outputs", NULL);
  FAILS(finflex_reference_deform(bend, NULL, &outputs), INVALID, NULL, "job", NULL);
  CHECK(positions[0] == 12345.0f);

  /* Jobs with bad values. */
  values[2] = 2.5f;
  FAILS(finflex_reference_deform(bend, &job, &outputs), FINFLEX_ERROR_OUT_OF_RANGE,
        finflex_model_error(bend), "m[2]", "2.5");
  CHECK(positions[0] == 12345.0f);
  job.clamp = 1;
  OK(finflex_reference_deform(bend, &job, &outputs));
  CHECK(finflex_error_status(finflex_model_error(bend)) == FINFLEX_OK);
  job.clamp = 0;
  values[2] = (float)NAN;
  FAILS(finflex_reference_deform(bend, &job, &outputs), INVALID, NULL, "m[2]", NULL);
  values[2] = 0.3f;
  job.normals = (finflex_normal_mode)3;
  FAILS(finflex_reference_deform(bend, &job, &outputs), INVALID, NULL, "job.normals", NULL);
  job.normals = FINFLEX_NORMALS_ROTATE;
  job.path = (finflex_rig_path)7;
  FAILS(finflex_reference_deform(bend, &job, &outputs), INVALID, NULL, "job.path", NULL);
  job.path = FINFLEX_PATH_AUTO;
  job.instance_count = 0;
  FAILS(finflex_reference_deform(bend, &job, &outputs), INVALID, NULL, "job.instances", NULL);
  job.instance_count = INSTANCES;
  job.parameters = NULL;
  FAILS(finflex_reference_deform(bend, &job, &outputs), INVALID, NULL, "job.parameters.data", NULL);
  job.parameters = values;
  job.instance_count = 1;
  job.parameter_stride = 2; /* the rig reads 4 values per instance */
  FAILS(finflex_reference_deform(rigged, &job, &outputs), INVALID, NULL, "job.parameters.stride",
        "below the model's 4 values");
  job.parameter_stride = 4;
  OK(finflex_reference_deform(rigged, &job, &outputs));
  job.parameter_stride = 0;

  free(positions);
  free(normals);
  free(instance_positions);
  finflex_model_destroy(rigged);
  finflex_model_destroy(bend);
  finflex_rig_destroy(rig);
  finflex_mesh_destroy(mesh);
}

/* ------------------------------------------------------------------------ device */

static void compare_device(finflex_deformer* deformer, finflex_model* model, const char* rig_path,
                           finflex_format format) {
  const size_t vertices = finflex_model_vertex_count(model);
  const size_t n = INSTANCES * vertices * 3;
  float* values = make_values(model);
  float* positions = (float*)malloc(n * sizeof(float));
  float* normals = (float*)malloc(n * sizeof(float));
  float* expected_positions = (float*)malloc(n * sizeof(float));
  float* expected_normals = (float*)malloc(n * sizeof(float));
  finflex_batch* batch = NULL;
  finflex_event* done = NULL;
  finflex_host_outputs outputs;
  finflex_job job;
  int complete = 0;

  OK(finflex_deformer_allocate(deformer, INSTANCES, format, &batch));
  finflex_job_init(&job);
  job.parameters = values;
  job.instance_count = INSTANCES;
  job.normals = FINFLEX_NORMALS_JACOBIAN;
  OK(finflex_deformer_enqueue(deformer, &job, batch, NULL, 0, &done));
  OK(finflex_event_wait(done));
  OK(finflex_event_is_complete(done, &complete));
  CHECK(complete == 1);
  CHECK(finflex_error_status(finflex_event_error(done)) == FINFLEX_OK);
  packed_outputs(positions, normals, vertices, &outputs);
  OK(finflex_deformer_read(deformer, batch, &outputs));
  CHECK(oracle_reference(MESH_PATH, rig_path, INSTANCES, values, 1, expected_positions,
                         expected_normals) == 0);
  CHECK(max_difference(positions, expected_positions, n) < 1e-4);
  CHECK(max_difference(normals, expected_normals, n) <
        (format == FINFLEX_FORMAT_HALF ? 5e-3 : 2e-3));

  finflex_event_destroy(done);
  finflex_batch_destroy(batch);
  free(values);
  free(positions);
  free(normals);
  free(expected_positions);
  free(expected_normals);
}

static void test_device(void) {
  finflex_device_info devices[8];
  finflex_device_info info;
  size_t count = 0;
  finflex_context* context = NULL;
  finflex_context* none = NULL;
  finflex_mesh* mesh = NULL;
  finflex_rig* rig = NULL;
  finflex_model* bend = NULL;
  finflex_model* rigged = NULL;
  finflex_deformer* deformer = NULL;
  finflex_deformer* rig_deformer = NULL;
  finflex_deformer* no_deformer = NULL;
  finflex_batch* batch = NULL;
  finflex_batch* rig_batch = NULL;
  finflex_batch* no_batch = NULL;
  finflex_event* first = NULL;
  finflex_event* second = NULL;
  finflex_mesh* saved = NULL;
  finflex_batch_layout layout;
  finflex_host_outputs outputs;
  finflex_job job;
  float values[INSTANCES] = {0.1f, -0.2f, 0.3f, 0.5f};
  float five[5] = {0.0f, 0.0f, 0.0f, 0.0f, 0.0f};
  uint32_t* slots;
  float* positions;
  float* normals;
  size_t vertices, k;

  /* Devices and the context. */
  OK(finflex_list_devices(NULL, 0, &count));
  CHECK(count > 0);
  OK(finflex_list_devices(devices, 8, &count));
  {
    int defaults = 0;
    for (k = 0; k < count && k < 8; ++k) defaults += devices[k].is_default;
    CHECK(defaults == 1);
    CHECK(strlen(devices[0].device_name) > 0 && devices[0].global_memory_bytes > 0);
  }
  FAILS(finflex_context_create("no-such-device", &none), FINFLEX_ERROR_DEVICE, NULL, NULL,
        "no-such-device");
  CHECK(none == NULL);
  OK(finflex_context_create(NULL, &context));
  OK(finflex_context_device(context, &info));
  CHECK(info.is_default == 1);
  FAILS(finflex_context_device(context, NULL), INVALID, finflex_context_error(context), "info",
        NULL);
  CHECK(finflex_context_cl_context(context) != NULL);
  CHECK(finflex_context_cl_queue(context) != NULL);

  /* Models and deformers. */
  OK(finflex_mesh_load(MESH_PATH, &mesh));
  OK(finflex_rig_load(RIG_PATH, &rig));
  OK(finflex_model_create_single_bend(mesh, NULL, FINFLEX_BEND_EXACT, &bend));
  OK(finflex_model_create(mesh, rig, &rigged));
  OK(finflex_deformer_create(context, bend, &deformer));
  OK(finflex_deformer_create(context, rigged, &rig_deformer));
  FAILS(finflex_deformer_create(context, NULL, &no_deformer), INVALID,
        finflex_context_error(context), "model", NULL);
  FAILS(finflex_deformer_create(NULL, bend, &no_deformer), INVALID, NULL, "context", NULL);
  CHECK(no_deformer == NULL);
  compare_device(deformer, bend, NULL, FINFLEX_FORMAT_FLOAT32);
  compare_device(deformer, bend, NULL, FINFLEX_FORMAT_HALF);
  compare_device(rig_deformer, rigged, RIG_PATH, FINFLEX_FORMAT_FLOAT32);

  /* Batches. */
  FAILS(finflex_deformer_allocate(deformer, 0, FINFLEX_FORMAT_FLOAT32, &no_batch), INVALID,
        finflex_deformer_error(deformer), "instances", NULL);
  FAILS(finflex_deformer_allocate(deformer, 1, (finflex_format)4, &no_batch), INVALID, NULL,
        "format", NULL);
  FAILS(finflex_deformer_allocate(deformer, (size_t)1 << 50, FINFLEX_FORMAT_FLOAT32, &no_batch),
        FINFLEX_ERROR_OUT_OF_RANGE, NULL, "instances", NULL);
  CHECK(no_batch == NULL);
  OK(finflex_deformer_allocate(deformer, INSTANCES, FINFLEX_FORMAT_FLOAT32, &batch));
  OK(finflex_deformer_allocate(rig_deformer, INSTANCES, FINFLEX_FORMAT_FLOAT32, &rig_batch));
  CHECK(finflex_batch_instance_count(batch) == INSTANCES);
  finflex_batch_get_layout(batch, &layout);
  vertices = finflex_model_vertex_count(bend);
  CHECK(layout.vertex_count == vertices && layout.instance_count == INSTANCES &&
        layout.plane_stride == 960 && layout.tangents == 0 &&
        layout.normal_format == FINFLEX_FORMAT_FLOAT32);
  CHECK(finflex_batch_cl_buffer(batch, FINFLEX_POSITIONS) != NULL);
  CHECK(finflex_batch_cl_buffer(batch, FINFLEX_NORMALS) != NULL);
  CHECK(finflex_batch_cl_buffer(batch, FINFLEX_TANGENTS) == NULL);

  /* Frames: events in, an event out. */
  finflex_job_init(&job);
  job.parameters = values;
  job.instance_count = INSTANCES;
  OK(finflex_deformer_enqueue(deformer, &job, batch, NULL, 0, &first));
  OK(finflex_deformer_enqueue(deformer, &job, batch, &first, 1, &second));
  OK(finflex_deformer_enqueue(deformer, &job, batch, NULL, 0, NULL));
  OK(finflex_event_wait(second));
  OK(finflex_context_finish(context));
  {
    finflex_event* missing[1] = {NULL};
    FAILS(finflex_deformer_enqueue(deformer, &job, batch, missing, 1, NULL), INVALID,
          finflex_deformer_error(deformer), "wait[0]", NULL);
    FAILS(finflex_deformer_enqueue(deformer, &job, batch, NULL, 2, NULL), INVALID, NULL, "wait",
          NULL);
  }
  values[3] = 3.0f;
  FAILS(finflex_deformer_enqueue(deformer, &job, batch, NULL, 0, NULL), FINFLEX_ERROR_OUT_OF_RANGE,
        finflex_deformer_error(deformer), "m[3]", "3");
  values[3] = 0.5f;
  FAILS(finflex_deformer_enqueue(deformer, &job, rig_batch, NULL, 0, NULL), INVALID, NULL,
        "job.outputs", NULL);
  job.parameters = five;
  job.instance_count = 5;
  FAILS(finflex_deformer_enqueue(deformer, &job, batch, NULL, 0, NULL), INVALID, NULL,
        "job.outputs", NULL);
  job.parameters = values;
  job.instance_count = INSTANCES;
  FAILS(finflex_deformer_enqueue(deformer, NULL, batch, NULL, 0, NULL), INVALID, NULL, "job", NULL);
  FAILS(finflex_deformer_enqueue(deformer, &job, NULL, NULL, 0, NULL), INVALID, NULL, "batch",
        NULL);
  OK(finflex_deformer_enqueue(deformer, &job, batch, NULL, 0, NULL));
  CHECK(finflex_error_status(finflex_deformer_error(deformer)) == FINFLEX_OK);

  /* Reading and saving. */
  positions = (float*)malloc(INSTANCES * vertices * 12);
  normals = (float*)malloc(INSTANCES * vertices * 12);
  packed_outputs(positions, normals, vertices, &outputs);
  OK(finflex_deformer_read(deformer, batch, &outputs));
  outputs.normals.capacity = 0;
  FAILS(finflex_deformer_read(deformer, batch, &outputs), INVALID, NULL, "outputs.normals.capacity",
        NULL);
  outputs.normals.data = NULL; /* not written */
  OK(finflex_deformer_read(deformer, batch, &outputs));
  FAILS(finflex_deformer_read(deformer, NULL, &outputs), INVALID, NULL, "batch", NULL);
  FAILS(finflex_deformer_read(deformer, batch, NULL), INVALID, NULL, "outputs", NULL);
  OK(finflex_deformer_save_instance(deformer, batch, 3, temp_file("device_instance.obj")));
  OK(finflex_mesh_load(temp_file("device_instance.obj"), &saved));
  CHECK(finflex_mesh_vertex_count(saved) == vertices);
  {
    float* loaded = (float*)malloc(vertices * 12);
    OK(finflex_mesh_get_positions(saved, loaded, vertices * 3));
    CHECK(max_difference(loaded, positions + 3 * vertices * 3, vertices * 3) < 1e-5);
    free(loaded);
  }
  FAILS(finflex_deformer_save_instance(deformer, batch, INSTANCES, temp_file("none.obj")), INVALID,
        finflex_deformer_error(deformer), "instance", NULL);
  FAILS(finflex_deformer_save_instance(deformer, batch, 0, NULL), INVALID, NULL, "path", NULL);

  /* Slots: the single bend keeps the mesh's order; a rig reorders. */
  slots = (uint32_t*)malloc(vertices * sizeof(uint32_t));
  OK(finflex_deformer_slot_of_vertex(deformer, slots, vertices));
  for (k = 0; k < vertices && slots[k] == k; ++k) {
  }
  CHECK(k == vertices);
  OK(finflex_deformer_slot_of_vertex(rig_deformer, slots, vertices));
  finflex_batch_get_layout(rig_batch, &layout);
  for (k = 0; k < vertices && slots[k] < layout.plane_stride; ++k) {
  }
  CHECK(k == vertices);
  CHECK(layout.plane_stride > 960); /* every component whole work-groups of 64 slots */
  FAILS(finflex_deformer_slot_of_vertex(deformer, slots, 3), INVALID,
        finflex_deformer_error(deformer), "count", NULL);

  /* Handles in any order: the context and the model go first. */
  finflex_context_destroy(context);
  finflex_model_destroy(bend);
  OK(finflex_deformer_enqueue(deformer, &job, batch, NULL, 0, NULL));
  OK(finflex_deformer_read(deformer, batch, &outputs));
  finflex_deformer_destroy(deformer);
  finflex_event_destroy(first);
  OK(finflex_event_wait(second));
  finflex_event_destroy(second);

  free(slots);
  free(positions);
  free(normals);
  finflex_mesh_destroy(saved);
  finflex_batch_destroy(batch);
  finflex_batch_destroy(rig_batch);
  finflex_deformer_destroy(rig_deformer);
  finflex_model_destroy(rigged);
  finflex_rig_destroy(rig);
  finflex_mesh_destroy(mesh);
}

/* -------------------------------------------------------------------------- swim */

#define SWIM_RIG_PATH FINFLEX_DATA_DIR "/rigs/blub_low_resolution_swim.rig.json"
#define FISH 3

static void test_swim(void) {
  const float lengths[FISH] = {0.3f, 0.45f, 0.25f};
  const float bad_lengths[2] = {0.3f, -0.2f};
  finflex_swim_input inputs[FISH];
  float rows[FISH * 7];
  finflex_mesh* mesh = NULL;
  finflex_rig* rig = NULL;
  finflex_model* model = NULL;
  finflex_model* bend = NULL;
  finflex_model* own = NULL;
  finflex_swim_model* swim = NULL;
  finflex_swim_model* no_swim = NULL;
  finflex_context* context = NULL;
  finflex_swim_driver* driver = NULL;
  finflex_swim_driver* no_driver = NULL;
  finflex_deformer* deformer = NULL;
  finflex_deformer* other = NULL;
  finflex_batch* batch = NULL;
  finflex_event* driven = NULL;
  finflex_event* done = NULL;
  finflex_frame_gate* no_gate = NULL;
  finflex_host_outputs outputs;
  float *positions, *normals, *want_positions, *want_normals, *values, *records;
  size_t vertices, i, frame;

  for (i = 0; i < FISH; ++i) {
    inputs[i].position[0] = (float)i - 1.0f;
    inputs[i].position[1] = 0.5f + 0.1f * (float)i;
    inputs[i].position[2] = 0.2f * (float)i;
    inputs[i].yaw = 1.1f * (float)i;
    inputs[i].pitch = 0.05f * (float)i - 0.05f;
    inputs[i].speed = lengths[i] * (0.6f + 0.5f * (float)i);
    inputs[i].turn_rate = i % 2 ? 0.4f : -0.3f;
    memcpy(rows + 7 * i, &inputs[i], sizeof inputs[i]);
  }
  CHECK(sizeof(finflex_swim_input) == 7 * sizeof(float));
  OK(finflex_mesh_load(MESH_PATH, &mesh));
  OK(finflex_rig_load(SWIM_RIG_PATH, &rig));
  OK(finflex_model_create(mesh, rig, &model));
  OK(finflex_model_create_single_bend(mesh, NULL, FINFLEX_BEND_EXACT, &bend));
  FAILS(finflex_swim_model_create(bend, &no_swim), INVALID, finflex_model_error(bend), "swim.wave",
        NULL);
  FAILS(finflex_swim_model_create(NULL, &no_swim), INVALID, NULL, "model", NULL);
  CHECK(no_swim == NULL);
  OK(finflex_swim_model_create(model, &swim));
  CHECK(finflex_swim_model_samples(swim) == 32);
  CHECK(finflex_swim_model_samples(NULL) == 0);
  OK(finflex_swim_model_get_model(swim, &own));
  OK(finflex_context_create(NULL, &context));
  FAILS(finflex_swim_driver_create(context, swim, bad_lengths, 2, NULL, &no_driver), INVALID,
        finflex_context_error(context), "lengths[1]", NULL);
  FAILS(finflex_swim_driver_create(context, NULL, lengths, FISH, NULL, &no_driver), INVALID, NULL,
        "swim", NULL);
  FAILS(finflex_swim_driver_create(context, swim, NULL, FISH, NULL, &no_driver), INVALID, NULL,
        "lengths", NULL);
  CHECK(no_driver == NULL);
  OK(finflex_swim_driver_create(context, swim, lengths, FISH, NULL, &driver));
  CHECK(finflex_swim_driver_fish_count(driver) == FISH);
  OK(finflex_deformer_create(context, own, &deformer));
  OK(finflex_deformer_create(context, model, &other));
  OK(finflex_deformer_allocate(deformer, FISH, FINFLEX_FORMAT_FLOAT32, &batch));

  /* Five frames, the driver's event handed to the deformation; the last two behind a
   * frame gate: nothing of them runs before it opens (frame 3: opened, frame 4: by its
   * destruction). */
  FAILS(finflex_frame_gate_create(NULL, &no_gate), INVALID, NULL, "context", NULL);
  CHECK(no_gate == NULL);
  CHECK(finflex_frame_gate_event_list(NULL) == NULL);
  CHECK(finflex_frame_gate_is_open(NULL) == 0);
  finflex_frame_gate_destroy(NULL);
  for (frame = 0; frame < 5; ++frame) {
    finflex_frame_gate* gate = NULL;
    int complete = 1;
    if (frame >= 3) OK(finflex_frame_gate_create(context, &gate));
    OK(finflex_swim_driver_enqueue(driver, inputs, FISH, 1.0f / 30.0f,
                                   gate ? finflex_frame_gate_event_list(gate) : NULL, gate ? 1 : 0,
                                   &driven));
    OK(finflex_deformer_enqueue_swim(deformer, driver, batch, FINFLEX_NORMALS_ROTATE, &driven, 1,
                                     &done));
    if (gate) {
      OK(finflex_event_is_complete(driven, &complete));
      CHECK(complete == 0);
      CHECK(finflex_frame_gate_is_open(gate) == 0);
      if (frame == 3) {
        OK(finflex_frame_gate_open(gate));
        OK(finflex_frame_gate_open(gate));
        CHECK(finflex_frame_gate_is_open(gate) == 1);
      }
      finflex_frame_gate_destroy(gate);
    }
    OK(finflex_event_wait(done));
    finflex_event_destroy(driven);
    finflex_event_destroy(done);
  }
  vertices = finflex_model_vertex_count(own);
  positions = (float*)malloc(FISH * vertices * 12);
  normals = (float*)malloc(FISH * vertices * 12);
  want_positions = (float*)malloc(FISH * vertices * 12);
  want_normals = (float*)malloc(FISH * vertices * 12);
  packed_outputs(positions, normals, vertices, &outputs);
  OK(finflex_deformer_read(deformer, batch, &outputs));
  CHECK(oracle_swim(MESH_PATH, SWIM_RIG_PATH, FISH, lengths, rows, 5, want_positions,
                    want_normals) == 0);
  CHECK(max_difference(positions, want_positions, FISH * vertices * 3) == 0.0);
  CHECK(max_difference(normals, want_normals, FISH * vertices * 3) == 0.0);

  /* Reads of the driver's last frame. */
  values = (float*)malloc(FISH * finflex_model_values_per_instance(own) * sizeof(float));
  records = (float*)malloc(FISH * 16 * sizeof(float));
  OK(finflex_swim_driver_read_parameters(driver, values,
                                         FISH * finflex_model_values_per_instance(own)));
  OK(finflex_swim_driver_read_placements(driver, records, FISH * 16));
  for (i = 0; i < FISH; ++i) {
    CHECK(records[16 * i + 9] == inputs[i].position[0]);
    CHECK(fabs(records[16 * i + 12] * lengths[i] - 1.0) < 1e-6);
  }
  FAILS(finflex_swim_driver_read_placements(driver, records, 16), INVALID,
        finflex_swim_driver_error(driver), "capacity", NULL);
  FAILS(finflex_swim_driver_read_parameters(driver, values, 1), INVALID, NULL, "capacity", NULL);

  /* Bad frames: nothing is enqueued, the field is named. */
  FAILS(finflex_swim_driver_enqueue(driver, inputs, FISH - 1, 1.0f / 30.0f, NULL, 0, NULL), INVALID,
        finflex_swim_driver_error(driver), "inputs", NULL);
  FAILS(finflex_swim_driver_enqueue(driver, inputs, FISH, 0.0f, NULL, 0, NULL), INVALID, NULL, "dt",
        NULL);
  inputs[1].speed = -1.0f;
  FAILS(finflex_swim_driver_enqueue(driver, inputs, FISH, 1.0f / 30.0f, NULL, 0, NULL), INVALID,
        NULL, "inputs[1].speed", NULL);
  inputs[1].speed = 0.2f;
  FAILS(finflex_swim_driver_enqueue(driver, NULL, FISH, 1.0f / 30.0f, NULL, 0, NULL), INVALID, NULL,
        "inputs", NULL);
  FAILS(finflex_deformer_enqueue_swim(other, driver, batch, FINFLEX_NORMALS_ROTATE, NULL, 0, NULL),
        INVALID, finflex_deformer_error(other), "driver", NULL);
  FAILS(finflex_deformer_enqueue_swim(deformer, NULL, batch, FINFLEX_NORMALS_ROTATE, NULL, 0, NULL),
        INVALID, NULL, "driver", NULL);
  FAILS(
      finflex_deformer_enqueue_swim(deformer, driver, batch, (finflex_normal_mode)7, NULL, 0, NULL),
      INVALID, NULL, "job.normals", NULL);
  FAILS(
      finflex_deformer_enqueue_swim(deformer, driver, NULL, FINFLEX_NORMALS_ROTATE, NULL, 0, NULL),
      INVALID, NULL, "batch", NULL);

  /* Handles in any order: the swim model, the context and the models go first. */
  finflex_swim_model_destroy(swim);
  finflex_context_destroy(context);
  finflex_model_destroy(own);
  OK(finflex_swim_driver_enqueue(driver, inputs, FISH, 1.0f / 30.0f, NULL, 0, NULL));
  OK(finflex_deformer_enqueue_swim(deformer, driver, batch, FINFLEX_NORMALS_JACOBIAN, NULL, 0,
                                   NULL));
  OK(finflex_deformer_read(deformer, batch, &outputs));

  free(positions);
  free(normals);
  free(want_positions);
  free(want_normals);
  free(values);
  free(records);
  finflex_batch_destroy(batch);
  finflex_deformer_destroy(deformer);
  finflex_deformer_destroy(other);
  finflex_swim_driver_destroy(driver);
  finflex_model_destroy(model);
  finflex_model_destroy(bend);
  finflex_rig_destroy(rig);
  finflex_mesh_destroy(mesh);
}

/* -------------------------------------------------------------------------- main */

int main(int argc, char** argv) {
  const char* section = argc > 1 ? argv[1] : "all";
  const int all = strcmp(section, "all") == 0;
  int ran = 0;
  if (all || strcmp(section, "errors") == 0) test_errors(), ran = 1;
  if (all || strcmp(section, "mesh") == 0) test_mesh(), ran = 1;
  if (all || strcmp(section, "model") == 0) test_model(), ran = 1;
  if (all || strcmp(section, "parameters") == 0) test_parameters(), ran = 1;
  if (all || strcmp(section, "reference") == 0) test_reference(), ran = 1;
  if (all || strcmp(section, "device") == 0) test_device(), ran = 1;
  if (all || strcmp(section, "swim") == 0) test_swim(), ran = 1;
  if (!ran) {
    fprintf(stderr, "unknown section '%s'\n", section);
    return 2;
  }
  printf("%s: %d checks passed, %d failed\n", section, passed, failed);
  return failed == 0 ? 0 : 1;
}
