// A smooth saturation, shared by the section templates and the blend.
#pragma once

#include <cmath>

namespace fairlines::detail {

/// x saturating smoothly toward +-cap (cap > 0): x / (1 + (|x| / cap)^p)^(1/p), about x where
/// |x| << cap; p sets how sharply it bends over.
inline double soft_cap(double x, double cap, double p) {
  return x / std::pow(1.0 + std::pow(std::abs(x) / cap, p), 1.0 / p);
}

}  // namespace fairlines::detail
