#include "refinement.hpp"

#include <algorithm>

namespace prism::viewer {

Refinement::Refinement(int target_spp) : target_(std::max(1, target_spp)) {}

void Refinement::restart() { shown_ = 0; }

std::optional<int> Refinement::next_spp() const {
  if (shown_ == 0) return 1;
  if (shown_ >= target_) return std::nullopt;
  // Doubling: each step halves the noise's variance against the last one.
  return std::min(2 * shown_, target_);
}

void Refinement::rendered(int spp) { shown_ = spp; }

}  // namespace prism::viewer
