#include "fish_hand_off.hpp"

#include <algorithm>

namespace finflex::pictures {

namespace {

// FinFlex's planes of positions and normals for the renderer: no tangents (not drawn).
OutputLayout drawn_planes(const ClDeformer& deformer, std::size_t instances, NormalFormat format) {
  OutputLayout layout = deformer.layout(instances, format);
  layout.tangents.reset();
  layout.previous_positions.reset();
  return layout;
}

// Bytes of a GL buffer for `attribute`: what the engine checks, and every plane whole
// (what the renderer's StreamLayout::planes over all the slots reads).
std::size_t buffer_bytes(const ClDeformer& deformer, const AttributeLayout& attribute,
                         std::size_t instances) {
  const std::size_t engine = OutputLayout::required_bytes(
      attribute, instances, deformer.output_vertices(VertexOrder::kSlots));
  return std::max(engine, instances * attribute.instance_stride);
}

render::StreamLayout stream_layout(const AttributeLayout& attribute) {
  return render::StreamLayout::planes(attribute.plane_stride,
                                      attribute.format == AttributeFormat::kFloat16x3
                                          ? render::ComponentType::kFloat16
                                          : render::ComponentType::kFloat32);
}

}  // namespace

GlSpeciesOutputs::GlSpeciesOutputs(render::Renderer& renderer, ClDeformer& deformer,
                                   std::size_t instances, NormalFormat format)
    : renderer_(renderer),
      layout_(drawn_planes(deformer, instances, format)),
      positions_(renderer.create_buffer(buffer_bytes(deformer, layout_.positions, instances))),
      normals_(renderer.create_buffer(buffer_bytes(deformer, layout_.normals, instances))),
      position_layout_(stream_layout(layout_.positions)),
      normal_layout_(stream_layout(layout_.normals)),
      instances_(instances),
      // create_buffer left the renderer's context current, as GlOutputs needs.
      outputs_(deformer, instances, layout_,
               GlBuffers{renderer.gl_buffer(positions_), renderer.gl_buffer(normals_), 0, 0}) {}

cl::Event GlSpeciesOutputs::enqueue(ClDeformer& /*deformer: the outputs'*/, const ClJob& job,
                                    std::vector<cl::Event>* kernel_events) {
  renderer_.make_current();
  drawable_ = outputs_.enqueue(job, kernel_events);
  return drawable_;
}

void GlSpeciesOutputs::begin_reading() {
  renderer_.make_current();
  outputs_.begin_reading();
}

void GlSpeciesOutputs::end_reading() { outputs_.end_reading(); }

void GlSpeciesOutputs::wait_until_drawable() {
  if (drawable_() != nullptr) check_cl(drawable_.wait(), "clWaitForEvents");
}

tank::OutputsFactory gl_outputs(render::Renderer& renderer) {
  return [&renderer](std::size_t, ClDeformer& deformer, std::size_t instances,
                     NormalFormat format) -> std::unique_ptr<tank::SpeciesOutputs> {
    return std::make_unique<GlSpeciesOutputs>(renderer, deformer, instances, format);
  };
}

SpeciesDrawing prepare_drawing(render::Renderer& renderer, const ClDeformer& deformer,
                               GlSpeciesOutputs& outputs, const glm::vec3& albedo,
                               std::vector<std::uint32_t> ids) {
  SpeciesDrawing drawing;
  // The triangles over slots; padding slots (never indexed) are vertices too.
  drawing.mesh =
      renderer.add_mesh(deformer.remapped_indices(), outputs.layout().positions.plane_stride);
  drawing.outputs = &outputs;
  drawing.albedo = albedo;
  drawing.ids = std::move(ids);
  return drawing;
}

render::FishDraw fish_draw(const SpeciesDrawing& drawing) {
  const GlSpeciesOutputs& outputs = *drawing.outputs;
  render::FishDraw draw;
  draw.mesh = drawing.mesh;
  draw.albedo = drawing.albedo;
  draw.instance_count = outputs.instance_count();
  draw.positions =
      render::VertexStream::from_buffer(outputs.positions(), outputs.position_layout());
  draw.normals = render::VertexStream::from_buffer(outputs.normals(), outputs.normal_layout());
  draw.ids = drawing.ids.data();
  return draw;
}

}  // namespace finflex::pictures
