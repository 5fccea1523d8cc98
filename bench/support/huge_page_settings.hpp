// The host's huge-page settings, reported with `finflex bench` results: on CPU devices
// they move a frame's time (docs/benchmarks.md, Swimming, "Huge pages").
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace finflex::bench {

// The system's transparent huge page mode ("always", "madvise" or "never"): the word in
// brackets in /sys/kernel/mm/transparent_hugepage/enabled; "unknown" where that file is
// missing (systems other than Linux) or says something else.
std::string transparent_huge_pages();

// glibc's malloc huge-page tunable as this process's environment sets it: the value of
// glibc.malloc.hugetlb among GLIBC_TUNABLES's colon-separated settings (the last one
// given), "0" (glibc's default, off) where it is not set.
std::string glibc_malloc_hugetlb();

// The bytes of this process's anonymous memory in transparent huge pages now (the
// AnonHugePages line of /proc/self/smaps_rollup): on CPU devices the outputs of at
// least 2 MiB are advised as huge pages (engine/src/cl/host_pages.hpp), and this says
// whether the system gave them. Empty where the file is missing or unreadable.
std::optional<std::uint64_t> process_huge_page_bytes();

}  // namespace finflex::bench
