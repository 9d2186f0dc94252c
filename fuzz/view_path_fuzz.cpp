// libFuzzer target: the view's path-file reader (scene/view_path.h: the bounded text reader,
// the nesting check, nlohmann-json, the keyframes' counts, times and ranges) on arbitrary bytes,
// through its file entry point. A path it accepts is flown along (the spline over flat ground at
// its first, middle and last time) and must give finite cameras, and written back as JSON it must
// read back to the same text.
#include <cmath>
#include <optional>

#include "fuzz/fuzz_input.h"
#include "scene/view_path.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace wangscape;
  const fuzz::InputFile file(data, size);
  return fuzz::accepted_values_round_trip(
      [&] {
        ViewPath path = read_view_path(file.path());
        const GroundHeightAt flat = [](double, double) { return std::optional<double>(0.0); };
        const double t0 = path.keys.front().time;
        for (const double t : {t0, t0 + path.duration() / 2, path.keys.back().time}) {
          const Camera c = camera_along(path, t, 50, flat, file.path());
          for (int k = 0; k < 3; ++k)
            if (!std::isfinite(c.position[k]) || !std::isfinite(c.target[k])) std::abort();
        }
        return path;
      },
      [](const ViewPath& path) { return view_path_json(path); },
      [](const std::string& text) { return parse_view_path(text, "round-trip.json"); });
}
