// GDAL plumbing shared by terrain/ sources (not part of the terrain API): one-time driver
// registration, and capture of GDAL's error messages so they become Error text
// instead of chatter on stderr.
#pragma once

#include <string>
#include <vector>

namespace wangscape::gdal_support {

// Registers GDAL's drivers once and silences GDAL's default stderr error printer.
// Thread-safe.
void ensure_registered();

// While alive, collects the errors and warnings GDAL raises on this thread (GDAL keeps
// error handlers per thread) instead of printing them.
class ErrorCapture {
 public:
  ErrorCapture();
  ~ErrorCapture();
  ErrorCapture(const ErrorCapture&) = delete;
  ErrorCapture& operator=(const ErrorCapture&) = delete;

  // The messages so far, joined with "; " (empty if GDAL said nothing).
  std::string messages() const;
  // " (GDAL: <messages>)" or "" when GDAL said nothing: for appending to an error.
  std::string suffix() const;
  void add(std::string message);  // repeated messages are kept once

 private:
  std::vector<std::string> messages_;
};

}  // namespace wangscape::gdal_support
