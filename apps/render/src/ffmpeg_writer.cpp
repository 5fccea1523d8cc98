#include "ffmpeg_writer.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <vector>

#include "render/error.hpp"

extern char** environ;

namespace finflex::render::detail {

namespace {

std::string last_line(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

void append(std::vector<std::string>& arguments, std::initializer_list<std::string> more) {
  arguments.insert(arguments.end(), more);
}

std::vector<std::string> ffmpeg_arguments(const VideoOptions& options, FfmpegFormat format,
                                          const std::string& output) {
  const std::string size = std::to_string(options.width) + "x" + std::to_string(options.height);
  std::vector<std::string> arguments = {"ffmpeg", "-hide_banner", "-loglevel", "error", "-y"};
  // input: raw frames on standard input
  append(arguments, {"-f", "rawvideo", "-pix_fmt", "rgb24", "-s", size});
  append(arguments, {"-framerate", std::to_string(options.fps), "-i", "pipe:0"});
  if (format == FfmpegFormat::kGif) {
    // scaled down to gif_width; one palette for the clip, from every frame;
    // error-diffusion dithering (Sierra-2-4A)
    std::string filter;
    if (options.gif_width > 0) {
      filter = "scale=w='min(" + std::to_string(options.gif_width) + ",iw)':h=-1:flags=lanczos,";
    }
    filter += "split[a][b];[a]palettegen=max_colors=" + std::to_string(options.gif_colours) +
              ":stats_mode=full[p];[b][p]paletteuse=dither=sierra2_4a";
    append(arguments, {"-vf", filter, "-loop", "0", "-f", "gif", output});
    return arguments;
  }
  // even sizes for 4:2:0, BT.709 limited range, tagged as sRGB transfer
  append(arguments, {"-vf",
                     "pad=ceil(iw/2)*2:ceil(ih/2)*2,scale=out_color_matrix=bt709:"
                     "out_range=tv,format=yuv420p"});
  append(arguments, {"-colorspace", "bt709", "-color_primaries", "bt709"});
  append(arguments, {"-color_trc", "iec61966-2-1", "-color_range", "tv"});
  append(arguments, {"-c:v", "libx264", "-preset", options.preset});
  append(arguments, {"-crf", std::to_string(options.crf), "-movflags", "+faststart"});
  append(arguments, {"-f", "mp4", output});
  return arguments;
}

}  // namespace

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    const std::string candidate = (folder.empty() ? "." : folder) + "/" + program;
    struct stat info {};
    if (stat(candidate.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
        access(candidate.c_str(), X_OK) == 0) {
      return true;
    }
  }
  return false;
}

FfmpegWriter::FfmpegWriter(const std::string& path, const VideoOptions& options,
                           FfmpegFormat format)
    : file_(path), log_(path + ".log"), options_(options) {
  options_.validate();
  int sockets[2];
  if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sockets) != 0) {
    fail(std::string("cannot make a socket for ffmpeg (") + std::strerror(errno) + ")");
  }
  input_ = sockets[0];
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, sockets[1], 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, log_.descriptor(), 2);
  const std::vector<std::string> arguments = ffmpeg_arguments(options_, format, file_.path());
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  const int status = posix_spawnp(&child_, "ffmpeg", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(sockets[1]);
  if (status != 0) {
    child_ = -1;
    fail(std::string("cannot start ffmpeg (") + std::strerror(status) + ")");
  }
}

FfmpegWriter::~FfmpegWriter() { stop(); }

int FfmpegWriter::stop() {
  if (input_ >= 0) {
    close(input_);
    input_ = -1;
  }
  if (child_ < 0) return -1;
  int status = 0;
  while (waitpid(child_, &status, 0) < 0 && errno == EINTR) {
  }
  child_ = -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

void FfmpegWriter::fail(const std::string& what) {
  stop();
  const std::string reason = last_line(log_.path());
  throw RenderError(ErrorCode::kIo, path(),
                    "\"" + path() + "\": " + what + (reason.empty() ? "" : ": " + reason));
}

void FfmpegWriter::add_frame(const Image& frame) {
  options_.check_frame(frame);
  if (input_ < 0) throw RenderError(ErrorCode::kInvalidArgument, "frame", "the video is finished");
  const auto* next = frame.rgb.data();
  std::size_t left = frame.rgb.size();
  while (left > 0) {
    const ssize_t sent = send(input_, next, left, MSG_NOSIGNAL);
    if (sent < 0 && errno == EINTR) continue;
    if (sent <= 0) fail("ffmpeg stopped reading frames");
    next += sent;
    left -= static_cast<std::size_t>(sent);
  }
  ++frames_;
}

void FfmpegWriter::finish() {
  if (frames_ == 0)
    throw RenderError(ErrorCode::kInvalidArgument, "frames", "a video needs a frame");
  const int status = stop();
  if (status != 0) fail("ffmpeg failed (exit status " + std::to_string(status) + ")");
  file_.commit();
  log_.discard();
}

}  // namespace finflex::render::detail
