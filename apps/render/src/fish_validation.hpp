// Checks of a frame's fish draws against the meshes and buffers they refer to, before
// anything is uploaded or drawn.
#pragma once

#include <vector>

#include "gl_resources.hpp"
#include "render/fish_draw.hpp"

namespace finflex::render::detail {

// Throws RenderError (kInvalidArgument) naming the first bad field and its value, e.g.
// "fish[2].normals.layout.vertex_stride": an unknown mesh or buffer; a stream with both
// sources or neither; an offset or stride that is not a multiple of the element size;
// fewer bytes than instance_count instances of the mesh need; an albedo that is not
// finite or outside 0..1; a device list (FishDraw::list) without `device_lists`, in
// no buffer of the renderer, or whose offsets are not multiples of 4 or whose command
// (20 bytes) or entries (4 bytes per row) pass the buffer's end. Draws with
// instance_count 0 are not checked.
void validate_fish(const std::vector<FishDraw>& fish, const std::vector<MeshResources>& meshes,
                   const std::vector<BufferResource>& buffers, bool device_lists);

// For the id pass: every draw with instances has ids ("fish[d].ids": null), all > 0
// ("fish[d].ids[i]": 0 is the background's); with a device list id_count of them
// ("fish[d].id_count": 0).
void validate_ids(const std::vector<FishDraw>& fish);

}  // namespace finflex::render::detail
