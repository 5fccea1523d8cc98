// Several models in one frame (finflex/cl_deformer.hpp): every entry's job checked
// first, then all enqueued, so a bad entry stops the frame before anything runs.
#include <string>

#include "cl/deformer_impl.hpp"
#include "finflex/cl_deformer.hpp"
#include "finflex/error.hpp"

namespace finflex {

struct RigFrame::Entry {
  ClDeformer* deformer;
  DeviceBatch batch;
  RigParameters parameters;
};

RigFrame::RigFrame() = default;
RigFrame::~RigFrame() = default;

std::size_t RigFrame::add(ClDeformer& deformer, std::size_t instances, NormalFormat format) {
  entries_.push_back(Entry{&deformer, deformer.allocate(instances, format),
                           RigParameters(deformer.model(), instances)});
  return entries_.size() - 1;
}

std::size_t RigFrame::size() const { return entries_.size(); }

RigFrame::Entry& RigFrame::at(std::size_t entry) {
  if (entry >= entries_.size()) {
    throw Error(ErrorCode::kInvalidArgument, "entry",
                "entry = " + std::to_string(entry) + " is out of range (" +
                    std::to_string(entries_.size()) + " entries)");
  }
  return entries_[entry];
}

RigParameters& RigFrame::parameters(std::size_t entry) { return at(entry).parameters; }
DeviceBatch& RigFrame::batch(std::size_t entry) { return at(entry).batch; }

std::vector<cl::Event> RigFrame::enqueue(NormalMode normals, RigPath path, bool clamp) {
  std::vector<ClJob> jobs(entries_.size());
  for (std::size_t k = 0; k < entries_.size(); ++k) {
    Entry& entry = entries_[k];
    ClJob& job = jobs[k];
    job.instances = entry.parameters.instance_count();
    job.parameters = entry.parameters.view();
    job.normals = normals;
    job.clamp = clamp;
    job.path = path;
    job.outputs = &entry.batch;
    entry.deformer->impl_->check(job);
  }
  std::vector<cl::Event> done;
  done.reserve(entries_.size());
  for (std::size_t k = 0; k < entries_.size(); ++k)
    done.push_back(entries_[k].deformer->impl_->enqueue(jobs[k], nullptr, true));
  return done;
}

}  // namespace finflex
