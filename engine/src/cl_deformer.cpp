#include "finflex/cl_deformer.hpp"

#include <string>

#include "device_batch.hpp"
#include "finflex/error.hpp"

namespace finflex {
namespace {

cl_float4 to_cl_float4(const glm::dvec3& v) {
  cl_float4 out;
  out.s[0] = static_cast<float>(v.x);
  out.s[1] = static_cast<float>(v.y);
  out.s[2] = static_cast<float>(v.z);
  out.s[3] = 0.0f;
  return out;
}

// Rest planes px py pz nx ny nz [tx ty tz], padding vertices at the origin with normal e_z.
std::vector<float> rest_planes(const LocalMesh& mesh, std::size_t stride) {
  const std::size_t planes = mesh.has_tangents() ? 9 : 6;
  std::vector<float> data(planes * stride, 0.0f);
  for (std::size_t v = mesh.vertex_count(); v < stride; ++v) data[5 * stride + v] = 1.0f;
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    for (int c = 0; c < 3; ++c) {
      data[c * stride + v] = static_cast<float>(mesh.positions[v][c]);
      data[(3 + c) * stride + v] = static_cast<float>(mesh.normals[v][c]);
      if (mesh.has_tangents()) data[(6 + c) * stride + v] = static_cast<float>(mesh.tangents[v][c]);
    }
  }
  return data;
}

}  // namespace

std::string bend_build_options(const BendSettings& settings, bool tangents, NormalFormat format,
                               std::size_t instances_per_item) {
  return std::string("-DFF_BEND_EXACT=") + (settings.mode == BendMode::kExact ? "1" : "0") +
         " -DFF_NORMALS_JACOBIAN=" + (settings.normals == NormalMode::kJacobian ? "1" : "0") +
         " -DFF_TANGENTS=" + (tangents ? "1" : "0") +
         " -DFF_HALF_NORMALS=" + (format == NormalFormat::kHalf ? "1" : "0") +
         " -DFF_INSTANCES_PER_ITEM=" + std::to_string(instances_per_item);
}

std::size_t instances_per_work_item(const DeviceDescription& device, NormalFormat format) {
  if (device.type != "GPU") return 1;
  return format == NormalFormat::kHalf ? 4 : 2;
}

namespace {

// NDRange of the batch kernels: (plane_stride, ceil(instances / per_item)).
cl::NDRange batch_range(const BatchLayout& layout, std::size_t per_item) {
  return cl::NDRange(layout.plane_stride, (layout.instance_count + per_item - 1) / per_item);
}

}  // namespace

cl::Event enqueue_write_only(Context& context, DeviceBatch& batch, std::size_t instances_per_item,
                             WriteValues values) {
  const std::size_t per_item =
      instances_per_item
          ? instances_per_item
          : instances_per_work_item(context.description(), batch.layout.normal_format);
  if (values == WriteValues::kDeviceDefault) {
    values = context.description().type == "GPU" ? WriteValues::kVarying : WriteValues::kConstant;
  }
  const std::string options =
      std::string("-DFF_INSTANCES_PER_ITEM=") + std::to_string(per_item) +
      (batch.layout.normal_format == NormalFormat::kHalf ? " -DFF_HALF_NORMALS=1" : "") +
      (values == WriteValues::kVarying ? " -DFF_VARYING_WRITES=1" : "") +
      (batch.layout.tangents ? " -DFF_TANGENTS=1" : "");
  cl::Kernel kernel = context.kernel("write_planes", ProgramSource::bend_batch(), options);
  check_cl(kernel.setArg(0, batch.positions), "clSetKernelArg write_planes");
  check_cl(kernel.setArg(1, batch.normals), "clSetKernelArg write_planes");
  check_cl(kernel.setArg(2, batch.tangents), "clSetKernelArg write_planes");
  check_cl(kernel.setArg(3, static_cast<cl_uint>(batch.layout.plane_stride)), "clSetKernelArg");
  check_cl(kernel.setArg(4, static_cast<cl_uint>(batch.layout.instance_count)), "clSetKernelArg");
  check_cl(kernel.setArg(5, 1.0f), "clSetKernelArg write_planes");
  cl::Event done;
  check_cl(context.queue().enqueueNDRangeKernel(
               kernel, cl::NullRange, batch_range(batch.layout, per_item),
               cl::NDRange(ClDeformer::kLocalSize, 1), nullptr, &done),
           "clEnqueueNDRangeKernel write_planes");
  return done;
}

ClDeformer::ClDeformer(Context& context, const LocalMesh& mesh, std::size_t instances_per_item)
    : context_(context),
      mesh_(mesh),
      plane_stride_(padded_plane_stride(mesh.vertex_count())),
      instances_per_item_(instances_per_item) {
  static_assert(64 % kLocalSize == 0, "plane_stride must be a multiple of the work-group size");
  if (plane_stride_ > 0xffffffffu) {
    throw Error(ErrorCode::kInvalidMesh, "positions", "the mesh has more than 2^32 vertices");
  }
  std::vector<float> planes = rest_planes(mesh_, plane_stride_);
  rest_ = detail::make_buffer(context_.context(), CL_MEM_READ_ONLY, planes.size() * sizeof(float),
                              planes.data());
  const BodyFrame& f = mesh_.frame;
  back_transform_ = {to_cl_float4(f.origin),
                     to_cl_float4(f.axis_x * f.length),
                     to_cl_float4(f.axis_y * f.length),
                     to_cl_float4(f.axis_z * f.length),
                     to_cl_float4(f.axis_x),
                     to_cl_float4(f.axis_y),
                     to_cl_float4(f.axis_z)};
}

BatchLayout ClDeformer::layout(std::size_t instances, NormalFormat format) const {
  BatchLayout layout;
  layout.normal_format = format;
  layout.vertex_count = mesh_.vertex_count();
  layout.instance_count = instances;
  layout.plane_stride = plane_stride_;
  layout.tangents = mesh_.has_tangents();
  return layout;
}

DeviceBatch ClDeformer::allocate(std::size_t instances, NormalFormat format) const {
  return detail::allocate_batch(context_, layout(instances, format), 1);
}

cl::Event ClDeformer::enqueue(const std::vector<float>& m, const BendSettings& settings,
                              DeviceBatch& batch, bool clamp, const std::vector<cl::Event>* wait) {
  if (m.size() != batch.layout.instance_count) {
    throw Error(ErrorCode::kInvalidArgument, "m",
                "m has " + std::to_string(m.size()) + " values for a batch of " +
                    std::to_string(batch.layout.instance_count) + " instances");
  }
  std::vector<float>& staged = detail::next_staging(batch);
  check_bend_params_into(m, mesh_.x_max, clamp, staged);
  detail::upload_parameters(context_, batch, staged, wait);

  cl::CommandQueue& queue = context_.queue();

  BoundKernel& bound = bend_kernel(settings, batch.layout.normal_format);
  cl::Kernel& kernel = bound.kernel;
  if (!bound.bound_to(batch)) {
    cl_uint arg = 0;
    check_cl(kernel.setArg(arg++, rest_), "clSetKernelArg rest");
    check_cl(kernel.setArg(arg++, batch.parameters), "clSetKernelArg m");
    check_cl(kernel.setArg(arg++, batch.positions), "clSetKernelArg out_positions");
    check_cl(kernel.setArg(arg++, batch.normals), "clSetKernelArg out_normals");
    check_cl(kernel.setArg(arg++, batch.tangents), "clSetKernelArg out_tangents");
    check_cl(kernel.setArg(arg++, static_cast<cl_uint>(plane_stride_)), "clSetKernelArg stride");
    check_cl(kernel.setArg(arg++, static_cast<cl_uint>(batch.layout.instance_count)),
             "clSetKernelArg instances");
    for (const cl_float4& value : back_transform_) {
      check_cl(kernel.setArg(arg++, value), "clSetKernelArg back transform");
    }
    bound.mark_bound(batch);
  }
  cl::Event done;
  check_cl(
      queue.enqueueNDRangeKernel(kernel, cl::NullRange,
                                 batch_range(batch.layout, per_item(batch.layout.normal_format)),
                                 cl::NDRange(kLocalSize, 1), nullptr, &done),
      "clEnqueueNDRangeKernel bend_batch");
  detail::staging_used(batch, done);
  return done;
}

std::size_t ClDeformer::per_item(NormalFormat format) const {
  return instances_per_item_ ? instances_per_item_
                             : instances_per_work_item(context_.description(), format);
}

BoundKernel& ClDeformer::bend_kernel(const BendSettings& settings, NormalFormat format) {
  const auto key = std::make_tuple(settings.mode, settings.normals, format);
  auto found = kernels_.find(key);
  if (found == kernels_.end()) {
    const std::string options =
        bend_build_options(settings, mesh_.has_tangents(), format, per_item(format));
    found = kernels_
                .emplace(key, BoundKernel{context_.kernel("bend_batch", ProgramSource::bend_batch(),
                                                          options)})
                .first;
  }
  return found->second;
}

DeformedBatch<float> ClDeformer::read(const DeviceBatch& batch) {
  return detail::read_batch(context_, batch);
}

}  // namespace finflex
