#include "tank_pictures.hpp"

#include <string>

namespace finflex::pictures {

namespace {

// Per species, the id of each of its instances: 1 + the fish's index in the tank (the
// tank lists every species' fish; species s's instances are its fish in that order).
std::vector<std::vector<std::uint32_t>> instance_ids(const tank::Tank& tank,
                                                     std::size_t species_count) {
  std::vector<std::vector<std::uint32_t>> ids(species_count);
  const std::vector<tank::Fish>& fish = tank.fish();
  for (std::size_t i = 0; i < fish.size(); ++i) {
    ids[fish[i].species].push_back(static_cast<std::uint32_t>(i + 1));
  }
  return ids;
}

}  // namespace

render::RenderSettings render_settings(const PictureSettings& settings) {
  render::RenderSettings out;
  out.width = settings.width;
  out.height = settings.height;
  out.samples = settings.samples;
  return out;
}

TankPictures::TankPictures(render::Renderer& renderer, tank::SwimScene& scene,
                           const PictureSettings& settings)
    : renderer_(renderer),
      look_(tank_scene(scene.tank().settings())),
      camera_(
          tank_camera(scene.tank().settings(), settings.view, settings.width, settings.height)) {
  std::vector<std::vector<std::uint32_t>> ids = instance_ids(scene.tank(), scene.species().size());
  for (std::size_t s = 0; s < scene.species().size(); ++s) {
    tank::Species& species = scene.species()[s];
    if (!species.deformer) continue;
    auto* outputs = dynamic_cast<GlSpeciesOutputs*>(species.outputs.get());
    if (outputs == nullptr) {
      throw Error(ErrorCode::kInvalidArgument, "scene",
                  "scene: species " + std::to_string(s) +
                      " does not write GL buffers of the renderer (make the scene with "
                      "gl_outputs(renderer))");
    }
    path_ = outputs->path();
    if (!outputs->device_ordered() && device_ordered_) {
      device_ordered_ = false;
      why_not_ordered_ = outputs->why_not_device_ordered();
    }
    drawings_.push_back(prepare_drawing(renderer_, *species.deformer, *outputs,
                                        species_albedo(species.name, s), std::move(ids[s])));
  }
  for (const SpeciesDrawing& drawing : drawings_) draws_.push_back(fish_draw(drawing));
}

void TankPictures::draw() {
  for (SpeciesDrawing& drawing : drawings_) drawing.outputs->wait_until_drawable();
  renderer_.render(look_, camera_, draws_);
}

void TankPictures::draw_reference() { renderer_.render_reference(look_, camera_, draws_); }

const render::Image& TankPictures::read_image() {
  renderer_.read_image(image_);
  return image_;
}

const render::IdImage& TankPictures::draw_ids() {
  renderer_.render_ids(look_, camera_, draws_);
  renderer_.read_ids(ids_);
  return ids_;
}

void TankPictures::request_ids() {
  renderer_.render_ids(look_, camera_, draws_);
  renderer_.request_ids();
}

}  // namespace finflex::pictures
