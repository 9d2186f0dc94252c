#include "folder/pack_light.h"

#include <type_traits>

namespace wangscape {

namespace {

// The fields a record shares with the light, each with its place in both: one list for the
// record and its reading back. field(in_light, in_record) for each.
template <class Light, class Record, class Field>
void for_each_light_field(Light& light, Record& record, const Field& field) {
  field(light.sun_color, record.sun_color);
  field(light.sky_color, record.sky_color);
  field(light.ground_color, record.ground_color);
  field(light.exposure, record.exposure);
  field(light.shadows, record.shadows);
  field(light.ao_rays, record.sky_rays);
  field(light.ao_distance, record.sky_reach);
  field(light.ray_offset, record.ray_offset);
}

// `to` = `from`, between a field's types in the light and in the record (bool, int, u32).
const auto assign = [](auto& to, const auto& from) { to = static_cast<std::remove_reference_t<decltype(to)>>(from); };

}  // namespace

ShadingSettings scene_file_light(const SceneConfig& config) {
  ShadingSettings light;
  light.ao_rays = config.ldi.sky_rays;
  return light;
}

LdiPackLight pack_light_record(const ShadingSettings& light, const Sun& sun) {
  LdiPackLight record;
  for_each_light_field(light, record, [](const auto& in_light, auto& in_record) { assign(in_record, in_light); });
  record.sun_direction = with_sun(light, sun).sun_direction;
  record.sun_strength = float(sun.strength);
  return record;
}

ShadingSettings recorded_light(const LdiPackLight& record) {
  ShadingSettings light;
  for_each_light_field(light, record, [](auto& in_light, const auto& in_record) { assign(in_light, in_record); });
  light.sun_direction = record.sun_direction;
  return light;
}

}  // namespace wangscape
