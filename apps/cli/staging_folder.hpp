// An output folder that appears whole or not at all: a command writes everything into
// a hidden staging folder next to the target (".<name>.partial-XXXXXX", on the same
// file system) and commit() moves it into place at the end. A staging folder not
// committed (an error, an exception) is removed with everything in it, so a failed
// command leaves the target as it was.
#pragma once

#include <string>

namespace finflex::cli {

// Checks that `out` can be an output folder: an existing writable folder, or a new one
// whose parent folder exists. finflex::Error naming `option` and the path otherwise.
// Nothing is created.
void check_output_folder(const std::string& out, const std::string& option);

class StagingFolder {
 public:
  // Makes the staging folder next to `target` (which check_output_folder accepted).
  // kIo naming `option` when it cannot be made (e.g. the place is not writable).
  StagingFolder(const std::string& target, const std::string& option);
  ~StagingFolder();
  StagingFolder(const StagingFolder&) = delete;
  StagingFolder& operator=(const StagingFolder&) = delete;

  const std::string& path() const { return path_; }
  const std::string& target() const { return target_; }

  // Moves the contents into place: when the target does not exist the staging folder
  // is renamed to it (atomic); when it does, each entry replaces the target's entry of
  // the same name, and the rest of the target is left alone. kIo on failure.
  void commit();

 private:
  std::string target_;
  std::string option_;
  std::string path_;
  bool committed_ = false;
};

}  // namespace finflex::cli
