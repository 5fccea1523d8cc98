#include "tank_pictures.hpp"

#include <string>

#include "camera_file.hpp"

namespace finflex::pictures {

namespace {

// Per species, the id of each of its instances: 1 + the fish's index in the tank (the
// tank lists every species' fish; species s's instances are its fish in that order).
std::vector<std::vector<std::uint32_t>> instance_ids(const tank::Hall& tank,
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
      base_look_(tank_scene(scene.hall().hall_settings())),
      optics_settings_(settings.optics),
      cameras_{hall_view_camera(scene.hall().hall_settings(), settings.view, settings.width,
                                settings.height)} {
  base_look_.view_refraction = settings.refraction;
  base_look_.port = settings.port;
  optics_ = frame_optics(optics_settings_, 0);
  look_ = with_optics(base_look_, optics_);
  if (settings.stereo_baseline > 0.0) {
    cameras_.push_back(stereo_right_camera(cameras_.front(), settings.stereo_baseline));
  }
  std::vector<std::vector<std::uint32_t>> ids = instance_ids(scene.hall(), scene.species().size());
  const auto gl_outputs_of = [&](tank::SpeciesOutputs* made, std::size_t s) {
    auto* outputs = dynamic_cast<GlSpeciesOutputs*>(made);
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
    return outputs;
  };
  for (std::size_t s = 0; s < scene.species().size(); ++s) {
    tank::Species& species = scene.species()[s];
    const glm::vec3 albedo = species_albedo(species.name, s);
    if (species.leveled) {
      tank::SpeciesLevels& lv = *species.leveled;
      leveled_.push_back({&lv.deformer->chooser(), std::move(ids[s]), drawings_.size()});
      for (std::size_t k = 0; k < lv.outputs.size(); ++k) {
        drawings_.push_back(prepare_drawing(renderer_, lv.deformer->deformer(k),
                                            *gl_outputs_of(lv.outputs[k].get(), s), albedo, {}));
      }
      continue;
    }
    if (!species.deformer) continue;
    drawings_.push_back(prepare_drawing(renderer_, *species.deformer,
                                        *gl_outputs_of(species.outputs.get(), s), albedo,
                                        std::move(ids[s])));
  }
  for (const SpeciesDrawing& drawing : drawings_) draws_.push_back(fish_draw(drawing));
  for (LeveledSpecies& species : leveled_) {
    const LevelChooser& chooser = *species.chooser;
    // Every level's outputs are on the one hand-off path: all have device lists, or none.
    species.device_lists = drawings_[species.first_drawing].outputs->has_device_list() &&
                           renderer_.device().device_lists;
    for (std::size_t k = 0; k < chooser.level_count(); ++k) {
      SpeciesDrawing& drawing = drawings_[species.first_drawing + k];
      render::FishDraw& draw = draws_[species.first_drawing + k];
      if (!species.device_lists) {  // no fish until a frame's lists
        draw.instance_count = 0;
        continue;
      }
      // The GPU draws each level's fish from the chooser's command and list, copied
      // beside the level's outputs every frame; ids through the species' table.
      drawing.outputs->set_list_sources(chooser.draw_arguments(), 5 * sizeof(cl_uint) * k,
                                        chooser.lists(), sizeof(cl_uint) * chooser.list_first(k),
                                        chooser.rows(k));
      draw.list = drawing.outputs->device_list();
      draw.ids = species.ids.data();
      draw.id_count = species.ids.size();
    }
  }
  if (!leveled_.empty()) {
    std::vector<LevelView> views;
    for (const render::Camera& c : cameras_) {
      views.push_back(LevelView::look_at(c.position, c.target, c.up, c.vertical_fov_degrees,
                                         settings.width, settings.height, c.near_plane,
                                         c.far_plane));
    }
    scene.set_views(views);
    // The walls' test follows straight sight lines: refracted views see past them
    // elsewhere, so nothing is hidden by them there.
    if (settings.refraction != render::ViewRefraction::kNone) scene.set_occluders({});
  }
}

// Without device lists: each level's fish of the last frame and their ids, from its
// chooser's lists on the host.
void TankPictures::take_lists() {
  for (LeveledSpecies& species : leveled_) {
    if (species.device_lists) continue;
    const LevelChooser::Choice choice = species.chooser->read(false);
    for (std::size_t k = 0; k < choice.lists.size(); ++k) {
      SpeciesDrawing& drawing = drawings_[species.first_drawing + k];
      drawing.ids.clear();
      for (std::uint32_t fish : choice.lists[k]) drawing.ids.push_back(species.ids[fish]);
      render::FishDraw& draw = draws_[species.first_drawing + k];
      draw.instance_count = drawing.ids.size();
      draw.ids = drawing.ids.data();
    }
  }
}

void TankPictures::set_frame(std::size_t frame) {
  if (!optics_settings_.vary) return;  // every frame the base's
  optics_ = frame_optics(optics_settings_, frame);
  look_ = with_optics(base_look_, optics_);
}

void TankPictures::point_at_last_frame() {
  for (std::size_t d = 0; d < drawings_.size(); ++d)
    pictures::point_at_last_frame(drawings_[d], draws_[d]);
}

void TankPictures::draw() {
  take_lists();
  for (SpeciesDrawing& drawing : drawings_) drawing.outputs->wait_until_drawable();
  point_at_last_frame();
  renderer_.render(look_, cameras_.front(), draws_);
}

void TankPictures::draw_view(std::size_t view) {
  point_at_last_frame();
  renderer_.render(look_, camera(view), draws_);
}

void TankPictures::draw_reference() {
  point_at_last_frame();
  renderer_.render_reference(look_, cameras_.front(), draws_);
}

const render::Image& TankPictures::read_image() {
  renderer_.read_image(image_);
  return image_;
}

const render::IdImage& TankPictures::draw_ids(std::size_t view) {
  point_at_last_frame();
  renderer_.render_ids(look_, camera(view), draws_);
  renderer_.read_ids(ids_);
  return ids_;
}

void TankPictures::request_ids(std::size_t view) {
  point_at_last_frame();
  renderer_.render_ids(look_, camera(view), draws_);
  renderer_.request_ids();
}

}  // namespace finflex::pictures
