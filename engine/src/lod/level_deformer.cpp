#include "finflex/level_deformer.hpp"

#include <string>

#include "finflex/error.hpp"

namespace finflex {

struct LevelDeformer::Impl {
  const DetailLevels& levels;
  LevelChooser chooser;
  std::vector<std::unique_ptr<ClDeformer>> deformers;
  std::vector<DeviceBatch> batches;

  Impl(Context& context, const DetailLevels& detail, std::size_t capacity,
       const LevelChoiceOptions& options, NormalFormat format, bool own_outputs)
      : levels(detail), chooser(context, detail, capacity, options) {
    for (std::size_t k = 0; k < detail.size(); ++k) {
      deformers.push_back(std::make_unique<ClDeformer>(context, detail.level(k).model));
      batches.push_back(own_outputs ? deformers.back()->allocate(chooser.rows(k), format)
                                    : DeviceBatch{});
    }
  }
};

LevelDeformer::LevelDeformer(Context& context, const DetailLevels& levels, std::size_t capacity,
                             const LevelChoiceOptions& options, NormalFormat format,
                             bool own_outputs)
    : impl_(std::make_unique<Impl>(context, levels, capacity, options, format, own_outputs)) {}

LevelDeformer::~LevelDeformer() = default;

std::size_t LevelDeformer::level_count() const { return impl_->deformers.size(); }
const DetailLevels& LevelDeformer::levels() const { return impl_->levels; }
LevelChooser& LevelDeformer::chooser() { return impl_->chooser; }
ClDeformer& LevelDeformer::deformer(std::size_t level) { return *impl_->deformers.at(level); }
DeviceBatch& LevelDeformer::batch(std::size_t level) { return impl_->batches.at(level); }

void LevelDeformer::set_batch(std::size_t level, DeviceBatch batch) {
  const std::size_t rows = impl_->chooser.rows(level);
  if (batch.model_id != deformer(level).model().id() || batch.shape.instance_count != rows) {
    throw Error(ErrorCode::kInvalidArgument, "batch",
                "batch: level " + std::to_string(level) + " takes a batch of its deformer for " +
                    std::to_string(rows) + " instances (this one holds " +
                    std::to_string(batch.shape.instance_count) + ")");
  }
  impl_->batches.at(level) = std::move(batch);
}

ClJob LevelDeformer::job(std::size_t level, const ClDeviceInputs& inputs, std::size_t instances,
                         NormalMode normals) {
  Impl& d = *impl_;
  ClJob job;
  job.instances = d.chooser.rows(level);
  job.normals = normals;
  job.outputs = &d.batches.at(level);
  job.device = inputs;
  job.list = {&d.chooser.lists(), d.chooser.list_first(level), &d.chooser.counts(), level,
              instances};
  return job;
}

cl::Event LevelDeformer::enqueue(const ClDeviceInputs& inputs, std::size_t instances,
                                 const std::vector<LevelView>& views, NormalMode normals,
                                 const std::vector<cl::Event>* wait,
                                 std::vector<cl::Event>* kernel_events) {
  if (inputs.parameters == nullptr) {
    throw Error(ErrorCode::kInvalidArgument, "inputs.parameters",
                "inputs.parameters: null (the instances' values on the device are needed)");
  }
  if (inputs.placements == nullptr) {
    throw Error(ErrorCode::kInvalidArgument, "inputs.placements",
                "inputs.placements: null (the choice needs every instance's placement)");
  }
  Impl& d = *impl_;
  std::vector<ClJob> jobs(d.deformers.size());
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    jobs[k] = job(k, inputs, instances, normals);
    d.deformers[k]->check(jobs[k]);  // every level's job checked before anything is enqueued
  }
  std::vector<cl::Event> choice;
  cl::Event done = d.chooser.enqueue(*inputs.placements, instances, views, wait,
                                     kernel_events ? &choice : nullptr);
  std::vector<cl::Event> level_events;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    done = d.deformers[k]->enqueue(jobs[k], kernel_events ? &level_events : nullptr);
    if (kernel_events) choice.insert(choice.end(), level_events.begin(), level_events.end());
  }
  if (kernel_events) *kernel_events = std::move(choice);
  return done;
}

}  // namespace finflex
