// Writing an output file of the command line atomically: into a new temporary file in
// the target's folder, then renamed onto the target. On any error the temporary file
// is removed and an existing target is left as it was.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace finflex::cli {

// Writes through `write`; kIo (field `option`) naming the path and the reason when
// creating, writing, syncing or renaming fails. A replaced file keeps its permission
// bits; a new one gets 0666 less the umask.
void write_file_atomically(const std::string& option, const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace finflex::cli
