// The process's resident memory (VmRSS of /proc/self/status), for watching that a
// long run's memory stays flat.
#pragma once

#include <cstddef>

namespace finflex::soak {

// Resident bytes now; 0 where /proc is not available.
std::size_t resident_bytes();

}  // namespace finflex::soak
