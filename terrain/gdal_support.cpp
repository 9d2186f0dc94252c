#include "terrain/gdal_support.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal.h>

#include <mutex>

namespace wangscape::gdal_support {

void ensure_registered() {
  static std::once_flag once;
  std::call_once(once, [] {
    CPLSetErrorHandler(CPLQuietErrorHandler);
    // No .aux.xml side files: never written next to the user's DEMs, never read (a stray
    // one must not change what a DEM means).
    CPLSetConfigOption("GDAL_PAM_ENABLED", "NO");
    GDALAllRegister();
  });
}

namespace {
void CPL_STDCALL collect(CPLErr level, CPLErrorNum, const char* message) {
  if (level < CE_Warning || message == nullptr) return;  // debug chatter
  auto* capture = static_cast<ErrorCapture*>(CPLGetErrorHandlerUserData());
  if (capture != nullptr) capture->add(message);
}
}  // namespace

ErrorCapture::ErrorCapture() {
  ensure_registered();
  CPLPushErrorHandlerEx(collect, this);
}

ErrorCapture::~ErrorCapture() { CPLPopErrorHandler(); }

void ErrorCapture::add(std::string message) {
  for (const auto& m : messages_)
    if (m == message) return;
  messages_.push_back(std::move(message));
}

std::string ErrorCapture::messages() const {
  std::string joined;
  for (const auto& m : messages_) {
    if (!joined.empty()) joined += "; ";
    joined += m;
  }
  return joined;
}

std::string ErrorCapture::suffix() const {
  const std::string m = messages();
  return m.empty() ? std::string() : " (GDAL: " + m + ")";
}

}  // namespace wangscape::gdal_support
