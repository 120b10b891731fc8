// TEMPORARY (wt-C A/B measurement, removed before merge): the old code paths when the
// environment variable TORRANCE_AB_OLD is set at the start of a render.
#pragma once

namespace torrance {
inline bool& ab_old() {
  static bool old = false;
  return old;
}
}  // namespace torrance
