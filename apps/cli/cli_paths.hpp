// File options checked before anything is read or written: an input must be a regular
// file (a FIFO, a device such as /dev/zero, a socket or a directory is refused by its
// kind, found with stat, so nothing is opened and nothing can block); an output must be
// in an existing folder and must not be anything but a regular file already (a
// directory, a FIFO or a device is never replaced).
#pragma once

#include <string>
#include <vector>

namespace finflex::cli {

// The extensions finflex/mesh_io.hpp reads and writes.
const std::vector<std::string>& mesh_extensions();

// kIo (field `option`): "--rig '/dev/zero': is a character device, not a regular
// file"; missing or inaccessible files with the system's reason. With `extensions`:
// kFormat unless the path ends with one of them (case-insensitive).
void check_input_file(const std::string& option, const std::string& path,
                      const std::vector<std::string>& extensions = {});

// kInvalidArgument for an empty path; kIo for a folder that does not exist or an
// existing path that is not a regular file; with `extensions`, kFormat unless the
// path ends with one of them.
void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& extensions = {});

}  // namespace finflex::cli
