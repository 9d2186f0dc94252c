// The scene the far field's tests share (tests/scene/far_field_test.cpp and
// tests/renders/far_field_render_test.cpp): a flat field of cohen8 tiles, 20 flowers each, three
// sunflower variants with 400-triangle proxies, heads turned to `facing`, the evening sun of
// templates/scenes/whole-dem.toml (low in the west), painted beyond `far`.
#pragma once

#include <string>

namespace wangscape::testing {

struct FarFieldScene {
  double flat_size = 200;                    // meters
  double facing = 180;                       // compass degrees the heads turn to
  std::string camera = "[0.0, -90.0, 2.4]";  // ENU meters
  std::string target = "[0.0, 0.0, 2.0]";
  double far = 40;  // meters
  int width = 160, height = 90;
};

inline std::string far_field_scene_text(const FarFieldScene& s) {
  return "[terrain]\nflat_size = " + std::to_string(s.flat_size) +
         "\n[tiles]\ntile_size = 4.0\npoints_per_tile = 20\nrelaxation_rounds = 0\nseed = 7\n"
         "[models]\nvariants = 3\ntriangle_budget = 600\nseed = 3\nfacing = " +
         std::to_string(s.facing) + "\nfacing_jitter = 35.0\n[camera]\nposition = " + s.camera +
         "\ntarget = " + s.target +
         "\nfov = 50.0\n[sun]\nazimuth = 277.0\nelevation = 22.0\n[image]\nwidth = " + std::to_string(s.width) +
         "\nheight = " + std::to_string(s.height) +
         "\n[ground]\nbake_pixels = 256\n[camera_aware]\nnear = 10.0\nfar = " + std::to_string(s.far) +
         "\nproxy_triangles = 400\n";
}

}  // namespace wangscape::testing
