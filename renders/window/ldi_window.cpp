#include "renders/window/ldi_window.h"

#include <SDL2/SDL.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <unordered_set>
#include <vector>

#include "core/atomic_file.h"
#include "core/error.h"
#include "exporters/image_io.h"
#include "renders/view/view_frames.h"  // the path files (scene/view_path.h) the view plays

namespace wangscape {

namespace {

// ---- the script ----------------------------------------------------------------------------

struct ScriptStep {
  enum Kind { key, mouse, wait, resize } kind = key;
  SDL_Keycode code = 0;
  int frames = 1, dx = 0, dy = 0;
};

SDL_Keycode script_key(const std::string& name) {
  if (name == "screenshot") return SDLK_F12;
  if (name == "Escape") return SDLK_ESCAPE;
  if (name == "Space") return SDLK_SPACE;
  if (name == "Shift") return SDLK_LSHIFT;
  if (name == "+") return SDLK_EQUALS;
  if (name == "-") return SDLK_MINUS;
  if (name.size() == 1 && std::isalnum(static_cast<unsigned char>(name[0])))
    return SDL_Keycode(std::tolower(static_cast<unsigned char>(name[0])));
  return 0;
}

std::vector<ScriptStep> parse_script(const std::string& script, std::string_view what = "script") {
  std::vector<ScriptStep> steps;
  std::size_t at = 0;
  while (at < script.size()) {
    const std::size_t end = std::min(script.find(',', at), script.size());
    const std::string token = script.substr(at, end - at);
    at = end + 1;
    auto bad = [&](const std::string& why) {
      return Error(std::string(what) + ": '" + token + "' " + why +
                   " (expected KEY, KEY*N, mouse:DX:DY, size:W:H, wait*N, screenshot or Escape; docs/viewer.md)");
    };
    ScriptStep step;
    std::string name = token;
    if (const auto star = token.find('*'); star != std::string::npos) {
      name = token.substr(0, star);
      const std::string count = token.substr(star + 1);
      if (count.empty() || count.size() > 5 || count.find_first_not_of("0123456789") != std::string::npos)
        throw bad("has no frame count 1 .. 99999 after '*'");
      step.frames = std::stoi(count);
      if (step.frames < 1) throw bad("has no frame count 1 .. 99999 after '*'");
    }
    if (name.rfind("mouse:", 0) == 0) {
      int dx = 0, dy = 0;
      char tail = 0;
      if (std::sscanf(name.c_str() + 6, "%d:%d%c", &dx, &dy, &tail) != 2 || std::abs(dx) > 10000 ||
          std::abs(dy) > 10000)
        throw bad("is not mouse:DX:DY in pixels");
      step.kind = ScriptStep::mouse;
      step.dx = dx;
      step.dy = dy;
    } else if (name.rfind("size:", 0) == 0) {
      int w = 0, h = 0;
      char tail = 0;
      if (std::sscanf(name.c_str() + 5, "%d:%d%c", &w, &h, &tail) != 2 || w < 16 || h < 16 || w > 16384 || h > 16384)
        throw bad("is not size:WIDTH:HEIGHT, 16 .. 16384 pixels each");
      step.kind = ScriptStep::resize;
      step.dx = w;
      step.dy = h;
    } else if (name == "wait") {
      step.kind = ScriptStep::wait;
    } else {
      step.code = script_key(name);
      if (step.code == 0) throw bad("is not a key");
    }
    steps.push_back(step);
  }
  return steps;
}

// ---- a tiny bitmap font (3 x 5 pixels per glyph) for the on-screen figures ------------------

std::uint16_t glyph(char c) {
  // Five rows of three bits, top row in the high bits.
  switch (c) {
    case '0':
      return 0b111101101101111;
    case '1':
      return 0b010110010010111;
    case '2':
      return 0b111001111100111;
    case '3':
      return 0b111001111001111;
    case '4':
      return 0b101101111001001;
    case '5':
      return 0b111100111001111;
    case '6':
      return 0b111100111101111;
    case '7':
      return 0b111001010010010;
    case '8':
      return 0b111101111101111;
    case '9':
      return 0b111101111001111;
    case '.':
      return 0b000000000000010;
    case '/':
      return 0b001001010100100;
    case 'M':
      return 0b101111111101101;
    case 'S':
      return 0b111100111001111;
    case 'D':
      return 0b110101101101110;
    case 'P':
      return 0b111101111100100;
    case 'W':
      return 0b101101111111101;
    case 'A':
      return 0b111101111101101;
    case 'L':
      return 0b100100100100111;
    case 'K':
      return 0b101110100110101;
    case 'F':
      return 0b111100111100100;
    case 'E':
      return 0b111100111100111;
    case 'Y':
      return 0b101101010010010;
    case 'X':
      return 0b101101010101101;
    case 'N':
      return 0b110101101101101;
    case 'T':
      return 0b111010010010010;
    case 'I':
      return 0b111010010010111;
    case '%':
      return 0b101001010100101;
    default:
      return 0;
  }
}

void draw_text(ImageRgb8& image, int x, int y, const std::string& text, int scale) {
  for (char c : text) {
    const std::uint16_t g = glyph(c);
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col) {
        const bool on = (g >> (14 - (row * 3 + col))) & 1;
        // A dark outline box behind lit pixels keeps the text readable on a bright sky.
        image.fill_rect(x + col * scale, y + row * scale, scale, scale, on ? Rgb8{255, 255, 255} : Rgb8{20, 20, 20});
      }
    x += 4 * scale;
  }
}

struct Walker {
  Camera camera;
  bool moved = false;  // until the first move the start camera is used as given (the offline frame's)
  double yaw = 0, pitch = 0;
  bool fly = false;
  double speed = 1.4;  // meters per second

  explicit Walker(const Camera& start) : camera(start) {
    const double dx = start.target[0] - start.position[0], dy = start.target[1] - start.position[1],
                 dz = start.target[2] - start.position[2];
    yaw = std::atan2(dy, dx);
    pitch = std::atan2(dz, std::hypot(dx, dy));
  }
  void update(const ViewWorld& world, const std::unordered_set<SDL_Keycode>& held, double dt, int mouse_dx,
              int mouse_dy) {
    auto down = [&](SDL_Keycode k) { return held.count(k) != 0; };
    double forward = (down(SDLK_w) ? 1 : 0) - (down(SDLK_s) ? 1 : 0);
    double side = (down(SDLK_d) ? 1 : 0) - (down(SDLK_a) ? 1 : 0);
    double rise = fly ? (down(SDLK_SPACE) ? 1 : 0) - (down(SDLK_c) ? 1 : 0) : 0;
    if (forward == 0 && side == 0 && rise == 0 && mouse_dx == 0 && mouse_dy == 0) return;
    moved = true;
    yaw -= mouse_dx * 0.003;
    pitch = std::clamp(pitch - mouse_dy * 0.003, -1.45, 1.45);
    const double step = speed * dt * (down(SDLK_LSHIFT) ? 4 : 1);
    auto& p = camera.position;
    const double c = std::cos(yaw), s = std::sin(yaw);
    if (fly) {
      p[0] += step * (forward * c * std::cos(pitch) + side * s);
      p[1] += step * (forward * s * std::cos(pitch) - side * c);
      p[2] += step * (forward * std::sin(pitch) + rise);
    } else {
      p[0] += step * (forward * c + side * s);
      p[1] += step * (forward * s - side * c);
    }
    const double ground = world.ground_height(p[0], p[1], p[2] - world.pack().info().head_height);
    const double eye = ground + world.pack().info().head_height;
    if (!fly || p[2] < eye) p[2] = eye;  // walking stays on the ground, flying stays above it
    p = world.clear_of_stems(p);         // and out of the stems, sliding along them
    camera.target = {p[0] + 100 * c * std::cos(pitch), p[1] + 100 * s * std::cos(pitch), p[2] + 100 * std::sin(pitch)};
  }
};

struct SdlSession {
  SDL_Window* window = nullptr;
  SDL_Renderer* renderer = nullptr;
  SDL_Texture* texture = nullptr;
  SdlSession(int w, int h) {
    if (SDL_Init(SDL_INIT_VIDEO) != 0)
      throw Error(std::string("view: cannot open a window (SDL: ") + SDL_GetError() +
                  "); without a display the view draws offline frames only");
    window =
        SDL_CreateWindow("wangscape view", SDL_WINDOWPOS_CENTERED, SDL_WINDOWPOS_CENTERED, w, h, SDL_WINDOW_RESIZABLE);
    if (window) renderer = SDL_CreateRenderer(window, -1, 0);
    if (renderer) make_texture(w, h);
    if (!texture) {
      const std::string why = SDL_GetError();
      release();
      throw Error("view: cannot open a window (SDL: " + why + ")");
    }
  }
  ~SdlSession() { release(); }
  void make_texture(int w, int h) {
    if (texture) SDL_DestroyTexture(texture);
    texture = SDL_CreateTexture(renderer, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING, w, h);
    if (!texture)
      throw Error(std::string("view: cannot make a frame of ") + std::to_string(w) + "x" + std::to_string(h) +
                  " (SDL: " + SDL_GetError() + ")");
  }
  void release() {
    if (texture) SDL_DestroyTexture(texture);
    if (renderer) SDL_DestroyRenderer(renderer);
    if (window) SDL_DestroyWindow(window);
    texture = nullptr;
    renderer = nullptr;
    window = nullptr;
    SDL_Quit();
  }
  SdlSession(const SdlSession&) = delete;
  SdlSession& operator=(const SdlSession&) = delete;
};

void push_key(SDL_Keycode code, bool pressed) {
  SDL_Event e{};
  e.type = pressed ? SDL_KEYDOWN : SDL_KEYUP;
  e.key.state = pressed ? SDL_PRESSED : SDL_RELEASED;
  e.key.keysym.sym = code;
  e.key.keysym.scancode = SDL_GetScancodeFromKey(code);
  SDL_PushEvent(&e);
}

}  // namespace

void check_view_script(const std::string& script, std::string_view what) { parse_script(script, what); }

bool display_available() {
  const auto set = [](const char* name) {
    const char* v = std::getenv(name);
    return v != nullptr && *v != 0;
  };
  return set("DISPLAY") || set("WAYLAND_DISPLAY") || set("SDL_VIDEODRIVER");
}

namespace {

// The keyframes K drops: the eye by its height above the ground, the point looked at as it is.
class WalkRecorder {
 public:
  void drop(const ViewWorld& world, const Camera& camera, double time) {
    const auto mm = [](double v) { return std::round(v * 1000) / 1000; };     // a file a person edits
    if (!path_.keys.empty() && !(mm(time) > path_.keys.back().time)) return;  // one a millisecond
    const double ground = world.ground_height(camera.position[0], camera.position[1],
                                              camera.position[2] - world.pack().info().head_height);
    PathKeyframe key;
    key.time = mm(time);
    key.position = {mm(camera.position[0]), mm(camera.position[1]), mm(std::max(camera.position[2] - ground, 0.0))};
    key.look_at = {mm(camera.target[0]), mm(camera.target[1]), mm(camera.target[2])};
    path_.keys.push_back(key);
  }
  std::size_t size() const { return path_.keys.size(); }
  // Writes the walk to `file` when it has two keyframes or more (a path); what was recorded.
  RecordedWalk write(const std::filesystem::path& file) {
    RecordedWalk walk{file, path_.keys.size(), 0, false};
    if (path_.keys.size() < 2) return walk;
    path_.position_above_ground = true;
    write_file_atomically(file, view_path_json(path_));
    walk.seconds = path_.duration();
    walk.written = true;
    return walk;
  }

 private:
  ViewPath path_;
};

}  // namespace

void run_view_window(std::shared_ptr<const ViewWorld> world, const ViewWindowOptions& options) {
  const std::vector<ScriptStep> script = parse_script(options.script);
  LdiRenderer renderer(world, options.width, options.height);
  renderer.apply(options.settings);
  FrameBudget budget;
  budget.fps = options.fps;
  budget.adaptive = script.empty();
  FrameCache cache(renderer, budget);
  SdlSession sdl(options.width, options.height);
  if (options.script.empty()) SDL_SetRelativeMouseMode(SDL_TRUE);  // mouse look (a script moves it itself)

  Walker walker(options.camera);
  std::unordered_set<SDL_Keycode> held;
  ImageRgb8 shown(options.width, options.height);
  WalkRecorder recorder;
  double walk_time = 0;
  int screenshots = 0;
  std::size_t next_step = 0;
  int step_frames_left = 0;
  const bool scripted = !script.empty();
  auto last = std::chrono::steady_clock::now();
  double shown_ms = 0, shown_fresh = 0;
  for (bool running = true; running;) {
    // The script: each step's events go into SDL's queue, keys are released when it ends.
    if (scripted && step_frames_left == 0) {
      if (next_step > 0 && script[next_step - 1].kind == ScriptStep::key) push_key(script[next_step - 1].code, false);
      if (next_step == script.size()) {
        push_key(SDLK_ESCAPE, true);  // the script's end closes the window
      } else {
        const ScriptStep& step = script[next_step++];
        step_frames_left = step.frames;
        if (step.kind == ScriptStep::key) push_key(step.code, true);
        if (step.kind == ScriptStep::resize) SDL_SetWindowSize(sdl.window, step.dx, step.dy);  // as a user drags
        if (step.kind == ScriptStep::mouse) {
          SDL_Event e{};
          e.type = SDL_MOUSEMOTION;
          e.motion.xrel = step.dx;
          e.motion.yrel = step.dy;
          SDL_PushEvent(&e);
        }
      }
    }
    if (step_frames_left > 0) --step_frames_left;

    int mouse_dx = 0, mouse_dy = 0;
    bool screenshot = false, keyframe = false;
    int new_width = 0, new_height = 0;
    for (SDL_Event e; SDL_PollEvent(&e);) {
      if (e.type == SDL_QUIT) running = false;
      if (e.type == SDL_WINDOWEVENT && e.window.event == SDL_WINDOWEVENT_SIZE_CHANGED) {
        new_width = std::clamp(e.window.data1, 16, 16384);
        new_height = std::clamp(e.window.data2, 16, 16384);
      }
      if (e.type == SDL_MOUSEMOTION) {
        mouse_dx += e.motion.xrel;
        mouse_dy += e.motion.yrel;
      }
      if (e.type == SDL_KEYUP) held.erase(e.key.keysym.sym);
      if (e.type != SDL_KEYDOWN) continue;
      const SDL_Keycode k = e.key.keysym.sym;
      if (!e.key.repeat) held.insert(k);
      if (k == SDLK_ESCAPE) running = false;
      if (k == SDLK_f && !e.key.repeat) walker.fly = !walker.fly;
      if (k == SDLK_EQUALS || k == SDLK_PLUS || k == SDLK_KP_PLUS) walker.speed = std::min(walker.speed * 2, 400.0);
      if (k == SDLK_MINUS || k == SDLK_KP_MINUS) walker.speed = std::max(walker.speed / 2, 0.1);
      if (k == SDLK_F12 && !e.key.repeat) screenshot = true;
      if (k == SDLK_k && !e.key.repeat) keyframe = true;
    }
    if (!running) break;
    if (new_width > 0 && (new_width != renderer.width() || new_height != renderer.height())) {
      // Frames at the window's new size (not the old frame stretched).
      renderer.resize(new_width, new_height);
      sdl.make_texture(new_width, new_height);
      shown = ImageRgb8(new_width, new_height);
    }
    const auto now = std::chrono::steady_clock::now();
    const double dt = scripted ? 1.0 / 30 : std::min(0.25, std::chrono::duration<double>(now - last).count());
    last = now;
    walker.update(*world, held, dt, mouse_dx, mouse_dy);
    walk_time += dt;
    if (keyframe) recorder.drop(*world, walker.camera, walk_time);

    const CachedFrameStats& stats = cache.render(walker.camera);
    if (screenshot) {
      // The next free number: an earlier run's screenshots in the folder are kept.
      std::filesystem::path file;
      do {
        char name[32];
        std::snprintf(name, sizeof name, "view-%04d.png", ++screenshots);
        file = options.screenshot_dir / name;
      } while (std::filesystem::exists(file));
      write_image(file, cache.image());  // the frame, without the overlay
      if (options.on_screenshot) options.on_screenshot(file);
    }
    // The overlay: a smoothed frame time and share of the pixels traced anew.
    shown_ms = shown_ms == 0 ? stats.frame_ms : shown_ms * 0.9 + stats.frame_ms * 0.1;
    const double fresh = 100 * stats.fresh_share();
    shown_fresh = shown_fresh == 0 ? fresh : shown_fresh * 0.9 + fresh * 0.1;
    shown.pixels = cache.image().pixels;
    char text[80];
    std::snprintf(text, sizeof text, "%.1f MS  %.0f%% NEW  %s%s%s", shown_ms, shown_fresh, walker.fly ? "FLY" : "WALK",
                  stats.still_frames > 0 ? "  STILL" : "",
                  recorder.size() ? ("  KEYS " + std::to_string(recorder.size())).c_str() : "");
    draw_text(shown, 6, 6, text, 2);
    SDL_UpdateTexture(sdl.texture, nullptr, shown.pixels.data(), shown.width * 3);
    SDL_RenderClear(sdl.renderer);
    SDL_RenderCopy(sdl.renderer, sdl.texture, nullptr, nullptr);
    SDL_RenderPresent(sdl.renderer);
  }
  if (recorder.size() > 0) {
    const RecordedWalk walk = recorder.write(options.record);
    if (options.on_recorded) options.on_recorded(walk);
  }
}

}  // namespace wangscape
