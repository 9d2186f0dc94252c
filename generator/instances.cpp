#include "generator/instances.h"

namespace wangscape {

void InstanceBatch::clear() {
  x.clear();
  y.clear();
  z.clear();
  yaw.clear();
  scale.clear();
  variant.clear();
  tile.clear();
  rank.clear();
}

void InstanceBatch::reserve(std::size_t n) {
  x.reserve(n);
  y.reserve(n);
  z.reserve(n);
  yaw.reserve(n);
  scale.reserve(n);
  variant.reserve(n);
  tile.reserve(n);
  rank.reserve(n);
}

void InstanceBatch::push_back(float px, float py, float pz, float pyaw, float pscale, std::uint16_t pvariant,
                              std::uint32_t ptile, float prank) {
  x.push_back(px);
  y.push_back(py);
  z.push_back(pz);
  yaw.push_back(pyaw);
  scale.push_back(pscale);
  variant.push_back(pvariant);
  tile.push_back(ptile);
  rank.push_back(prank);
}

}  // namespace wangscape
