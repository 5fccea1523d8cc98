// What kind of file a stat() mode names, for messages that refuse anything but a
// regular file as input (FIFOs and devices would block or never end).
#pragma once

#include <string>

#include "finflex/export.hpp"

namespace finflex {

// "a directory", "a FIFO (named pipe)", "a character device", "a block device",
// "a socket", "not a regular file" for other kinds; "" for a regular file.
FINFLEX_API std::string non_regular_kind(unsigned st_mode);

}  // namespace finflex
