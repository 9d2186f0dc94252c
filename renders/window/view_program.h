// `wangscape view DIR`: the window (renders/window/ldi_window.h) or, when the request asks for
// files or figures, the offline frames of renders/view/view_frames.h.
#pragma once

#include "renders/view/view_frames.h"

namespace wangscape {

// Checks the request, loads the folder once and runs the window or the offline frames.
// Returns the exit code (0). Throws Error for bad input.
int run_view(const ViewRequest& request);

}  // namespace wangscape
