// libFuzzer: bytes as a rig file through parse_rig_json, resolve_rig against a small
// fish, the model and one reference frame. finflex::Error is the expected outcome of
// bad input; anything else (a crash, a sanitizer report, another exception, a
// timeout, memory past the run's limit) is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "finflex/error.hpp"
#include "finflex/rig.hpp"
#include "fuzz_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace finflex;
  try {
    const RigSpec spec = parse_rig_json(std::string(reinterpret_cast<const char*>(data), size));
    fuzz::exercise(resolve_rig(spec, fuzz::rig_fuzz_mesh()));
  } catch (const Error&) {
  }
  return 0;
}
