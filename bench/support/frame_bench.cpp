#include "frame_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>

#include "huge_page_settings.hpp"
#include "reference_kernels.hpp"

namespace finflex::bench {
namespace {

// The write-only kernel of a shape through the batch's layout.
cl::Event enqueue_write_only(Context& context, DeviceBatch& batch, std::size_t vertices,
                             const WriteOnlyShape& shape) {
  return enqueue_write_only(context, batch, vertices, shape.per_item, WriteValues::kDeviceDefault,
                            shape.lanes, shape.streaming);
}

// Frames whose kernels are waited for, then mapped for the host and timed: on CPU
// devices the kernels wrote the caller's memory (no copy), on GPUs the driver copies
// the frame into it.
std::vector<double> time_host_maps(ClDeformer& deformer, ClJob& job, std::size_t frames) {
  std::vector<double> seconds;
  for (std::size_t f = 0; f <= frames; ++f) {
    std::vector<cl::Event> events;
    deformer.enqueue(job, &events);
    check_cl(cl::Event::waitForEvents(events), "clWaitForEvents");
    const auto start = std::chrono::steady_clock::now();
    deformer.map_host(*job.outputs);
    const auto end = std::chrono::steady_clock::now();
    if (f > 0) seconds.push_back(std::chrono::duration<double>(end - start).count());
  }
  deformer.unmap_host(*job.outputs);
  return seconds;
}

}  // namespace

bool frames_ahead(Context& context) { return context.description().is_gpu(); }

WriteOnlyShape fastest_write_only(Context& context, DeviceBatch& batch, std::size_t vertices,
                                  const KernelShape& deformer, std::size_t frames) {
  std::vector<WriteOnlyShape> shapes;
  const std::size_t lanes = deformer.lanes;
  for (std::size_t per : {deformer.instances_per_item, std::size_t{4}}) {
    shapes.push_back({per, 1, false, 0.0});
    if (lanes > 1) shapes.insert(shapes.end(), {{per, lanes, true, 0.0}, {per, lanes, false, 0.0}});
  }
  WriteOnlyShape fastest;
  for (WriteOnlyShape& shape : shapes) {
    const FrameTimes times = time_frames(
        frames, [](std::size_t) {},
        [&](std::vector<cl::Event>& events) {
          events.assign(1, enqueue_write_only(context, batch, vertices, shape));
        },
        frames_ahead(context));
    shape.seconds = median(times.device);
    if (fastest.seconds == 0.0 || shape.seconds < fastest.seconds) fastest = shape;
  }
  return fastest;
}

std::function<cl::Event()> write_reference(Context& context, DeviceBatch& batch,
                                           std::size_t vertices, const WriteOnlyShape& shape) {
  if (frames_ahead(context)) return {};
  return [&context, &batch, vertices, shape] {
    return enqueue_write_only(context, batch, vertices, shape);
  };
}

void set_parameters(RigParameters& values,
                    const std::function<float(std::size_t, std::size_t, std::size_t)>& value) {
  const std::vector<RigParameter>& parameters = values.parameters();
  for (std::size_t i = 0; i < values.instance_count(); ++i) {
    for (std::size_t p = 0; p < parameters.size(); ++p) {
      const RigParameter& parameter = parameters[p];
      for (std::size_t k = 0; k < parameter.count; ++k) {
        values.values()[i * values.values_per_instance() + parameter.offset + k] = value(i, p, k);
      }
    }
  }
}

void animate_parameters(RigParameters& values, std::size_t frame) {
  const double f = double(frame);
  const std::vector<RigParameter>& parameters = values.parameters();
  set_parameters(values, [&parameters, f](std::size_t i, std::size_t p, std::size_t k) {
    const RigParameter& parameter = parameters[p];
    if (parameter.count == 1) {
      return static_cast<float>(0.5 * parameter.limit *
                                std::sin(0.05 * f + 0.1 * double(i) + double(p)));
    }
    return static_cast<float>(
        0.3 * std::sin(6.0 * double(k) / double(parameter.count) - 0.2 * f + 0.1 * double(i)));
  });
}

ClJob frame_job(const RigParameters& values, DeviceBatch& batch, NormalMode normals, RigPath path) {
  ClJob job;
  job.instances = values.instance_count();
  job.parameters = values.view();
  job.normals = normals;
  job.path = path;
  job.outputs = &batch;
  return job;
}

Measured measure_deform(Context& context, const RiggedMesh& model, const std::string& bend,
                        const FrameBenchSettings& settings, DeformBench& bench) {
  const std::size_t instances = settings.instances;
  bench.deformer = std::make_unique<ClDeformer>(context, model, settings.options);
  ClDeformer& deformer = *bench.deformer;
  const BenchLayout layout = bench_layout(deformer, settings.format, settings.outputs);
  bench.batch = make_bench_batch(deformer, instances, layout, bench.host);
  RigParameters values(model, instances);
  ClJob job = frame_job(values, bench.batch, settings.normals, settings.path);
  Measured measured;
  measured.passes = pass_report(deformer, settings.path);
  measured.shape = kernel_shape(deformer, bench.batch, settings.normals);
  measured.write_only =
      fastest_write_only(context, bench.batch, layout.vertices, measured.shape, settings.frames);
  measured.times = time_frames(
      settings.frames, [&](std::size_t f) { animate_parameters(values, f); },
      [&](std::vector<cl::Event>& events) { deformer.enqueue(job, &events); },
      frames_ahead(context),
      write_reference(context, bench.batch, layout.vertices, measured.write_only));
  if (settings.outputs.host) {
    measured.host_map_seconds = time_host_maps(deformer, job, settings.frames);
  }
  const RigPath chosen =
      settings.path == RigPath::kAuto ? deformer.automatic_path() : settings.path;
  measured.what = bend.empty() ? std::string("rig ") + to_string(chosen) : "bend " + bend;
  measured.batch = &bench.batch;
  measured.vertices = model.mesh().vertex_count();
  measured.output_vertices = layout.vertices;
  measured.bytes_per_vertex = layout.layout.bytes_per_vertex();
  return measured;
}

nlohmann::ordered_json frame_bench_record(Context& context, const std::string& mesh,
                                          const FrameBenchSettings& settings, const Measured& m) {
  const std::size_t instances = settings.instances;
  const double seconds = median(m.times.device);
  // The write-only kernel's fastest shape timed on its own, and (CPUs) each frame's
  // own ratio to that shape run right after it.
  const double write_seconds = m.write_only.seconds;
  std::vector<double> frame_fractions;
  for (std::size_t f = 0; f < m.times.reference.size(); ++f) {
    frame_fractions.push_back(m.times.reference[f] / m.times.device[f]);
  }
  const double vertices = double(m.vertices) * double(instances);
  const BatchShape& layout = m.batch->shape;
  const double bytes_per_vertex = double(m.bytes_per_vertex);
  const double written = double(m.output_vertices) * double(instances) * bytes_per_vertex;

  nlohmann::ordered_json result;
  result["device"] = context.description().device_name;
  result["mesh"] = mesh;
  result["deformation"] = m.what;
  result["normals"] = to_string(settings.normals);
  result["normal_format"] = to_string(settings.format);
  result["layout"] = to_string(settings.outputs.layout);
  result["order"] = to_string(settings.outputs.order);
  result["previous_positions"] = settings.outputs.previous;
  result["vertices"] = m.vertices;
  result["instances"] = instances;
  result["frames"] = settings.frames;
  result["passes"] = m.passes.passes;
  result["seconds_per_frame_median"] = seconds;
  result["seconds_per_frame_min"] = *std::min_element(m.times.device.begin(), m.times.device.end());
  result["vertices_per_second"] = vertices / seconds;
  result["output_bytes_per_second"] = written / seconds;
  // Multi-pass: intermediate results go through float32 scratch sets (12 B per
  // attribute each way).
  const double scratch_record_bytes = 12.0 * (layout.tangents ? 3.0 : 2.0);
  result["moved_bytes_per_vertex"] =
      bytes_per_vertex + scratch_record_bytes * m.passes.scratch_records_per_slot;
  result["write_bandwidth_bytes_per_second"] = written / write_seconds;
  result["write_fraction"] = write_seconds / seconds;
  result["write_fraction_interleaved"] = nullptr;
  if (!frame_fractions.empty()) {
    result["write_fraction_interleaved"] = median(frame_fractions);
  }
  result["host_enqueue_seconds_median"] = median(m.times.host);
  if (m.swim) {
    result["host_driver_seconds_median"] = median(m.host_driver_seconds);
    result["swim_inputs"] = settings.recorded_swim_inputs ? "recorded" : "live";
  }
  result["host_outputs"] = settings.outputs.host;
  if (settings.outputs.host) {
    const double map_seconds = median(m.host_map_seconds);
    result["host_map_seconds_median"] = map_seconds;
    result["host_map_bytes_per_second"] = written / map_seconds;
  }
  // Each kernel of a frame, in launch order (swim: the driver, rig_prepare, then the
  // deformation's).
  result["kernel_seconds_median"] = m.times.kernel_medians();
  result["instances_per_item"] = m.shape.instances_per_item;
  result["lanes"] = m.shape.lanes;
  result["streaming_stores"] = m.shape.streaming;
  result["frames_ahead"] = frames_ahead(context);
  // What puts the host's memory in huge pages (CPU devices' buffers are host memory),
  // and how much of it the process holds in them after the frames.
  const std::optional<std::uint64_t> huge_bytes = process_huge_page_bytes();
  result["huge_pages"] = {
      {"transparent", transparent_huge_pages()},
      {"glibc_malloc_hugetlb", glibc_malloc_hugetlb()},
      {"process_bytes", huge_bytes ? nlohmann::ordered_json(*huge_bytes) : nullptr}};
  return result;
}

}  // namespace finflex::bench
