// The light of an LDI pack (folder/ldi_pack.h LdiPackLight) as the shading model has it
// (scene/shading_light.h): recorded by the LDI build, read back by the folder's readers; and the
// light a scene file's [ldi] section gives, for a folder whose pack records none (a version 2
// pack, or no pack) and for the build that records it.
#pragma once

#include "folder/ldi_pack.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "scene/shading_light.h"

namespace wangscape {

// The light the scene file's [ldi] section sets (its sky rays) on the shading model's defaults,
// before the sun: what a folder's LDI pack is shaded with.
ShadingSettings scene_file_light(const SceneConfig& config);

// The record of `light` (before the sun) lit by `sun` (with_sun): what a pack shaded so holds.
LdiPackLight pack_light_record(const ShadingSettings& light, const Sun& sun);

// The light before the sun a record holds, its sun's direction in place (with_sun of the same
// sun gives the light the pack was shaded with).
ShadingSettings recorded_light(const LdiPackLight& record);

}  // namespace wangscape
