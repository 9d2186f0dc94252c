// The window of `wangscape view DIR` (SDL2): walk at head height over the terrain or fly,
// mouse look, speed keys, an on-screen frame time and depth-pixel rate, screenshots, keyframes
// recorded into a path file; resizable (frames are drawn at the window's size). A script
// of key presses (docs/viewer.md) is pushed into SDL's own event queue, so tests drive the
// same event path a user does (under Xvfb).
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "renders/view/frame_cache.h"
#include "renders/view/ldi_renderer.h"

namespace wangscape {

inline constexpr int kDefaultWindowWidth = 1280, kDefaultWindowHeight = 720;

struct ViewWindowOptions {
  int width = 640, height = 360;
  ViewSettings settings;
  // The rate to hold: each frame traces anew what its share of 1000 / fps ms allows (FrameCache),
  // sized by the window's own clock, or, under a script, by the nominal costs (the frames of
  // `view --path` at the same rate).
  double fps = kDefaultViewFps;
  // "W*30,mouse:40:0,screenshot,Escape": KEY*N holds KEY for N frames, KEY alone one frame,
  // mouse:DX:DY moves the mouse, screenshot presses F12, wait*N waits N frames. Scripted
  // frames advance time by 1/30 s each, so a script gives the same frames on any machine.
  std::string script;
  std::filesystem::path screenshot_dir = ".";  // F12 writes view-0001.png, view-0002.png, ...
  // K drops a keyframe of the walk (the eye by its height above the ground); on exit, two or more
  // are written here as a path file (renders/view/view_path.h) that `view --path` replays.
  std::filesystem::path record = "path.json";
  bool quiet = false;
};

// Opens the window at `start` and runs until Escape, the window's close button or the end of
// the script. Throws Error when SDL cannot open a window (no display) or the script is bad.
void run_view_window(std::shared_ptr<const ViewWorld> world, const Camera& start, const ViewWindowOptions& options);

// Throws Error at once when there is no display to open a window on (no DISPLAY and no
// WAYLAND_DISPLAY, unless SDL_VIDEODRIVER names a driver): SDL would otherwise wait.
void check_display();

// The moves a script asks for, checked without a display (tests, the CLI's early refusal).
// Throws Error naming the token at fault.
void check_view_script(const std::string& script);

}  // namespace wangscape
