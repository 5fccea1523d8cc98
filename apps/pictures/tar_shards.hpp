// WebDataset's layout (github.com/webdataset/webdataset): POSIX tar files ("shards")
// whose members are grouped into samples by their names' stem, `KEY.EXT` for every
// part of sample KEY, a sample's members one after another. Written here as plain
// ustar: regular files, mode 0644, owner 0, time 0 (the same bytes for the same
// content), names below 100 bytes.
#pragma once

#include <cstddef>
#include <fstream>
#include <string>

namespace finflex::pictures {

class TarShards {
 public:
  // Shards `folder`/shard-NNNNNN.tar of at most `samples_per_shard` samples each.
  TarShards(std::string folder, std::size_t samples_per_shard);
  // Starts the next sample (a new shard when the current one is full).
  void begin_sample();
  // Adds `name` (e.g. "frame_000007.png") with the bytes of the file at `path`. kIo
  // naming "--out" when the file cannot be read or the shard written; kInvalidArgument
  // for a name of 100 bytes or more.
  void add_file(const std::string& name, const std::string& path);
  void add_bytes(const std::string& name, const std::string& bytes);
  // Ends the last shard (two zero blocks).
  void finish();
  std::size_t shards() const { return shard_; }

 private:
  std::string folder_;
  std::size_t per_shard_;
  std::size_t in_shard_ = 0;
  std::size_t shard_ = 0;
  std::ofstream out_;
  std::string path_;
  void close_shard();
};

}  // namespace finflex::pictures
