#include "exporters/povray_writer.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <set>
#include <span>
#include <vector>

#include "core/atomic_file.h"
#include "core/number_text.h"
#include "core/printable.h"
#include "exporters/export_support.h"
#include "exporters/image_io.h"
#include "scene/shading_light.h"

namespace wangscape {

namespace {

// ---- locale-independent number formatting -------------------------------------------------

// Appends `value` with exactly `decimals` digits after the point, via an integer: much faster
// than floating-point formatting and never locale-dependent. |value| * 10^decimals must fit
// in 63 bits to take the fast path (meters and degrees always do); larger values are written by
// fixed_text.
void append_fixed(std::string& out, double value, int decimals) {
  static constexpr double kPowers[] = {1, 10, 100, 1000, 1e4, 1e5, 1e6, 1e7, 1e8};
  if (!std::isfinite(value)) value = 0.0;
  if (std::fabs(value) * kPowers[decimals] >= 9.2e18) {  // beyond 63 bits: the slow way, never wrapped
    out += fixed_text(value, decimals);
    return;
  }
  const bool negative = value < 0;
  const auto scaled = static_cast<std::uint64_t>(std::llround(std::fabs(value) * kPowers[decimals]));
  char digits[24];
  auto [end, ec] = std::to_chars(digits, digits + sizeof digits, scaled);
  (void)ec;
  std::size_t length = static_cast<std::size_t>(end - digits);
  if (negative && scaled != 0) out.push_back('-');
  const auto whole_digits =
      length > static_cast<std::size_t>(decimals) ? length - static_cast<std::size_t>(decimals) : 0;
  if (whole_digits == 0) {
    out.push_back('0');
  } else {
    out.append(digits, whole_digits);
  }
  if (decimals == 0) return;
  out.push_back('.');
  for (std::size_t pad = length; pad < static_cast<std::size_t>(decimals); ++pad) out.push_back('0');
  out.append(digits + whole_digits, length - whole_digits);
}

void append_int(std::string& out, std::uint64_t value) {
  char digits[24];
  auto [end, ec] = std::to_chars(digits, digits + sizeof digits, value);
  (void)ec;
  out.append(digits, end);
}

// "<x,y,z>" with the given precision.
void append_vector(std::string& out, double x, double y, double z, int decimals) {
  out.push_back('<');
  append_fixed(out, x, decimals);
  out.push_back(',');
  append_fixed(out, y, decimals);
  out.push_back(',');
  append_fixed(out, z, decimals);
  out.push_back('>');
}

// ENU (x east, y north, z up) -> POV (x east, y up, z north).
void append_enu_as_pov(std::string& out, const std::array<double, 3>& enu, int decimals) {
  append_vector(out, enu[0], enu[2], enu[1], decimals);
}

std::string fixed(double value, int decimals) {
  std::string s;
  append_fixed(s, value, decimals);
  return s;
}

// ---- meshes ---------------------------------------------------------------------------------

std::string comment_safe(std::string_view source);  // the scene file's, below

// A texture_list of one texture per material: an image map where `material_files` names the
// material's image (its alpha a cutout), else the material's colour; then face_indices with each
// triangle's texture. For meshes with images only: a texture_list costs every copy of the mesh a
// copy of each texture, which the palette below avoids.
void append_textured_faces(std::string& out, const Mesh& mesh, std::span<const std::string> material_files) {
  out += "  uv_vectors { ";
  append_int(out, mesh.uvs.size());
  for (std::size_t i = 0; i < mesh.uvs.size(); ++i) {
    out += (i % 4 == 0) ? ",\n    <" : ", <";
    append_fixed(out, mesh.uvs[i][0], 6);
    out.push_back(',');
    append_fixed(out, mesh.uvs[i][1], 6);
    out.push_back('>');
  }
  out += "\n  }\n  texture_list { ";
  append_int(out, mesh.materials.size());
  for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
    const Material& material = mesh.materials[m];
    const std::string finish = fixed(material.roughness, 3) + ", " + fixed(material.translucency, 3);
    out += ",\n    texture { ";
    if (m < material_files.size() && !material_files[m].empty()) {
      // The PNG's alpha (0 or 255) is POV-Ray's transmit: the holes of a cutout.
      out += "uv_mapping pigment { image_map { png \"" + material_files[m] + "\" interpolate 2 } } finish { " +
             "Wangscape_Finish(" + finish + ") } }  // " + comment_safe(material.name);
    } else {
      out += "Wangscape_Material(";
      append_vector(out, material.base_color[0], material.base_color[1], material.base_color[2], 4);
      out += ", " + finish + ") }  // " + comment_safe(material.name);
    }
  }
  out += "\n  }\n  face_indices { ";
  append_int(out, mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    out += (t % 4 == 0) ? ",\n    <" : ", <";
    append_int(out, tri[0]);
    out.push_back(',');
    append_int(out, tri[1]);
    out.push_back(',');
    append_int(out, tri[2]);
    out += ">, ";
    append_int(out, std::min<std::size_t>(mesh.triangle_material[t], mesh.materials.size() - 1));
  }
  out += "\n  }\n}\n";
}

// Writes `mesh2 { ... }` (without a declaration) for a mesh whose positions are ENU/model
// space (z up). Textures: one per material, chosen per triangle through texture_list.
void append_mesh2(std::string& out, const Mesh& mesh, int position_decimals, const std::string& texture_override,
                  std::span<const std::string> material_files = {}) {
  out += "mesh2 {\n  vertex_vectors { ";
  append_int(out, mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const auto& p = mesh.positions[i];
    out += (i % 4 == 0) ? ",\n    " : ", ";
    append_vector(out, p[0], p[2], p[1], position_decimals);
  }
  out += "\n  }\n";
  const bool has_normals = mesh.normals.size() == mesh.positions.size();
  if (has_normals) {
    out += "  normal_vectors { ";
    append_int(out, mesh.normals.size());
    for (std::size_t i = 0; i < mesh.normals.size(); ++i) {
      const auto& n = mesh.normals[i];
      out += (i % 4 == 0) ? ",\n    " : ", ";
      append_vector(out, n[0], n[2], n[1], 4);
    }
    out += "\n  }\n";
  }
  const bool has_images =
      std::any_of(material_files.begin(), material_files.end(), [](const std::string& file) { return !file.empty(); });
  if (texture_override.empty() && has_images && mesh.uvs.size() == mesh.positions.size() &&
      mesh.triangle_material.size() == mesh.triangles.size() && !mesh.materials.empty()) {
    append_textured_faces(out, mesh, material_files);
    return;
  }
  const bool per_triangle_textures =
      texture_override.empty() && mesh.materials.size() > 1 && mesh.triangle_material.size() == mesh.triangles.size();
  if (per_triangle_textures) {
    // Materials as a palette: one uv coordinate per material, one texture whose uv-mapped
    // gradient holds every material's color. A texture_list would cost each copy of the mesh a
    // copy of every texture (about 3 KB per flower in POV-Ray 3.7); one texture costs a fifth.
    out += "  uv_vectors { ";
    append_int(out, mesh.materials.size());
    for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
      out += ", <";
      append_fixed(out, (double(m) + 0.5) / double(mesh.materials.size()), 6);
      out += ",0.5>";
    }
    out += " }\n";
  }
  out += "  face_indices { ";
  append_int(out, mesh.triangles.size());
  const auto material_count = mesh.materials.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    out += (t % 4 == 0) ? ",\n    " : ", ";
    // The y/z swap mirrors the mesh; POV-Ray does not cull by winding, so the order stays.
    out.push_back('<');
    append_int(out, tri[0]);
    out.push_back(',');
    append_int(out, tri[1]);
    out.push_back(',');
    append_int(out, tri[2]);
    out.push_back('>');
  }
  out += "\n  }\n";
  if (per_triangle_textures) {
    out += "  uv_indices { ";
    append_int(out, mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      out += (t % 8 == 0) ? ",\n    <" : ", <";
      const auto m = std::min<std::size_t>(mesh.triangle_material[t], material_count - 1);
      append_int(out, m);
      out.push_back(',');
      append_int(out, m);
      out.push_back(',');
      append_int(out, m);
      out.push_back('>');
    }
    out += "\n  }\n";
    double roughness = 0, translucency = 0;
    out += "  texture {\n    uv_mapping pigment { gradient x color_map {";
    for (std::size_t m = 0; m < material_count; ++m) {
      const auto& material = mesh.materials[m];
      roughness += material.roughness / double(material_count);
      translucency = std::max<double>(translucency, material.translucency);
      for (double edge : {double(m) / double(material_count), double(m + 1) / double(material_count)}) {
        out += "\n      [";
        append_fixed(out, edge, 6);
        out += " rgb ";
        append_vector(out, material.base_color[0], material.base_color[1], material.base_color[2], 4);
        out += "]";
      }
      out += "  // " + material.name;
    }
    out += "\n    } }\n    finish { Wangscape_Finish(" + fixed(roughness, 3) + ", " + fixed(translucency, 3) +
           ") }\n  }\n";
  }
  if (!texture_override.empty()) {
    out += "  texture { " + texture_override + " }\n";
  } else if (!per_triangle_textures) {
    out += "  texture { Wangscape_Material(";
    if (mesh.materials.empty()) {
      out += "<0.5,0.5,0.5>, 0.5, 0";
    } else {
      const auto& material = mesh.materials.front();
      append_vector(out, material.base_color[0], material.base_color[1], material.base_color[2], 4);
      out += ", " + fixed(material.roughness, 3) + ", " + fixed(material.translucency, 3);
    }
    out += ") }\n";
  }
  out += "}\n";
}

// What POV-Ray needs of a mesh (normals are optional in mesh2, unlike in the array exports).
void check_povray_mesh(const Mesh& mesh, const std::string& what) {
  if (mesh.triangles.empty()) throw Error("POV-Ray export: " + what + " has no triangles");
  for (const auto& tri : mesh.triangles)
    for (auto index : tri)
      if (index >= mesh.positions.size())
        throw Error("POV-Ray export: " + what + " has a triangle index " + std::to_string(index) + " past its " +
                    std::to_string(mesh.positions.size()) + " vertices");
}

// ---- the scene file ---------------------------------------------------------------------------

std::string comment_safe(std::string_view source) {
  std::string text = valid_utf8(source);  // names from a DEM's CRS may be Latin-1
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

// The one shading model's light (scene/shading_light.h) with the scene's sun: what the Embree
// reference and the view show, so POV-Ray gets the same numbers.
ShadingSettings scene_light(const Sun& sun) { return with_sun(ShadingSettings{}, sun); }

// `rgb <r, g, b>` of a linear color times the exposure (POV-Ray with assumed_gamma 1 is linear).
std::string exposed_rgb(const Vec3f& color, float exposure) {
  std::string out = "rgb ";
  append_vector(out, double(color[0] * exposure), double(color[1] * exposure), double(color[2] * exposure), 4);
  return out;
}

struct HeightRange {
  double min = 0, max = 1;
};

HeightRange terrain_heights(const Mesh& terrain) {
  if (terrain.positions.empty()) return {};
  HeightRange range{std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest()};
  for (const auto& p : terrain.positions) {
    range.min = std::min<double>(range.min, p[2]);
    range.max = std::max<double>(range.max, p[2]);
  }
  if (range.max <= range.min) range.max = range.min + 1.0;
  return range;
}

constexpr const char* kPovrayGroundImage = "ground.png";

std::string scene_pov(const Scene& scene, bool has_terrain, bool has_instances, std::uint64_t instance_count) {
  std::string s;
  s += "// " + comment_safe(scene.name) + ": written by wangscape for POV-Ray 3.7.\n";
  s += "// Render from this folder: povray scene.ini (or: wangscape render <this folder>)\n";
  s += "// Axes: x = east, y = up, z = north, meters, from the local ENU frame below.\n";
  s += "// Georeference:\n";
  for (const auto& [key, value] : scene.georeference)
    s += "//   " + comment_safe(key) + ": " + comment_safe(value) + "\n";
  s += "//   instances: " + std::to_string(instance_count) + "\n";
  s += "#version 3.7;\n\n";
  s += "// Switches (override with Declare=Use_Radiosity=1 in the ini or on the command line).\n";
  s += "#ifndef (Use_Radiosity) #declare Use_Radiosity = " + std::string(scene.render.radiosity ? "1" : "0") +
       "; #end\n";
  s += "#ifndef (Show_Instances) #declare Show_Instances = 1; #end\n";
  // Without radiosity every surface gets the open sky's light as ambient (lit()'s sky term, open
  // everywhere); with it, the light the sky_sphere and the other surfaces send.
  s += "#declare Ambient_Level = (Use_Radiosity ? 0 : 1);\n\n";
  const ShadingSettings light = scene_light(scene.sun);
  s += "global_settings {\n  assumed_gamma 1.0\n  max_trace_level 8\n  ambient_light " +
       exposed_rgb(light.sky_color, light.exposure) + "\n";
  s += "  #if (Use_Radiosity)\n";
  s += "  radiosity {\n    pretrace_start 0.08 pretrace_end 0.02 count 50 nearest_count 5\n";
  s += "    error_bound 1.5 recursion_limit 1 low_error_factor 0.5 gray_threshold 0\n";
  s += "    minimum_reuse 0.015 brightness 1 adc_bailout 0.01\n  }\n  #end\n}\n\n";

  // A material from the models' Material: linear RGB color, roughness 0..1, translucency 0..1
  // (light through thin petals and leaves, as POV-Ray's back-side diffuse). Lambert alone, as in
  // the one shading model (sun_share): the front gets the sun's cosine, the back Translucency of it.
  // Roughness is kept in the call for the materials' record; no highlight depends on it.
  s += "#macro Wangscape_Finish(Roughness, Translucency)\n";
  s += "  ambient Ambient_Level\n  diffuse 1, Translucency\n#end\n";
  s += "#macro Wangscape_Material(Color, Roughness, Translucency)\n";
  s += "  pigment { rgb Color }\n  finish { Wangscape_Finish(Roughness, Translucency) }\n#end\n\n";

  s += povray_camera_and_sun(scene.camera, scene.sun) + "\n";

  // The sky of sky_radiance(): horizon to zenith by the square root of the ray's up component.
  const SkyGradient sky = sky_gradient(light);
  s += "sky_sphere {\n  pigment {\n    function { sqrt(max(0, y)) }\n    color_map {\n";
  s += "      [0 " + exposed_rgb(sky.horizon, light.exposure) + "]\n      [1 " +
       exposed_rgb(sky.zenith, light.exposure) + "]\n    }\n  }\n}\n\n";

  if (has_terrain) {
    s += "#include \"terrain.inc\"\n";
  }
  if (has_terrain && scene.ground_texture) {
    // The scene's [ground] look, baked once over the terrain's extent (ground.png, north at
    // the top): the planar map lies in x-y, rotated into x-z (top to north), stretched over the extent.
    const Extent& e = scene.ground_texture->extent;
    s += "// Ground: the scene's [ground] look baked into ground.png over the terrain's extent.\n";
    s += "#declare Ground_Texture =\n  texture {\n    pigment {\n";
    s += "      image_map { png \"" + std::string(kPovrayGroundImage) +
         "\" gamma srgb map_type 0 interpolate 2 once }\n";
    s += "      rotate x * 90\n      scale <" + fixed(e.width(), 3) + ", 1, " + fixed(e.height(), 3) + ">\n";
    s += "      translate <" + fixed(e.min_x, 3) + ", 0, " + fixed(e.min_y, 3) + ">\n    }\n";
    s += "    finish { ambient Ambient_Level diffuse 1 }\n  }\n";
    s += "object { Terrain texture { Ground_Texture } }\n\n";
  } else if (has_terrain) {
    // One plain color, the one Blender, glTF, the Embree reference and the view give the ground.
    s += "// Ground: one plain color (the scene has no [ground] look).\n";
    s += "#declare Ground_Texture =\n  texture {\n    pigment { " +
         exposed_rgb(default_ground_material().base_color, 1.0f) + " }\n";
    s += "    finish { ambient Ambient_Level diffuse 1 }\n  }\n";
    s += "object { Terrain texture { Ground_Texture } }\n\n";
  }
  // No fog: the Embree reference, the view and Cycles have no aerial perspective either.
  s += "#include \"models.inc\"\n";
  if (has_instances && scene.wind) s += povray_wind_functions(*scene.wind);
  if (has_instances) s += "#if (Show_Instances)\n  #include \"instances.inc\"\n#end\n";
  return s;
}

std::string scene_ini(const Scene& scene, const std::filesystem::path& library_dir) {
  const auto& r = scene.render;
  std::string s;
  s += "; POV-Ray settings written by wangscape. Render from this folder: povray scene.ini\n";
  s += std::string("Input_File_Name=") + kPovraySceneFile + "\nOutput_File_Name=render.png\nOutput_File_Type=N\n";
  s += "Width=" + std::to_string(r.width) + "\nHeight=" + std::to_string(r.height) + "\n";
  if (r.antialias_samples > 1) {
    s += "Antialias=on\nSampling_Method=2\nAntialias_Depth=" + std::to_string(std::min(r.antialias_samples, 9)) +
         "\nAntialias_Threshold=0.1\n";
  } else {
    s += "Antialias=off\n";
  }
  if (r.threads > 0) s += "Work_Threads=" + std::to_string(r.threads) + "\n";
  s += "File_Gamma=sRGB\nDisplay=off\nPause_When_Done=off\n";
  // Includes resolve against the current directory and these paths, not the .pov's folder.
  s += "Library_Path=" + povray_quoted_path(library_dir) + "\n";
  return s;
}

}  // namespace

std::string povray_wind_functions(const WindField& wind) {
  // " + c * what" (" - |c| * what"), nothing for c = 0.
  const auto term = [](double c, const std::string& what) -> std::string {
    if (c == 0) return {};
    return (c < 0 ? " - " : " + ") + number_text(std::abs(c)) + " * " + what;
  };
  std::string s;
  s += "// Wind ([wind]): every plant leans about its base, toward north by Wind_North and toward east by\n";
  s += "// Wind_East degrees (rotate <north, 0, -east>), at its place (E, N) and time Wind_Time seconds:\n";
  s += "// 0 in a still, the frame's time in a path's animation. Each wave's phase at Wind_Time is\n";
  s += "// worked out outside the functions: POV-Ray 3.7 folds `- a * Wind_Time + b` into -(a * t + b).\n";
  s += "#ifndef (Wind_Time) #declare Wind_Time = 0; #end\n";
  for (std::size_t i = 0; i < wind.waves.size(); ++i)
    s += "#declare Wind_Phase_" + std::to_string(i) + " = " + number_text(wind.waves[i].phase) +
         term(wind.waves[i].k_time, "Wind_Time") + ";\n";
  const auto lean = [&](const char* name, double base, double WindWave::*amplitude) {
    s += "#declare " + std::string(name) + " = function(E, N) {\n  " + number_text(base);
    for (std::size_t i = 0; i < wind.waves.size(); ++i) {
      const WindWave& w = wind.waves[i];
      std::string phase = term(w.k_east, "E") + term(w.k_north, "N");  // never empty: k > 0
      phase = (phase.starts_with(" - ") ? "-" : "") + phase.substr(3) + " + Wind_Phase_" + std::to_string(i);
      if (w.*amplitude != 0) s += "\n " + term(w.*amplitude, "sin(" + phase + ")");
    }
    s += "\n}\n";
  };
  lean("Wind_East", wind.base.east, &WindWave::amplitude_east);
  lean("Wind_North", wind.base.north, &WindWave::amplitude_north);
  return s;
}

std::string povray_quoted_path(const std::filesystem::path& path) {
  const std::string text = path.string();
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f || c == '"')
      throw Error(printable(text), "",
                  "POV-Ray cannot use this path: it holds a control character (a newline, a tab, ...) or a "
                  "double quote; choose a folder name without them");
  }
  return '"' + text + '"';
}

std::string povray_camera_and_sun(const Camera& cam, const Sun& sun) {
  std::string s;
  s += "camera {\n  perspective\n  location ";
  append_enu_as_pov(s, cam.position, 3);
  s += "\n  look_at ";
  append_enu_as_pov(s, cam.target, 3);
  s += "\n  right x * image_width / image_height\n  angle " + fixed(cam.fov_degrees, 3) + "\n}\n\n";

  const auto dir = sun.direction();
  const ShadingSettings light = scene_light(sun);
  // A parallel light must sit outside every object to cast their shadows: far along the sun.
  constexpr double kSunDistance = 1.0e6;
  const std::array<double, 3> sun_position{cam.target[0] + dir[0] * kSunDistance, cam.target[1] + dir[1] * kSunDistance,
                                           cam.target[2] + dir[2] * kSunDistance};
  s += "// Sun: azimuth " + fixed(sun.azimuth_degrees, 2) + " deg from north, elevation " +
       fixed(sun.elevation_degrees, 2) + " deg.\n";
  s += "light_source {\n  ";
  append_enu_as_pov(s, sun_position, 1);
  s += "\n  color " + exposed_rgb(light.sun_color, light.exposure);
  s += "\n  parallel\n  point_at ";
  append_enu_as_pov(s, cam.target, 3);
  s += "\n}\n";
  return s;
}

std::string povray_scene_with_camera_and_sun(const std::string& scene_pov, const Camera& camera, const Sun& sun,
                                             const std::filesystem::path& file) {
  const auto begin = scene_pov.find("camera {\n"), end = scene_pov.find("sky_sphere {");
  if (begin == std::string::npos || end == std::string::npos || end < begin)
    throw Error(file, "", "has no camera and sky_sphere blocks to replace (write it with `wangscape build`)");
  std::string text = scene_pov;
  text.replace(begin, end - begin, povray_camera_and_sun(camera, sun) + "\n");
  return text;
}

std::string povray_scene_with_cameras(const std::string& scene_pov, const std::vector<Camera>& cameras,
                                      const std::filesystem::path& file, const std::vector<double>& seconds) {
  if (cameras.empty()) throw Error(file, "", "no camera to render it from");
  const auto begin = scene_pov.find("camera {\n");
  const auto end = begin == std::string::npos ? begin : scene_pov.find("\n}\n", begin);
  if (end == std::string::npos)
    throw Error(file, "", "has no camera block to replace (write it with `wangscape build`)");
  std::string block;
  const auto append_points = [&](const char* name, auto point) {
    block += "#declare " + std::string(name) + " = array[" + std::to_string(cameras.size()) + "] {\n";
    for (std::size_t k = 0; k < cameras.size(); ++k) {
      block += "  ";
      append_enu_as_pov(block, point(cameras[k]), 4);
      block += k + 1 < cameras.size() ? ",\n" : "\n";
    }
    block += "}\n";
  };
  std::string location = "Wangscape_Eyes[0]", look_at = "Wangscape_Targets[0]";
  if (cameras.size() > 1) {
    block += "// An animation of " + std::to_string(cameras.size()) + " frames: frame_number k (+KFI0 +KFF" +
             std::to_string(cameras.size() - 1) + ") looks from Wangscape_Eyes[k] at Wangscape_Targets[k].\n";
    location = "Wangscape_Eyes[frame_number]";
    look_at = "Wangscape_Targets[frame_number]";
  }
  append_points("Wangscape_Eyes", [](const Camera& c) { return c.position; });
  append_points("Wangscape_Targets", [](const Camera& c) { return c.target; });
  if (!seconds.empty()) {
    // The wind's time of each frame (scene.pov declares Wind_Time only when this has not).
    if (seconds.size() != cameras.size()) throw Error(file, "", "a time for each camera expected");
    block += "#declare Wangscape_Times = array[" + std::to_string(seconds.size()) + "] {";
    for (std::size_t k = 0; k < seconds.size(); ++k) block += (k ? ", " : " ") + number_text(seconds[k]);
    block +=
        " }\n#declare Wind_Time = Wangscape_Times[" + std::string(cameras.size() > 1 ? "frame_number" : "0") + "];\n";
  }
  block += "camera {\n  perspective\n  location " + location + "\n  look_at " + look_at +
           "\n  right x * image_width / image_height\n  angle " + fixed(cameras.front().fov_degrees, 3) + "\n}\n";
  std::string out = scene_pov;
  out.replace(begin, end + 3 - begin, block);
  return out;
}

std::vector<std::string> povray_model_names(const std::vector<Mesh>& models) {
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (std::size_t v = 0; v < models.size(); ++v) {
    std::string name;
    for (const char c : models[v].name) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) name = "Model_" + name;
    name[0] = char(std::toupper(static_cast<unsigned char>(name[0])));
    if (taken.contains(name)) name += "_v" + std::to_string(v);
    taken.insert(name);
    names.push_back(std::move(name));
  }
  return names;
}

// ---- instances --------------------------------------------------------------------------------

PovrayInstanceWriter::PovrayInstanceWriter(std::ostream& out, const std::vector<std::string>& model_names, bool sway)
    : out_(out), sway_(sway) {
  for (const std::string& name : model_names) object_prefixes_.push_back("object{" + name);
  buffer_.reserve(1 << 20);
}

void PovrayInstanceWriter::write(const InstanceBatch& batch) {
  constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;
  for (std::size_t i = 0; i < batch.size(); ++i) {
    if (batch.variant[i] >= object_prefixes_.size())
      throw Error("POV-Ray export: an instance of model variant " + std::to_string(batch.variant[i]) + " of " +
                  std::to_string(object_prefixes_.size()));
    buffer_ += object_prefixes_[batch.variant[i]];
    // ENU yaw turns counter-clockwise seen from above (east towards north); POV's rotate
    // about y turns +x towards -z (east towards south) for positive angles.
    buffer_ += " rotate y*";
    append_fixed(buffer_, -static_cast<double>(batch.yaw[i]) * kDegreesPerRadian, 1);
    buffer_ += " scale ";
    append_fixed(buffer_, batch.scale[i], 3);
    if (sway_) {
      // About the plant's base, before it is moved there; functions, not a macro: a macro call
      // per plant made POV-Ray's parse of 287,000 plants 5 times slower, the functions 1.3 times.
      const auto place = [&] {
        append_fixed(buffer_, batch.x[i], 3);
        buffer_ += ',';
        append_fixed(buffer_, batch.y[i], 3);
      };
      buffer_ += " rotate<Wind_North(";
      place();
      buffer_ += "),0,-Wind_East(";
      place();
      buffer_ += ")>";
    }
    buffer_ += " translate";
    append_vector(buffer_, batch.x[i], batch.z[i], batch.y[i], 3);
    buffer_ += "}\n";
    if (buffer_.size() >= (1u << 20) - 256) flush();
  }
  instances_ += batch.size();
}

void PovrayInstanceWriter::flush() {
  if (buffer_.empty()) return;
  out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
  bytes_ += buffer_.size();
  buffer_.clear();
}

// ---- the folder -----------------------------------------------------------------------------

struct PovrayWriter::Impl {
  Impl(const Scene& s, const std::filesystem::path& d, const PovrayExportOptions& o) : scene(s), dir(d), options(o) {}
  const Scene& scene;
  std::filesystem::path dir;
  PovrayExportOptions options;
  bool has_terrain = false, has_instances = false;
  PovrayExportStats stats{};
  // All files stay temporary until every one is complete.
  std::vector<std::unique_ptr<AtomicFile>> files{};
  std::unique_ptr<AtomicFile> instances_file{};
  std::unique_ptr<PovrayInstanceWriter> instances{};

  void write_whole(const char* name, const std::string& contents) {
    files.push_back(std::make_unique<AtomicFile>(dir / name));
    files.back()->stream().write(contents.data(), static_cast<std::streamsize>(contents.size()));
    stats.total_bytes += contents.size();
  }
};

PovrayWriter::PovrayWriter(const Scene& scene, const std::filesystem::path& dir, const PovrayExportOptions& options)
    : impl_(std::make_unique<Impl>(scene, dir, options)) {
  if (!std::filesystem::is_directory(dir))
    throw Error("POV-Ray export: output folder '" + dir.string() + "' does not exist");
  if (scene.models.empty() && scene.instances) throw Error("POV-Ray export: the scene has instances but no models");
  const std::vector<std::string> model_names = povray_model_names(scene.models);
  for (std::size_t v = 0; v < scene.models.size(); ++v) check_povray_mesh(scene.models[v], "model " + model_names[v]);
  Impl& impl = *impl_;
  impl.has_terrain = !scene.terrain.triangles.empty();
  if (impl.has_terrain) check_povray_mesh(scene.terrain, "the terrain");
  impl.has_instances = static_cast<bool>(scene.instances);

  const auto library_dir = std::filesystem::absolute(options.final_dir.empty() ? dir : options.final_dir);
  impl.write_whole("scene.ini", scene_ini(scene, library_dir));
  // The models' images, beside models.inc (POV-Ray finds them through the folder's +L path).
  const MaterialTable table = build_material_table(scene);
  const std::vector<MaterialTexture> textures = material_textures(table);
  for (const MaterialTexture& texture : textures)
    if (!texture.file.empty()) impl.write_whole(texture.file.c_str(), texture.png);
  {
    std::string models = "// Model variants, each declared once: copies of a mesh2 share its data.\n";
    models += "#declare Wangscape_Model_Count = " + std::to_string(scene.models.size()) + ";\n";
    for (std::size_t v = 0; v < scene.models.size(); ++v) {
      const auto& mesh = scene.models[v];
      models += "\n// " + comment_safe(mesh.name) + ": " + std::to_string(mesh.triangle_count()) + " triangles\n";
      models += "#declare " + model_names[v] + " = ";
      std::vector<std::string> files;
      for (const std::uint32_t slot : table.model_slots[v]) files.push_back(textures[slot].file);
      append_mesh2(models, mesh, 5, "", files);
    }
    impl.write_whole("models.inc", models);
  }
  if (impl.has_terrain) {
    const auto heights = terrain_heights(scene.terrain);
    std::string terrain = "// Terrain, ENU meters as POV axes (x east, y up, z north).\n";
    terrain += "#declare Terrain_Min_Height = " + fixed(heights.min, 3) + ";\n";
    terrain += "#declare Terrain_Max_Height = " + fixed(heights.max, 3) + ";\n";
    terrain += "#declare Terrain = ";
    append_mesh2(terrain, scene.terrain, 3, "pigment { rgb 0.5 }");
    impl.write_whole("terrain.inc", terrain);
  }
  if (impl.has_instances) {
    impl.instances_file = std::make_unique<AtomicFile>(dir / "instances.inc");
    impl.instances =
        std::make_unique<PovrayInstanceWriter>(impl.instances_file->stream(), model_names, scene.wind.has_value());
  }
}

PovrayWriter::~PovrayWriter() = default;

void PovrayWriter::append(const InstanceBatch& batch) {
  Impl& impl = *impl_;
  if (!impl.instances) throw Error("POV-Ray export: instances for a scene without an instance stream");
  impl.instances->write(batch);
  if (impl.options.on_instances) impl.options.on_instances(impl.instances->instances());
}

void PovrayWriter::finish(const StreamTotals& totals) {
  Impl& impl = *impl_;
  if (impl.instances) {
    impl.instances->flush();
    // The count is known only now: it closes the file.
    const std::string trailer =
        "// " + std::to_string(impl.instances->instances()) + " instances of the models in models.inc\n";
    impl.instances_file->stream() << trailer;
    impl.stats.instances = impl.instances->instances();
    impl.stats.instance_bytes = impl.instances->bytes() + trailer.size();
    impl.stats.total_bytes += impl.stats.instance_bytes;
  }
  if (impl.has_terrain && impl.scene.ground_texture) {
    // Written last but one, so a failure here still leaves none of the text files.
    write_file_atomically(impl.dir / kPovrayGroundImage, encoded_ground(impl.scene, impl.options.ground)->png());
    std::error_code ec;
    impl.stats.total_bytes += std::filesystem::file_size(impl.dir / kPovrayGroundImage, ec);
  }
  impl.write_whole(kPovraySceneFile, scene_pov(impl.scene, impl.has_terrain, impl.has_instances, totals.instances));
  for (auto& file : impl.files) file->commit();
  if (impl.instances_file) impl.instances_file->commit();
}

const PovrayExportStats& PovrayWriter::stats() const { return impl_->stats; }

PovrayExportStats write_povray_scene(const Scene& scene, const std::filesystem::path& dir,
                                     const PovrayExportOptions& options) {
  PovrayWriter writer(scene, dir, options);
  run_scene_stream(scene, writer);
  return writer.stats();
}

}  // namespace wangscape
