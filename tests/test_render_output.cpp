// Frames to files (apps/render): PNG written atomically, the animated PNG decoded
// chunk by chunk with an independent unfilter, MP4 through ffmpeg where it is installed.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <zlib.h>

#include "render/error.hpp"
#include "render/png.hpp"
#include "render/video.hpp"
#include "support/test_support.hpp"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

namespace finflex::render {
namespace {

namespace fs = std::filesystem;

// A frame with smooth gradients, sharp edges and noise, different for each `seed`.
Image test_frame(int width, int height, unsigned seed) {
  Image image{width, height, {}};
  unsigned state = seed * 2654435761u + 1u;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      state = state * 1664525u + 1013904223u;
      image.rgb.push_back(static_cast<std::uint8_t>(x * 255 / width));
      image.rgb.push_back(static_cast<std::uint8_t>((x / 4 + y / 4 + seed) % 2 ? 200 : 40));
      image.rgb.push_back(static_cast<std::uint8_t>(state >> 24));
    }
  }
  return image;
}

std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::uint32_t be32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

struct Chunk {
  std::string type;
  std::vector<std::uint8_t> data;
};

// Every chunk of a PNG file, each CRC checked.
std::vector<Chunk> read_chunks(const std::vector<std::uint8_t>& file) {
  const std::uint8_t signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  EXPECT_TRUE(file.size() >= 8 && std::equal(signature, signature + 8, file.begin()));
  std::vector<Chunk> chunks;
  std::size_t at = 8;
  while (at + 12 <= file.size()) {
    const std::uint32_t length = be32(&file[at]);
    Chunk chunk{std::string(file.begin() + static_cast<long>(at) + 4,
                            file.begin() + static_cast<long>(at) + 8),
                {}};
    chunk.data.assign(file.begin() + static_cast<long>(at) + 8,
                      file.begin() + static_cast<long>(at + 8 + length));
    const auto crc = crc32(0L, &file[at + 4], length + 4);
    EXPECT_EQ(be32(&file[at + 8 + length]), crc) << chunk.type;
    chunks.push_back(std::move(chunk));
    at += 12 + length;
  }
  EXPECT_EQ(at, file.size());
  return chunks;
}

// Inflates and unfilters one 8-bit RGB image (the PNG specification's reconstruction).
Image decode(const std::uint8_t* deflated, std::size_t size, int width, int height) {
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  std::vector<std::uint8_t> filtered(static_cast<std::size_t>(height) * (row + 1));
  uLongf length = static_cast<uLongf>(filtered.size());
  EXPECT_EQ(uncompress(filtered.data(), &length, deflated, static_cast<uLong>(size)), Z_OK);
  EXPECT_EQ(length, filtered.size());
  Image image{width, height, std::vector<std::uint8_t>(row * static_cast<std::size_t>(height))};
  for (std::size_t y = 0; y < static_cast<std::size_t>(height); ++y) {
    const std::uint8_t type = filtered[y * (row + 1)];
    for (std::size_t i = 0; i < row; ++i) {
      const int a = i >= 3 ? image.rgb[y * row + i - 3] : 0;
      const int b = y > 0 ? image.rgb[(y - 1) * row + i] : 0;
      const int c = i >= 3 && y > 0 ? image.rgb[(y - 1) * row + i - 3] : 0;
      const int p = a + b - c;
      const int paeth = std::abs(p - a) <= std::abs(p - b) && std::abs(p - a) <= std::abs(p - c)
                            ? a
                            : (std::abs(p - b) <= std::abs(p - c) ? b : c);
      const int predictions[5] = {0, a, b, (a + b) / 2, paeth};
      EXPECT_LT(type, 5);
      image.rgb[y * row + i] =
          static_cast<std::uint8_t>(filtered[y * (row + 1) + 1 + i] + predictions[type % 5]);
    }
  }
  return image;
}

bool folder_holds_only(const std::string& folder, const std::vector<std::string>& names) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(folder)) {
    found.push_back(entry.path().filename().string());
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> expected = names;
  std::sort(expected.begin(), expected.end());
  return found == expected;
}

TEST(Png, WritesTheImageWhole) {
  const Image image = test_frame(31, 17, 1);
  const std::string path = test::temp_path("frame.png");
  write_png(path, image);
  int width = 0;
  int height = 0;
  int channels = 0;
  unsigned char* pixels = stbi_load(path.c_str(), &width, &height, &channels, 3);
  ASSERT_NE(pixels, nullptr);
  EXPECT_EQ(width, 31);
  EXPECT_EQ(height, 17);
  EXPECT_TRUE(std::equal(image.rgb.begin(), image.rgb.end(), pixels));
  stbi_image_free(pixels);
  EXPECT_TRUE(folder_holds_only(fs::path(path).parent_path().string(), {"frame.png"}));
}

TEST(Png, MissingFolderIsAnIoErrorAndWritesNothing) {
  const std::string path = test::temp_path("missing/frame.png");
  try {
    write_png(path, test_frame(4, 4, 0));
    FAIL() << "no error";
  } catch (const RenderError& error) {
    EXPECT_EQ(error.code(), ErrorCode::kIo);
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(path));
  Image bad = test_frame(4, 4, 0);
  bad.rgb.pop_back();
  EXPECT_THROW(write_png(test::temp_path("bad.png"), bad), RenderError);
}

TEST(Apng, HoldsEveryFrameInOrder) {
  const int width = 40;
  const int height = 24;
  const std::vector<Image> frames = {test_frame(width, height, 1), test_frame(width, height, 2),
                                     test_frame(width, height, 3)};
  const std::string path = test::temp_path("swim.png");
  VideoOptions options;
  options.width = width;
  options.height = height;
  options.fps = 25;
  std::unique_ptr<VideoWriter> writer = open_video(path, options);
  for (const Image& frame : frames) writer->add_frame(frame);
  EXPECT_FALSE(fs::exists(path)) << "visible before finish()";
  writer->finish();
  EXPECT_EQ(writer->frame_count(), 3u);

  const std::vector<Chunk> chunks = read_chunks(read_bytes(path));
  std::vector<std::string> types;
  for (const Chunk& chunk : chunks) types.push_back(chunk.type);
  EXPECT_EQ(types, (std::vector<std::string>{"IHDR", "acTL", "sRGB", "fcTL", "IDAT", "fcTL", "fdAT",
                                             "fcTL", "fdAT", "IEND"}));
  ASSERT_EQ(chunks.size(), 10u);
  EXPECT_EQ(be32(&chunks[1].data[0]), 3u);  // frames
  EXPECT_EQ(be32(&chunks[1].data[4]), 0u);  // plays forever
  std::vector<std::uint32_t> sequence;
  std::vector<Image> decoded;
  for (const Chunk& chunk : chunks) {
    if (chunk.type == "fcTL") {
      sequence.push_back(be32(&chunk.data[0]));
      EXPECT_EQ(be32(&chunk.data[4]), static_cast<std::uint32_t>(width));
      EXPECT_EQ(chunk.data[20] << 8 | chunk.data[21], 1);  // delay 1 / 25 s
      EXPECT_EQ(chunk.data[22] << 8 | chunk.data[23], 25);
    }
    if (chunk.type == "IDAT")
      decoded.push_back(decode(chunk.data.data(), chunk.data.size(), width, height));
    if (chunk.type == "fdAT") {
      sequence.push_back(be32(&chunk.data[0]));
      decoded.push_back(decode(chunk.data.data() + 4, chunk.data.size() - 4, width, height));
    }
  }
  EXPECT_EQ(sequence, (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  ASSERT_EQ(decoded.size(), frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) EXPECT_EQ(decoded[i].rgb, frames[i].rgb) << i;

  // Viewers without APNG show the first frame.
  int w = 0;
  int h = 0;
  int channels = 0;
  unsigned char* still = stbi_load(path.c_str(), &w, &h, &channels, 3);
  ASSERT_NE(still, nullptr);
  EXPECT_TRUE(std::equal(frames[0].rgb.begin(), frames[0].rgb.end(), still));
  stbi_image_free(still);
  EXPECT_TRUE(folder_holds_only(fs::path(path).parent_path().string(), {"swim.png"}));
}

TEST(Apng, UnfinishedOrWrongFramesLeaveNoFile) {
  const std::string path = test::temp_path("swim.apng");
  VideoOptions options;
  options.width = 8;
  options.height = 8;
  {
    std::unique_ptr<VideoWriter> writer = open_video(path, options);
    writer->add_frame(test_frame(8, 8, 0));
    try {
      writer->add_frame(test_frame(8, 9, 0));
      ADD_FAILURE() << "a frame of another size was accepted";
    } catch (const RenderError& error) {
      EXPECT_EQ(error.code(), ErrorCode::kInvalidArgument);
    }
  }
  EXPECT_TRUE(folder_holds_only(fs::path(path).parent_path().string(), {}));
  EXPECT_THROW(open_video(test::temp_path("swim.avi"), options), RenderError);
  options.fps = 0;
  EXPECT_THROW(open_video(test::temp_path("swim.png"), options), RenderError);
}

TEST(Mp4, ThroughFfmpegWhenInstalled) {
  EXPECT_EQ(default_video_path("tank"), ffmpeg_available() ? "tank.mp4" : "tank.png");
  if (!ffmpeg_available()) GTEST_SKIP() << "ffmpeg is not installed";
  const std::string path = test::temp_path("swim.mp4");
  VideoOptions options;
  options.width = 65;  // odd: padded to even for 4:2:0
  options.height = 48;
  std::unique_ptr<VideoWriter> writer = open_video(path, options);
  for (unsigned i = 0; i < 12; ++i) writer->add_frame(test_frame(65, 48, i));
  writer->finish();
  const std::vector<std::uint8_t> file = read_bytes(path);
  ASSERT_GT(file.size(), 100u);
  EXPECT_EQ(std::string(file.begin() + 4, file.begin() + 8), "ftyp");
  EXPECT_TRUE(folder_holds_only(fs::path(path).parent_path().string(), {"swim.mp4"}));
}

TEST(Gif, ThroughFfmpegWhenInstalled) {
  if (!ffmpeg_available()) GTEST_SKIP() << "ffmpeg is not installed";
  const std::string path = test::temp_path("swim.gif");
  VideoOptions options;
  options.width = 64;
  options.height = 48;
  options.fps = 10;
  std::unique_ptr<VideoWriter> writer = open_video(path, options);
  for (unsigned i = 0; i < 6; ++i) writer->add_frame(test_frame(64, 48, i));
  writer->finish();
  const std::vector<std::uint8_t> file = read_bytes(path);
  ASSERT_GT(file.size(), 100u);
  EXPECT_EQ(std::string(file.begin(), file.begin() + 6), "GIF89a");
  // The logical screen is the frames' size (little-endian), and it loops (NETSCAPE2.0).
  EXPECT_EQ(file[6] | (file[7] << 8), 64);
  EXPECT_EQ(file[8] | (file[9] << 8), 48);
  EXPECT_NE(std::string(file.begin(), file.end()).find("NETSCAPE2.0"), std::string::npos);
  EXPECT_TRUE(folder_holds_only(fs::path(path).parent_path().string(), {"swim.gif"}));
  // Wider frames are scaled down to gif_width, the aspect kept.
  const std::string preview = test::temp_path("preview.gif");
  options.width = 800;
  options.height = 450;
  writer = open_video(preview, options);
  for (unsigned i = 0; i < 3; ++i) writer->add_frame(test_frame(800, 450, i));
  writer->finish();
  const std::vector<std::uint8_t> scaled = read_bytes(preview);
  ASSERT_GT(scaled.size(), 10u);
  EXPECT_EQ(scaled[6] | (scaled[7] << 8), 400);
  EXPECT_EQ(scaled[8] | (scaled[9] << 8), 225);
}

// PATH led by a folder holding a stand-in `ffmpeg` script, for one scope.
class FakeFfmpeg {
 public:
  explicit FakeFfmpeg(const std::string& script) {
    const std::string program = test::temp_path("ffmpeg");
    std::ofstream(program) << "#!/bin/sh\n" << script;
    fs::permissions(program, fs::perms::owner_all);
    const char* path = std::getenv("PATH");
    saved_ = path != nullptr ? path : "";
    setenv("PATH", (fs::path(program).parent_path().string() + ":" + saved_).c_str(), 1);
  }
  ~FakeFfmpeg() { setenv("PATH", saved_.c_str(), 1); }

 private:
  std::string saved_;
};

TEST(Mp4, FfmpegFailingIsAnIoErrorWithItsLastLine) {
  VideoOptions options;
  options.width = 64;
  options.height = 48;
  const std::string path = test::temp_path("swim.mp4");
  {
    const FakeFfmpeg fake("cat > /dev/null\necho \"Unknown encoder 'libx264'\" >&2\nexit 1\n");
    std::unique_ptr<VideoWriter> writer = open_video(path, options);
    writer->add_frame(test_frame(64, 48, 0));
    try {
      writer->finish();
      ADD_FAILURE() << "no error";
    } catch (const RenderError& error) {
      EXPECT_EQ(error.code(), ErrorCode::kIo);
      EXPECT_NE(std::string(error.what()).find("exit status 1): Unknown encoder"),
                std::string::npos)
          << error.what();
    }
  }
  {
    // Exits without reading: the frames cannot be sent (no SIGPIPE kills the test).
    const FakeFfmpeg fake("echo 'cannot open' >&2\nexit 1\n");
    std::unique_ptr<VideoWriter> writer = open_video(path, options);
    try {
      for (unsigned i = 0; i < 10000; ++i) writer->add_frame(test_frame(64, 48, i));
      ADD_FAILURE() << "no error";
    } catch (const RenderError& error) {
      EXPECT_EQ(error.code(), ErrorCode::kIo);
      EXPECT_NE(std::string(error.what()).find("stopped reading frames: cannot open"),
                std::string::npos)
          << error.what();
    }
  }
  EXPECT_TRUE(folder_holds_only(fs::path(path).parent_path().string(), {}));
}

}  // namespace
}  // namespace finflex::render
