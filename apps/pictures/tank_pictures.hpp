// Pictures of a SwimScene whose species' deformations write GL buffers of the renderer
// (fish_hand_off.hpp): the renderer, the tank as it draws it, a camera. The renderer
// comes first, so that the OpenCL context can share its GL context:
//
//   render::Renderer renderer(render_settings(settings));  // kNoDevice without EGL
//   GlSharingContext opencl = make_gl_sharing_context(device, renderer.egl_display(),
//                                                     renderer.egl_context());
//   tank::SwimScene scene(*opencl.context, species, ..., gl_outputs(renderer));
//   TankPictures pictures(renderer, scene, settings);
//   each frame: scene.enqueue_frame(dt);    // the deformation writes the GL buffers
//               pictures.draw();  pictures.read_image();
//               pictures.draw_ids();        // the instance ids, for datasets
//               (or request_ids(), and the renderer's take_ids() frames later)
#pragma once

#include <cstdint>
#include <vector>

#include "fish_hand_off.hpp"
#include "frame_optics.hpp"
#include "render/renderer.hpp"
#include "swim_scene.hpp"
#include "tank_view.hpp"

namespace finflex::pictures {

struct PictureSettings {
  int width = 640;  // pixels
  int height = 360;
  int samples = 4;  // multisampling of the colour pass
  CameraView view = CameraView::kOblique;
  // > 0: a rectified stereo pair, the right camera this many metres to the left one's
  // right (stereo_right_camera); 0: one camera.
  double stereo_baseline = 0.0;
  OpticsSettings optics;  // the water and the light, the same or varied per frame
  // Where the view rays bend (Scene::view_refraction): kSurface for a camera above the
  // water, kPort (at `port`) for the underwater one.
  render::ViewRefraction refraction = render::ViewRefraction::kNone;
  render::FlatPort port;
};

// The renderer's settings for pictures of `settings`.
render::RenderSettings render_settings(const PictureSettings& settings);

class TankPictures {
 public:
  // Per species with fish a drawing of its outputs (which must be GlSpeciesOutputs of
  // `renderer`: kInvalidArgument naming "scene" otherwise) whose id pass writes 1 + the
  // fish's index in the hall (hall().fish()); with levels of detail, a drawing per
  // level. `renderer` (made with render_settings(settings)) and `scene` must outlive
  // the pictures. A scene with levels gets the cameras as its views (set_views).
  TankPictures(render::Renderer& renderer, tank::SwimScene& scene, const PictureSettings& settings);

  // The colour pass of every species' last frame, once GL may read it (a GPU-side
  // wait where semaphores order the frame); no wait for the GPU to draw it. Its image:
  // read_image (waits), or the renderer's request_image and take_image. With levels,
  // the GPU draws each level's fish from the frame's lists where the hand-off is
  // external memory and GL has indirect draws (nothing read back); otherwise their
  // lists are read first (a wait for the frame's kernels on the host).
  void draw();
  // The water and light of frame `frame` (frame_optics) for the draws that follow;
  // frame 0's until the first call.
  void set_frame(std::size_t frame);
  const FrameOptics& optics() const { return optics_; }
  // Another view of the same frame, after draw(): 1 is a stereo pair's right camera.
  void draw_view(std::size_t view);
  const render::Image& read_image();
  // The reference draw of the same fish (Renderer::render_reference): the yardstick of
  // draw()'s GPU time. The image stays draw()'s.
  void draw_reference();
  // The id pass of the same (seen by camera `view`), read back (waits for the GPU).
  const render::IdImage& draw_ids(std::size_t view = 0);
  // The id pass of the same, its read-back started without a wait: the renderer's
  // take_ids takes it (at most its settings' frames_in_flight at once).
  void request_ids(std::size_t view = 0);

  // How the deformations reach the renderer (fish_hand_off.hpp).
  HandOffPath hand_off_path() const { return path_; }
  // External memory: whether every species' frame orders itself on the GPU
  // (semaphores), and why not.
  bool device_ordered() const { return device_ordered_; }
  const std::string& why_not_device_ordered() const { return why_not_ordered_; }

  // The cameras: 1, or a stereo pair's 2 (left, right).
  std::size_t views() const { return cameras_.size(); }
  const render::Camera& camera(std::size_t view = 0) const { return cameras_.at(view); }
  const render::Scene& look() const { return look_; }
  render::Renderer& renderer() { return renderer_; }

 private:
  render::Renderer& renderer_;
  render::Scene base_look_;  // the tank, with the default water and light
  OpticsSettings optics_settings_;
  FrameOptics optics_;
  render::Scene look_;  // base_look_ with optics_
  std::vector<render::Camera> cameras_;
  std::vector<SpeciesDrawing> drawings_;  // per species with fish (and level), in order
  std::vector<render::FishDraw> draws_;
  // With levels: per species with levels, its chooser, every fish's id and the first
  // of its levels' drawings.
  struct LeveledSpecies {
    LevelChooser* chooser = nullptr;
    std::vector<std::uint32_t> ids;
    std::size_t first_drawing = 0;
    bool device_lists = false;  // drawn from the GPU's lists (external memory), else the host's
  };
  std::vector<LeveledSpecies> leveled_;
  void take_lists();
  // Every draw pointed at its outputs' last frame (point_at_last_frame).
  void point_at_last_frame();
  HandOffPath path_ = HandOffPath::kCopy;
  bool device_ordered_ = true;
  std::string why_not_ordered_;
  render::Image image_;
  render::IdImage ids_;
};

}  // namespace finflex::pictures
