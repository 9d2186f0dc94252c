// The window of `wangscape view DIR` (SDL2): walk at head height over the terrain or fly,
// mouse look, speed keys, an on-screen frame time and depth-pixel rate, screenshots, keyframes
// recorded into a path file; resizable (frames are drawn at the window's size). A script
// of key presses (docs/viewer.md) is pushed into SDL's own event queue, so tests drive the
// same event path a user does (under Xvfb). Takes typed options and prints nothing: the program
// (cli/cmd_view.cpp) fills them and reports what the window wrote through their callbacks.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "renders/view/frame_cache.h"
#include "renders/view/ldi_renderer.h"

namespace wangscape {

inline constexpr int kDefaultWindowWidth = 1280, kDefaultWindowHeight = 720;

// The keyframes K dropped in a window, as it closes.
struct RecordedWalk {
  std::filesystem::path file;  // where they were written (ViewWindowOptions::record)
  std::size_t keyframes = 0;
  double seconds = 0;    // from the first to the last
  bool written = false;  // two or more: a path file; one is not a path, and nothing is written
};

struct ViewWindowOptions {
  Camera camera;  // where the window opens
  int width = 640, height = 360;
  ViewSettings settings;
  // The rate to hold: each frame traces anew what its share of 1000 / fps ms allows (FrameCache),
  // sized by the window's own clock, or, under a script, by the nominal costs (the frames of a
  // path played offline at the same rate).
  double fps = kDefaultViewFps;
  // "W*30,mouse:40:0,screenshot,Escape": KEY*N holds KEY for N frames, KEY alone one frame,
  // mouse:DX:DY moves the mouse, screenshot presses F12, wait*N waits N frames. Scripted
  // frames advance time by 1/30 s each, so a script gives the same frames on any machine.
  std::string script;
  std::filesystem::path screenshot_dir = ".";  // F12 writes view-0001.png, view-0002.png, ...
  // K drops a keyframe of the walk (the eye by its height above the ground); on exit, two or more
  // are written here as a path file (scene/view_path.h) that a path playback replays.
  std::filesystem::path record = "path.json";
  // What the window wrote, for the program to report: each screenshot as it is written, and on
  // exit the walk K recorded (when K was pressed at all).
  std::function<void(const std::filesystem::path& screenshot)> on_screenshot;
  std::function<void(const RecordedWalk& walk)> on_recorded;
};

// Opens the window at options.camera and runs until Escape, the window's close button or the end
// of the script. Throws Error when SDL cannot open a window (no display) or the script is bad.
void run_view_window(std::shared_ptr<const ViewWorld> world, const ViewWindowOptions& options);

// False when there is no display to open a window on (no DISPLAY and no WAYLAND_DISPLAY, unless
// SDL_VIDEODRIVER names a driver): SDL would wait rather than fail.
bool display_available();

// The moves a script asks for, checked without a display (tests, the program's early refusal).
// Throws Error naming `what` (the script's source) and the token at fault.
void check_view_script(const std::string& script, std::string_view what = "script");

}  // namespace wangscape
