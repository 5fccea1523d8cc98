#include <string>

#include "finflex/error.hpp"
#include "finflex/rig_deformer.hpp"

namespace finflex {

std::size_t RigFrame::add(ClRigDeformer& deformer, std::size_t instances) {
  entries_.push_back(
      {&deformer, deformer.allocate(instances), RigParameters(deformer.rig(), instances)});
  return entries_.size() - 1;
}

RigFrame::Entry& RigFrame::at(std::size_t entry) {
  if (entry >= entries_.size()) {
    throw Error(ErrorCode::kInvalidArgument, "entry",
                "entry = " + std::to_string(entry) + " is out of range (" +
                    std::to_string(entries_.size()) + " entries)");
  }
  return entries_[entry];
}

std::vector<cl::Event> RigFrame::enqueue(NormalMode normals, RigPath path, bool clamp) {
  for (const Entry& entry : entries_) entry.deformer->check(entry.parameters, clamp);
  std::vector<cl::Event> done;
  done.reserve(entries_.size());
  for (Entry& entry : entries_) {
    done.push_back(entry.deformer->enqueue(entry.parameters, normals, entry.batch, path, clamp));
  }
  return done;
}

}  // namespace finflex
