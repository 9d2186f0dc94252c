// A mean over seeds with its standard error, for the benches that compare scores over many seeds
// (one tiling's score is mostly noise).
#pragma once

#include <algorithm>
#include <cmath>

namespace wangscape::bench {

struct MeanAndError {
  double sum = 0, squares = 0;
  int count = 0;
  void add(double x) {
    sum += x;
    squares += x * x;
    ++count;
  }
  double mean() const { return sum / count; }
  // The standard error of the mean (the sample standard deviation over sqrt(count)).
  double error() const {
    const double variance = (squares - sum * sum / count) / (count - 1);
    return std::sqrt(std::max(variance, 0.0) / count);
  }
};

}  // namespace wangscape::bench
