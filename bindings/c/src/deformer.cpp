// The OpenCL backend: deformers, device batches, events.
#include "host_outputs.hpp"
#include "job.hpp"

using finflex::c::create;
using finflex::c::guarded;
using finflex::c::require;
using finflex::c::slot_of;

namespace {

finflex::NormalFormat normal_format(finflex_format format) {
  switch (format) {
    case FINFLEX_FORMAT_FLOAT32:
      return finflex::NormalFormat::kFloat32;
    case FINFLEX_FORMAT_HALF:
      return finflex::NormalFormat::kHalf;
    default:  // not a value of the enum: refused below
      break;
  }
  throw finflex::Error(finflex::ErrorCode::kInvalidArgument, "format",
                       "format = " + std::to_string(static_cast<int>(format)) +
                           ": expected FINFLEX_FORMAT_FLOAT32 (0) or FINFLEX_FORMAT_HALF (1)");
}

finflex::ClDeformer& deformer_of(finflex_deformer* deformer) {
  return *require(deformer, "deformer")->deformer;
}

const finflex::DeviceBatch& batch_of(const finflex_batch* batch) {
  return require(batch, "batch")->batch;
}

}  // namespace

extern "C" {

finflex_status finflex_deformer_create(finflex_context* context, const finflex_model* model,
                                       finflex_deformer** deformer) {
  return create(slot_of(context), deformer, "deformer", [&] {
    auto handle = std::make_unique<finflex_deformer>();
    handle->context = require(context, "context")->context;
    handle->model = require(model, "model")->model;
    handle->deformer = std::make_unique<finflex::ClDeformer>(*handle->context, *handle->model);
    return handle;
  });
}

void finflex_deformer_destroy(finflex_deformer* deformer) { delete deformer; }

const finflex_error* finflex_deformer_error(const finflex_deformer* deformer) {
  return slot_of(deformer);
}

finflex_status finflex_deformer_allocate(finflex_deformer* deformer, size_t instance_count,
                                         finflex_format format, finflex_batch** batch) {
  return create(slot_of(deformer), batch, "batch", [&] {
    finflex::ClDeformer& d = deformer_of(deformer);
    auto handle = std::make_unique<finflex_batch>();
    handle->batch = d.allocate(instance_count, normal_format(format));
    return handle;
  });
}

finflex_status finflex_deformer_enqueue(finflex_deformer* deformer, const finflex_job* job,
                                        finflex_batch* batch, finflex_event* const* wait,
                                        size_t wait_count, finflex_event** done) {
  return guarded(slot_of(deformer), [&] {
    finflex::ClDeformer& d = deformer_of(deformer);
    finflex::ClJob cl_job;
    finflex::c::fill_job(job, cl_job);
    cl_job.path = finflex::c::rig_path(job->path);
    cl_job.outputs = &require(batch, "batch")->batch;
    const std::vector<cl::Event> events = finflex::c::wait_events(wait, wait_count);
    if (!events.empty()) cl_job.wait = &events;
    finflex::c::enqueue_with_event(done, [&] { return d.enqueue(cl_job); });
  });
}

finflex_status finflex_deformer_read(finflex_deformer* deformer, const finflex_batch* batch,
                                     const finflex_host_outputs* outputs) {
  return guarded(slot_of(deformer), [&] {
    finflex::ClDeformer& d = deformer_of(deformer);
    const finflex::DeviceBatch& b = batch_of(batch);
    if (b.shape.vertex_count != d.model().vertex_count()) {
      throw finflex::Error(finflex::ErrorCode::kInvalidArgument, "batch",
                           "batch holds " + std::to_string(b.shape.vertex_count) +
                               " vertices per instance, the deformer's model " +
                               std::to_string(d.model().vertex_count()));
    }
    finflex::c::check_outputs(outputs, b.shape.instance_count, b.shape.vertex_count,
                              b.shape.tangents);
    finflex::c::store_outputs(d.read(b), *outputs);
  });
}

finflex_status finflex_deformer_save_instance(finflex_deformer* deformer,
                                              const finflex_batch* batch, size_t instance,
                                              const char* path) {
  return guarded(slot_of(deformer), [&] {
    finflex::ClDeformer& d = deformer_of(deformer);
    const finflex::DeviceBatch& b = batch_of(batch);
    require(path, "path");
    if (b.shape.vertex_count != d.model().vertex_count()) {
      throw finflex::Error(finflex::ErrorCode::kInvalidArgument, "batch",
                           "batch holds " + std::to_string(b.shape.vertex_count) +
                               " vertices per instance, the deformer's model " +
                               std::to_string(d.model().vertex_count()));
    }
    finflex::save_mesh(path, finflex::instance_mesh(d.model().mesh(), d.read(b), instance));
  });
}

finflex_status finflex_deformer_slot_of_vertex(finflex_deformer* deformer, uint32_t* slots,
                                               size_t count) {
  return guarded(slot_of(deformer), [&] {
    const std::vector<std::uint32_t>& s = deformer_of(deformer).slot_of_vertex();
    require(slots, "slots");
    if (count != s.size()) {
      throw finflex::Error(finflex::ErrorCode::kInvalidArgument, "count",
                           "count = " + std::to_string(count) + ": the model has " +
                               std::to_string(s.size()) + " vertices");
    }
    std::copy(s.begin(), s.end(), slots);
  });
}

void finflex_batch_destroy(finflex_batch* batch) { delete batch; }

size_t finflex_batch_instance_count(const finflex_batch* batch) {
  return batch == nullptr ? 0 : batch->batch.shape.instance_count;
}

void finflex_batch_get_layout(const finflex_batch* batch, finflex_batch_layout* layout) {
  if (layout == nullptr) return;
  *layout = finflex_batch_layout{};
  if (batch == nullptr) return;
  const finflex::BatchShape& l = batch->batch.shape;
  layout->vertex_count = l.vertex_count;
  layout->instance_count = l.instance_count;
  layout->plane_stride = l.plane_stride;
  layout->tangents = l.tangents ? 1 : 0;
  layout->normal_format = l.normal_format == finflex::NormalFormat::kHalf ? FINFLEX_FORMAT_HALF
                                                                          : FINFLEX_FORMAT_FLOAT32;
}

void* finflex_batch_cl_buffer(const finflex_batch* batch, finflex_attribute attribute) {
  if (batch == nullptr) return nullptr;
  switch (attribute) {
    case FINFLEX_POSITIONS:
      return batch->batch.positions();
    case FINFLEX_NORMALS:
      return batch->batch.normals();
    case FINFLEX_TANGENTS:
      return batch->batch.shape.tangents ? batch->batch.tangents() : nullptr;
    default:  // not a value of the enum: refused below
      break;
  }
  return nullptr;
}

finflex_status finflex_event_wait(finflex_event* event) {
  return guarded(slot_of(event), [&] {
    finflex::check_cl(require(event, "event")->event.wait(), "clWaitForEvents");
  });
}

finflex_status finflex_event_is_complete(finflex_event* event, int* complete) {
  return guarded(slot_of(event), [&] {
    const cl::Event& e = require(event, "event")->event;
    require(complete, "complete");
    cl_int status = CL_COMPLETE;
    finflex::check_cl(e.getInfo(CL_EVENT_COMMAND_EXECUTION_STATUS, &status),
                      "clGetEventInfo CL_EVENT_COMMAND_EXECUTION_STATUS");
    if (status < 0) finflex::check_cl(status, "the event's command");
    *complete = status == CL_COMPLETE ? 1 : 0;
  });
}

void finflex_event_destroy(finflex_event* event) { delete event; }

const finflex_error* finflex_event_error(const finflex_event* event) { return slot_of(event); }

}  // extern "C"
