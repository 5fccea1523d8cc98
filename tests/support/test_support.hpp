// Shared helpers for the FinFlex tests: paths of bundled data and scratch files.
#pragma once

#include <string>

#include "finflex/context.hpp"

namespace finflex::test {

// Absolute path of a file under the project's data/ folder, e.g. "blub/fish.obj".
std::string data_path(const std::string& relative);

// A fresh path under the test build's tmp/ folder (the file does not exist).
std::string temp_path(const std::string& file_name);

// Every bundled real fish, as data/-relative paths.
const char* const kBundledFish[] = {"blub/fish.obj", "blub/fish_low_resolution.obj",
                                    "barramundi/BarramundiFish.gltf"};

// One OpenCL context for a whole test program (default device: PoCL on a CPU
// machine), so each kernel variant is compiled once. Sets POCL_CACHE_DIR to the test
// build's own cache unless the environment already sets it.
Context& shared_context();

}  // namespace finflex::test
