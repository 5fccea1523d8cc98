// Writing a file so that it appears whole or not at all: the bytes go to a temporary
// file in the destination's folder (same file system), which commit() renames onto the
// destination; a TempFile destroyed uncommitted removes its file.
#pragma once

#include <cstddef>
#include <string>

namespace finflex::render::detail {

class TempFile {
 public:
  // Creates ".<name>.tmp-XXXXXX" next to `destination` (mode 0644, close-on-exec). kIo naming the
  // destination when the folder is missing or not writable.
  explicit TempFile(const std::string& destination);
  ~TempFile();
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  const std::string& path() const { return path_; }
  const std::string& destination() const { return destination_; }
  int descriptor() const { return descriptor_; }  // open for writing until commit()

  void write(const void* data, std::size_t bytes);  // at the current position; kIo
  // Closes the file and renames it onto the destination. kIo on failure.
  void commit();
  // Closes and removes the file now (the destructor would do it later).
  void discard();

 private:
  std::string destination_;
  std::string path_;
  int descriptor_ = -1;
  bool committed_ = false;
};

// The whole of `bytes` written to `path` through a TempFile.
void write_file_atomically(const std::string& path, const void* data, std::size_t bytes);

}  // namespace finflex::render::detail
