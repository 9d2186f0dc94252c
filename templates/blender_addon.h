// The Wangscape Blender add-on (templates/blender_addon/wangscape_import), embedded at build
// time so exporters can write the installable zip next to a Blender export.
#pragma once

#include <span>
#include <string_view>

namespace wangscape {

struct EmbeddedFile {
  std::string_view path;      // inside the zip, e.g. "wangscape_import/__init__.py"
  std::string_view contents;  // UTF-8 text
};

// The add-on's files, in a fixed order.
std::span<const EmbeddedFile> blender_addon_files();

}  // namespace wangscape
