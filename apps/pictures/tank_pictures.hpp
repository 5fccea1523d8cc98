// Pictures of a SwimScene: the renderer, the tank as it draws it, a camera, and the
// hand-off of every species' deformed batch each frame (fish_hand_off.hpp).
//
//   TankPictures pictures(scene, settings);       // kNoDevice (RenderError) without EGL
//   each frame: scene.enqueue_frame(dt);
//               pictures.hand_off();              // waits for the deformation
//               pictures.draw();  pictures.read_image();
//               pictures.draw_ids();              // the instance ids, for datasets
#pragma once

#include <cstdint>
#include <vector>

#include "fish_hand_off.hpp"
#include "render/renderer.hpp"
#include "swim_scene.hpp"
#include "tank_view.hpp"

namespace finflex::pictures {

struct PictureSettings {
  int width = 640;  // pixels
  int height = 360;
  int samples = 4;  // multisampling of the colour pass
  CameraView view = CameraView::kOblique;
};

class TankPictures {
 public:
  // A renderer of settings' size, and per species with fish a drawing whose id pass
  // writes 1 + the fish's index in the tank (tank().fish()). Errors: RenderError
  // (kInvalidArgument for a bad size, kNoDevice without EGL).
  TankPictures(tank::SwimScene& scene, const PictureSettings& settings);

  // The hand-off: every species' batch as the scene's last enqueued frame left it.
  void hand_off();
  // The colour pass of the batches last handed off, and its image.
  void draw();
  const render::Image& read_image();
  // The id pass of the same, read back.
  const render::IdImage& draw_ids();

  const render::Camera& camera() const { return camera_; }
  const render::Scene& look() const { return look_; }
  render::Renderer& renderer() { return renderer_; }

 private:
  tank::SwimScene& scene_;
  render::Renderer renderer_;
  render::Scene look_;
  render::Camera camera_;
  std::vector<SpeciesDrawing> drawings_;  // per species with fish, in order
  std::vector<std::size_t> species_of_drawing_;
  std::vector<render::FishDraw> draws_;
  render::Image image_;
  render::IdImage ids_;
};

}  // namespace finflex::pictures
