#include "tar_shards.hpp"

#include <cstdio>
#include <cstring>
#include <iterator>
#include <utility>

#include "finflex/error.hpp"

namespace finflex::pictures {

namespace {

constexpr std::size_t kBlock = 512;

void octal(char* field, std::size_t width, unsigned long long value) {
  // width - 1 digits and a NUL, as ustar writes numbers.
  std::snprintf(field, width, "%0*llo", int(width - 1), value);
}

}  // namespace

TarShards::TarShards(std::string folder, std::size_t samples_per_shard)
    : folder_(std::move(folder)), per_shard_(samples_per_shard) {}

void TarShards::begin_sample() {
  if (out_.is_open() && in_shard_ < per_shard_) {
    ++in_shard_;
    return;
  }
  close_shard();
  char name[32];
  std::snprintf(name, sizeof name, "/shard-%06zu.tar", shard_++);
  path_ = folder_ + name;
  out_.open(path_, std::ios::binary);
  if (!out_) throw Error(ErrorCode::kIo, "--out", "'" + path_ + "': cannot be written");
  in_shard_ = 1;
}

void TarShards::add_file(const std::string& name, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(ErrorCode::kIo, "--out", "'" + path + "': cannot be read");
  add_bytes(name, std::string(std::istreambuf_iterator<char>(in), {}));
}

void TarShards::add_bytes(const std::string& name, const std::string& bytes) {
  if (name.size() >= 100) {
    throw Error(ErrorCode::kInvalidArgument, "name", "tar member name '" + name + "' is too long");
  }
  char header[kBlock] = {};
  std::memcpy(header, name.data(), name.size());
  octal(header + 100, 8, 0644);  // mode
  octal(header + 108, 8, 0);     // uid
  octal(header + 116, 8, 0);     // gid
  octal(header + 124, 12, bytes.size());
  octal(header + 136, 12, 0);  // mtime
  header[156] = '0';           // a regular file
  std::memcpy(header + 257, "ustar", 6);
  std::memcpy(header + 263, "00", 2);
  // The checksum: the header's bytes summed with its own field as spaces.
  std::memset(header + 148, ' ', 8);
  unsigned sum = 0;
  for (unsigned char c : header) sum += c;
  std::snprintf(header + 148, 8, "%06o", sum);
  header[155] = ' ';
  out_.write(header, kBlock);
  out_.write(bytes.data(), std::streamsize(bytes.size()));
  const std::size_t pad = (kBlock - bytes.size() % kBlock) % kBlock;
  const char zeros[kBlock] = {};
  out_.write(zeros, std::streamsize(pad));
  if (!out_) throw Error(ErrorCode::kIo, "--out", "'" + path_ + "': write failed");
}

void TarShards::close_shard() {
  if (!out_.is_open()) return;
  const char zeros[2 * kBlock] = {};
  out_.write(zeros, sizeof zeros);
  out_.close();
  if (!out_) throw Error(ErrorCode::kIo, "--out", "'" + path_ + "': write failed");
}

void TarShards::finish() { close_shard(); }

}  // namespace finflex::pictures
