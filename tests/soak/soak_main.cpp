// finflex_soak: runs a scene (soak_scene.hpp) for many frames and checks that it can
// run forever: resident memory measured at intervals stays flat after a warm-up,
// and outputs a period apart (identical inputs) are bit-identical on the device.
//
//   finflex_soak --frames 100000 [--species MESH RIG INSTANCES]... [--tank] [--period P]
//                [--digest-every D] [--sample-every S] [--max-growth-mb M]
//                [--normals rotate|jacobian] [--path auto|fused|passes] [--device NAME]
//
// --tank: the species (swim rigs) swim in the tank (tank_scene.hpp) instead of being
// deformed as a rig batch; INSTANCES are their fish.
//
// Prints a line per memory sample and a JSON summary; exit 0 when memory stayed
// within --max-growth-mb of its level after the warm-up (the first tenth of the
// frames, at least two periods) and every digest matched, 2 otherwise (or on an error).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "finflex/finflex.hpp"
#include "resident_memory.hpp"
#include "soak_scene.hpp"
#include "tank_scene.hpp"

namespace finflex::soak {
namespace {

struct Options {
  std::size_t frames = 100000;
  std::size_t period = 1000;
  std::size_t digest_every = 250;
  std::size_t sample_every = 5000;
  double max_growth_mb = 16.0;
  std::vector<RigSpecies> species;
  bool tank = false;
  std::string normals = "jacobian";
  std::string path = "auto";
  std::string device;
};

std::size_t count(const std::string& text, const std::string& option) {
  std::size_t used = 0;
  const unsigned long long value = text.empty() || text[0] == '-' ? 0 : std::stoull(text, &used);
  if (used != text.size() || value == 0) {
    throw Error(ErrorCode::kInvalidArgument, option,
                option + " '" + text + "': expected a count > 0");
  }
  return static_cast<std::size_t>(value);
}

Options parse(int argc, char** argv) {
  Options options;
  auto next = [&](int& k) -> std::string {
    if (k + 1 >= argc) {
      throw Error(ErrorCode::kInvalidArgument, argv[k], std::string(argv[k]) + " needs a value");
    }
    return argv[++k];
  };
  for (int k = 1; k < argc; ++k) {
    const std::string option = argv[k];
    if (option == "--frames") {
      options.frames = count(next(k), option);
    } else if (option == "--period") {
      options.period = count(next(k), option);
    } else if (option == "--digest-every") {
      options.digest_every = count(next(k), option);
    } else if (option == "--sample-every") {
      options.sample_every = count(next(k), option);
    } else if (option == "--max-growth-mb") {
      options.max_growth_mb = std::stod(next(k));
    } else if (option == "--species") {
      RigSpecies species;
      species.mesh = next(k);
      species.rig = next(k);
      species.instances = count(next(k), "--species instances");
      options.species.push_back(species);
    } else if (option == "--tank") {
      options.tank = true;
    } else if (option == "--normals") {
      options.normals = next(k);
    } else if (option == "--path") {
      options.path = next(k);
    } else if (option == "--device") {
      options.device = next(k);
    } else {
      throw Error(ErrorCode::kInvalidArgument, option, "unknown option '" + option + "'");
    }
  }
  if (options.species.empty()) {
    throw Error(ErrorCode::kInvalidArgument, "--species",
                "--species MESH RIG INSTANCES is required");
  }
  return options;
}

double mib(std::size_t bytes) { return double(bytes) / (1024.0 * 1024.0); }

int run(const Options& options) {
  Context context(options.device);
  const NormalMode normals = parse_normal_mode(options.normals, "--normals");
  const auto scene = options.tank
                         ? make_tank_scene(context, options.species, options.period, normals)
                         : make_rig_batch_scene(context, options.species, options.period, normals,
                                                parse_rig_path(options.path, "--path"));
  std::printf("soak: %s on %s, %zu frames, period %zu\n", scene->describe().c_str(),
              context.description().device_name.c_str(), options.frames, options.period);
  const std::size_t warm_up =
      std::max(options.frames / 10, std::min(options.frames, 2 * options.period));
  std::map<std::size_t, std::uint64_t> first_digest;  // by frame modulo the period
  std::size_t digests = 0, compared = 0, mismatches = 0;
  std::size_t baseline = 0, peak = 0, last = 0;
  std::vector<std::pair<std::size_t, std::size_t>> samples;  // (frame, resident bytes)
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t f = 0; f < options.frames; ++f) {
    scene->enqueue(f);
    if (f % options.digest_every == 0) {
      const std::uint64_t digest = scene->digest();
      ++digests;
      const auto [it, first] = first_digest.emplace(f % options.period, digest);
      if (!first) {
        ++compared;
        if (it->second != digest) {
          ++mismatches;
          std::printf("frame %zu: outputs differ from frame %zu's\n", f, f % options.period);
        }
      }
    }
    if ((f + 1) % options.sample_every == 0 || f + 1 == options.frames || f + 1 == warm_up) {
      scene->digest();  // the frames so far are done: their memory is in use
      last = resident_bytes();
      samples.emplace_back(f + 1, last);
      if (f + 1 == warm_up) baseline = last;
      if (f + 1 >= warm_up) peak = std::max(peak, last);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("frame %zu: resident %.1f MiB, %.0f s\n", f + 1, mib(last), seconds);
      std::fflush(stdout);
    }
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double growth = mib(peak) - mib(baseline);
  const bool flat = growth <= options.max_growth_mb;
  std::printf(
      "{\"frames\": %zu, \"seconds\": %.1f, \"frames_per_second\": %.1f, "
      "\"resident_after_warm_up_mib\": %.1f, \"resident_peak_mib\": %.1f, "
      "\"resident_last_mib\": %.1f, \"growth_mib\": %.2f, \"max_growth_mib\": %.1f, "
      "\"digests\": %zu, \"digests_compared\": %zu, \"digest_mismatches\": %zu, "
      "\"flat\": %s}\n",
      options.frames, seconds, double(options.frames) / seconds, mib(baseline), mib(peak),
      mib(last), growth, options.max_growth_mb, digests, compared, mismatches,
      flat ? "true" : "false");
  if (!flat) std::fprintf(stderr, "finflex_soak: resident memory grew by %.1f MiB\n", growth);
  return flat && mismatches == 0 ? 0 : 2;
}

}  // namespace
}  // namespace finflex::soak

int main(int argc, char** argv) {
  try {
    return finflex::soak::run(finflex::soak::parse(argc, argv));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "finflex_soak: error: %s\n", error.what());
    return 2;
  }
}
