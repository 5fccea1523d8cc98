// Swimming fish: swim models, the device driver, and a deformer's frames reading it.
#include <algorithm>
#include <string>

#include "job.hpp"

using finflex::c::create;
using finflex::c::guarded;
using finflex::c::require;
using finflex::c::slot_of;

namespace {

finflex::ClSwimDriver& driver_of(finflex_swim_driver* driver) {
  return *require(driver, "driver")->driver;
}

// Throws kInvalidArgument naming `field` when `capacity` floats are fewer than `needed`.
void check_capacity(std::size_t capacity, std::size_t needed, const char* field) {
  if (capacity >= needed) return;
  throw finflex::Error(finflex::ErrorCode::kInvalidArgument, field,
                       std::string(field) + " = " + std::to_string(capacity) +
                           " floats is too small: " + std::to_string(needed) + " are needed");
}

}  // namespace

extern "C" {

finflex_status finflex_swim_model_create(const finflex_model* model, finflex_swim_model** swim) {
  return create(slot_of(model), swim, "swim", [&] {
    auto handle = std::make_unique<finflex_swim_model>();
    handle->swim = std::make_shared<const finflex::SwimModel>(*require(model, "model")->model);
    return handle;
  });
}

void finflex_swim_model_destroy(finflex_swim_model* swim) { delete swim; }

const finflex_error* finflex_swim_model_error(const finflex_swim_model* swim) {
  return slot_of(swim);
}

finflex_status finflex_swim_model_get_model(const finflex_swim_model* swim, finflex_model** model) {
  return create(slot_of(swim), model, "model", [&] {
    const std::shared_ptr<const finflex::SwimModel>& own = require(swim, "swim")->swim;
    auto handle = std::make_unique<finflex_model>();
    // Shares the swim model: the deformer's model is the very one the driver writes for.
    handle->model = std::shared_ptr<const finflex::RiggedMesh>(own, &own->model());
    return handle;
  });
}

size_t finflex_swim_model_samples(const finflex_swim_model* swim) {
  return swim == nullptr ? 0 : swim->swim->samples();
}

finflex_status finflex_swim_driver_create(finflex_context* context, const finflex_swim_model* swim,
                                          const float* lengths, size_t fish_count,
                                          const float* phases, finflex_swim_driver** driver) {
  return create(slot_of(context), driver, "driver", [&] {
    auto handle = std::make_unique<finflex_swim_driver>();
    handle->context = require(context, "context")->context;
    handle->swim = require(swim, "swim")->swim;
    if (fish_count > 0) require(lengths, "lengths");
    const std::vector<float> fish_lengths(lengths, lengths + fish_count);
    const std::vector<float> fish_phases =
        phases == nullptr ? std::vector<float>{} : std::vector<float>(phases, phases + fish_count);
    handle->driver = std::make_unique<finflex::ClSwimDriver>(*handle->context, *handle->swim,
                                                             fish_lengths, fish_phases);
    return handle;
  });
}

void finflex_swim_driver_destroy(finflex_swim_driver* driver) { delete driver; }

const finflex_error* finflex_swim_driver_error(const finflex_swim_driver* driver) {
  return slot_of(driver);
}

size_t finflex_swim_driver_fish_count(const finflex_swim_driver* driver) {
  return driver == nullptr ? 0 : driver->driver->fish_count();
}

finflex_status finflex_swim_driver_enqueue(finflex_swim_driver* driver,
                                           const finflex_swim_input* inputs, size_t count, float dt,
                                           finflex_event* const* wait, size_t wait_count,
                                           finflex_event** done) {
  return guarded(slot_of(driver), [&] {
    finflex::ClSwimDriver& d = driver_of(driver);
    if (count > 0) require(inputs, "inputs");
    // A wrong count or dt is named before anything is staged (check_swim_inputs).
    if (count != d.fish_count()) finflex::check_swim_inputs(nullptr, count, d.fish_count(), dt);
    // Converted straight into the upload's staging memory, checked there.
    finflex::SwimInput* staged = d.staged_inputs();
    for (std::size_t i = 0; i < count; ++i) {
      finflex::SwimInput& in = staged[i];
      in.position = {inputs[i].position[0], inputs[i].position[1], inputs[i].position[2]};
      in.yaw = inputs[i].yaw;
      in.pitch = inputs[i].pitch;
      in.speed = inputs[i].speed;
      in.turn_rate = inputs[i].turn_rate;
    }
    const std::vector<cl::Event> events = finflex::c::wait_events(wait, wait_count);
    finflex::c::enqueue_with_event(
        done, [&] { return d.enqueue_staged(dt, events.empty() ? nullptr : &events); });
  });
}

finflex_status finflex_swim_driver_read_parameters(finflex_swim_driver* driver, float* values,
                                                   size_t capacity) {
  return guarded(slot_of(driver), [&] {
    finflex::ClSwimDriver& d = driver_of(driver);
    const std::size_t needed = d.fish_count() * driver->swim->model().values_per_instance();
    check_capacity(capacity, needed, "capacity");
    if (needed > 0) require(values, "values");
    const finflex::RigParameters read = d.read_parameters();
    std::copy(read.values().begin(), read.values().end(), values);
  });
}

finflex_status finflex_swim_driver_read_placements(finflex_swim_driver* driver, float* records,
                                                   size_t capacity) {
  return guarded(slot_of(driver), [&] {
    finflex::ClSwimDriver& d = driver_of(driver);
    const std::size_t needed = d.fish_count() * finflex::kPlacementFloats;
    check_capacity(capacity, needed, "capacity");
    if (needed > 0) require(records, "records");
    std::size_t at = 0;
    for (const finflex::PlacementRecord& record : d.read_placements()) {
      std::copy(record.begin(), record.end(), records + at);
      at += record.size();
    }
  });
}

finflex_status finflex_deformer_enqueue_swim(finflex_deformer* deformer,
                                             finflex_swim_driver* driver, finflex_batch* batch,
                                             finflex_normal_mode normals,
                                             finflex_event* const* wait, size_t wait_count,
                                             finflex_event** done) {
  return guarded(slot_of(deformer), [&] {
    finflex::ClDeformer& d = *require(deformer, "deformer")->deformer;
    finflex::ClSwimDriver& swim = driver_of(driver);
    if (&driver->swim->model() != deformer->model.get()) {
      throw finflex::Error(finflex::ErrorCode::kInvalidArgument, "driver",
                           "driver: its swim model's model is not the deformer's (make the "
                           "deformer from finflex_swim_model_get_model)");
    }
    finflex::ClJob job;
    job.normals = finflex::c::normal_mode(normals);
    job.instances = swim.fish_count();
    job.device.parameters = &swim.parameter_buffer();
    job.device.placements = &swim.placement_buffer();
    job.device.derived = swim.derived_buffer();
    job.outputs = &require(batch, "batch")->batch;
    const std::vector<cl::Event> events = finflex::c::wait_events(wait, wait_count);
    if (!events.empty()) job.wait = &events;
    finflex::c::enqueue_with_event(done, [&] { return d.enqueue(job); });
  });
}

}  // extern "C"
