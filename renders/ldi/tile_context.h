// A tile's 3 x 3 context as an Embree scene, for rays other than the LDI build's own (the ground's
// light under the plants, renders/ldi/ground_light.h). Internal to renders/.
#pragma once

#include <cstddef>
#include <span>

#include "renders/ldi/ldi_build.h"
#include "renders/trace/embree_device.h"

namespace wangscape {

// Tile `tile` in the 3 x 3 context its LDIs are shaded in (options.context_choice), as one scene
// of `device` for shadow and sky rays: each plant an instance of its model's scene in `occluders`
// (model_scenes(device, models, nullptr): leaf cards' holes let the rays pass); the ground at
// z = 0, the tile over [0, tile_size] x [0, tile_size].
EmbreeScene tile_context_scene(EmbreeDevice& device, std::span<const EmbreeScene> occluders,
                               const FilledTileSet& filled, std::span<const Mesh> models,
                               const LdiBuildOptions& options, std::size_t tile);

}  // namespace wangscape
