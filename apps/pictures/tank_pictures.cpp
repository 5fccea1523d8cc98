#include "tank_pictures.hpp"

namespace finflex::pictures {

namespace {

render::RenderSettings render_settings(const PictureSettings& settings) {
  render::RenderSettings out;
  out.width = settings.width;
  out.height = settings.height;
  out.samples = settings.samples;
  return out;
}

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

TankPictures::TankPictures(tank::SwimScene& scene, const PictureSettings& settings)
    : scene_(scene),
      renderer_(render_settings(settings)),
      look_(tank_scene(scene.tank().settings())),
      camera_(
          tank_camera(scene.tank().settings(), settings.view, settings.width, settings.height)) {
  std::vector<std::vector<std::uint32_t>> ids = instance_ids(scene.tank(), scene.species().size());
  for (std::size_t s = 0; s < scene.species().size(); ++s) {
    tank::Species& species = scene.species()[s];
    if (!species.deformer) continue;
    drawings_.push_back(prepare_drawing(renderer_, *species.deformer, species.batch,
                                        species_albedo(species.name, s), std::move(ids[s])));
    species_of_drawing_.push_back(s);
  }
}

void TankPictures::hand_off() {
  draws_.clear();
  for (std::size_t d = 0; d < drawings_.size(); ++d) {
    tank::Species& species = scene_.species()[species_of_drawing_[d]];
    draws_.push_back(pictures::hand_off(species.deformer->context().queue(), species.batch,
                                        renderer_, drawings_[d]));
  }
}

void TankPictures::draw() {
  renderer_.render(look_, camera_, draws_);
  renderer_.finish();
}

const render::Image& TankPictures::read_image() {
  renderer_.read_image(image_);
  return image_;
}

const render::IdImage& TankPictures::draw_ids() {
  renderer_.render_ids(look_, camera_, draws_);
  renderer_.read_ids(ids_);
  return ids_;
}

}  // namespace finflex::pictures
