#include "film/shadow_catcher.h"

#include <algorithm>

namespace torrance {

namespace {

// The channels' offsets in ShadowCatcherValues.
constexpr int kMatte = 0, kMatteAlpha = 3, kCatcher = 4, kSplits = 7, kBackground = 8;

float mean3(const Vec3& v) { return (v.x + v.y + v.z) / 3.0f; }
float saturate(float x) { return std::min(std::max(x, 0.0f), 1.0f); }

}  // namespace

ShadowCatcherValues shadow_catcher_values(const ShadowCatcherSample& s, const Vec3& combined, float alpha,
                                          const Vec3& environment) {
  ShadowCatcherValues v{};
  // Cycles: the split leaves the matte the sample's throughput as transparency
  // (film_write_shadow_catcher_bounce_data); a path that never splits is all matte.
  const Vec3 matte = s.split ? s.before_split : combined;
  const Vec3 background = s.split ? s.background : environment;
  const Vec3 catcher = s.split ? s.catcher : Vec3(0.0f);
  const float matte_alpha = s.split ? s.alpha_at_split - mean3(s.throughput) : alpha;
  for (int c = 0; c < 3; ++c) {
    v[size_t(kMatte + c)] = matte[c];
    v[size_t(kCatcher + c)] = catcher[c];
    v[size_t(kBackground + c)] = background[c];
  }
  v[kMatteAlpha] = matte_alpha;
  v[kSplits] = s.split ? 1.0f : 0.0f;
  return v;
}

Vec3 shadow_catcher_pass(const double* combined, const double* catcher) {
  if (!(catcher[kSplits] > 0.0)) return Vec3(1.0f);  // no catcher in this pixel
  // The matte's light taken off Combined: what the split paths brought with the CG objects.
  Vec3 ratio;
  for (int c = 0; c < 3; ++c) {
    const double with_objects = combined[c] - catcher[kMatte + c];
    const double without = catcher[kCatcher + c];
    ratio[c] = without != 0.0 ? float(with_objects / without) : 1.0f;
  }
  const float alpha = saturate(float(combined[3]));
  return (1.0f - alpha) * Vec3(1.0f) + alpha * ratio;  // over white by Combined's alpha
}

std::array<float, 4> shadow_catcher_combined(const ShadowCatcherOutput& out, const double* combined,
                                             const double* catcher) {
  const Vec3 matte{float(catcher[kMatte]), float(catcher[kMatte + 1]), float(catcher[kMatte + 2])};
  const float alpha = saturate(float(catcher[kMatteAlpha]));
  if (!out.approximate) return {matte.x, matte.y, matte.z, alpha};
  const Vec3 shadow = shadow_catcher_pass(combined, catcher);
  const float alpha_matte = (1.0f - alpha) * (1.0f - saturate(mean3(shadow))) + alpha;
  if (out.transparent_film) return {matte.x, matte.y, matte.z, alpha_matte};
  // An opaque film: the matte over the world behind it, darkened by the shadow.
  const Vec3 background{float(catcher[kBackground]), float(catcher[kBackground + 1]),
                        float(catcher[kBackground + 2])};
  const Vec3 over = matte + background * (1.0f - alpha_matte);
  return {over.x, over.y, over.z, 1.0f};
}

}  // namespace torrance
