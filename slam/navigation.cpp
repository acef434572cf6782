#include "slam/navigation.hpp"

#include <algorithm>
#include <cassert>

namespace msislab {

const HeadingReading& nearest_heading(const std::vector<HeadingReading>& heading, double t_s) {
  assert(!heading.empty());
  auto it = std::lower_bound(heading.begin(), heading.end(), t_s,
                             [](const HeadingReading& h, double t) { return h.t_s < t; });
  if (it == heading.end()) return heading.back();
  if (it != heading.begin() && t_s - std::prev(it)->t_s <= it->t_s - t_s) --it;
  return *it;
}

}  // namespace msislab
