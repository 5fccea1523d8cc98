/* Bends a small synthetic mesh through the installed C API (FinFlex::finflex_c) on the
 * default device and checks it against the CPU reference. Exit 0 on agreement. */
#include <math.h>
#include <stdio.h>

#include <finflex.h>

static int fail(const char* what) {
  const finflex_error* e = finflex_last_error();
  printf("%s failed: %s (%s, field '%s')\n", what, finflex_error_message(e),
         finflex_status_name(finflex_error_status(e)), finflex_error_field(e));
  return 1;
}

int main(void) {
  const float positions[9] = {-0.5f, 0.0f, 0.0f, 0.5f, 0.0f, 0.0f, 0.0f, 0.1f, 0.05f};
  const uint32_t indices[3] = {0, 1, 2};
  const float m[2] = {0.5f, -0.9f};
  float device[2][3][3], reference[2][3][3];
  finflex_mesh* mesh;
  finflex_model* model;
  finflex_context* context;
  finflex_deformer* deformer;
  finflex_batch* batch;
  finflex_event* done;
  finflex_body_frame frame;
  finflex_host_outputs out = {0};
  finflex_job job;
  finflex_device_info info;
  int i, v, c;

  finflex_body_frame_identity(&frame);
  if (finflex_mesh_create(positions, 3, indices, 3, NULL, &mesh)) return fail("mesh");
  if (finflex_model_create_single_bend(mesh, &frame, FINFLEX_BEND_EXACT, &model))
    return fail("model");
  if (finflex_context_create(NULL, &context)) return fail("context");
  if (finflex_deformer_create(context, model, &deformer)) return fail("deformer");
  if (finflex_deformer_allocate(deformer, 2, FINFLEX_FORMAT_FLOAT32, &batch)) return fail("batch");
  finflex_job_init(&job);
  job.parameters = m;
  job.instance_count = 2;
  job.normals = FINFLEX_NORMALS_JACOBIAN;
  if (finflex_deformer_enqueue(deformer, &job, batch, NULL, 0, &done)) return fail("enqueue");
  if (finflex_event_wait(done)) return fail("wait");
  finflex_attribute_layout_packed(device, 2, 3, &out.positions);
  if (finflex_deformer_read(deformer, batch, &out)) return fail("read");
  finflex_attribute_layout_packed(reference, 2, 3, &out.positions);
  if (finflex_reference_deform(model, &job, &out)) return fail("reference");
  for (i = 0; i < 2; ++i)
    for (v = 0; v < 3; ++v)
      for (c = 0; c < 3; ++c)
        if (fabsf(device[i][v][c] - reference[i][v][c]) > 1e-5f) {
          printf("instance %d vertex %d differs\n", i, v);
          return 1;
        }
  if (finflex_context_device(context, &info)) return fail("device");
  printf("downstream C: %s agrees with the reference\n", info.device_name);
  finflex_event_destroy(done);
  finflex_batch_destroy(batch);
  finflex_deformer_destroy(deformer);
  finflex_context_destroy(context);
  finflex_model_destroy(model);
  finflex_mesh_destroy(mesh);
  return 0;
}
