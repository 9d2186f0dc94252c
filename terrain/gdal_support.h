// GDAL plumbing shared by terrain/ sources (not part of the terrain API): one-time driver
// registration, capture of GDAL's error messages so they become Error text instead of chatter on
// stderr, and owning pointers to GDAL's datasets and coordinate transformations.
#pragma once

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <memory>
#include <string>
#include <vector>

namespace wangscape::gdal_support {

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

struct TransformDeleter {
  void operator()(OGRCoordinateTransformation* t) const { OGRCoordinateTransformation::DestroyCT(t); }
};
using TransformPtr = std::unique_ptr<OGRCoordinateTransformation, TransformDeleter>;

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
