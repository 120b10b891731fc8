#include "torrance/media/mie_phase.h"

#include <algorithm>
#include <cmath>

namespace torrance {

MieFit mie_fit(float d) {
  d = std::isfinite(d) ? std::max(d, 0.0f) : 0.0f;
  MieFit f;
  if (d <= 0.1f) {  // the fit's equations 11-14
    f.g_hg = 13.8f * d * d;
    f.g_draine = 1.1456f * d * std::sin(9.29044f * d);
    f.alpha = 250.0f;
    f.w = 0.252977f - 312.983f * std::pow(d, 4.3f);
  } else if (d < 1.5f) {  // 15-18
    const float l = std::log(d);
    f.g_hg = 0.862f - 0.143f * l * l;
    const float a = (l - 0.238604f) * (l + 1.00667f), b = 0.507522f - 0.15677f * l;
    const float c = 1.19692f * std::cos(a / b) + 1.37932f * l + 0.0625835f;
    f.g_draine = 0.379685f * std::cos(c) + 0.344213f;
    f.alpha = 250.0f;
    f.w = 0.146209f * std::cos(3.38707f * l + 2.11193f) + 0.316072f + 0.0778917f * l;
  } else if (d < 5.0f) {  // 19-22
    const float l = std::log(d), ll = std::log(l);
    f.g_hg = 0.0604931f * ll + 0.940256f;
    f.g_draine = 0.500411f - 0.081287f / (-2.0f * l + std::tan(l) + 1.27551f);
    f.alpha = 7.30354f * l + 6.31675f;
    f.w = 0.026914f * (l - std::cos(5.68947f * (ll - 0.0292149f))) + 0.3764f;
  } else {  // 7-10
    f.g_hg = std::exp(-0.0990567f / (d - 1.67154f));
    f.g_draine = std::exp(-2.20679f / (d + 3.91029f) - 0.428934f);
    f.alpha = std::exp(3.62489f - 8.29288f / (d + 5.52825f));
    f.w = std::exp(-0.599085f / (d - 0.641583f) - 0.665888f);
  }
  return f;
}

MiePhase::MiePhase(float diameter)
    : fit_(mie_fit(diameter)), hg_(fit_.g_hg), draine_(fit_.g_draine, fit_.alpha) {}

float MiePhase::eval(const Vec3& wo, const Vec3& wi) const {
  return (1.0f - fit_.w) * hg_.eval(wo, wi) + fit_.w * draine_.eval(wo, wi);
}

PhaseSample MiePhase::sample(const Vec3& wo, const Vec2& u) const {
  PhaseSample s;
  if (u.x < fit_.w) s = draine_.sample(wo, Vec2(u.x / fit_.w, u.y));
  else s = hg_.sample(wo, Vec2(std::min((u.x - fit_.w) / (1.0f - fit_.w), 0.99999994f), u.y));
  s.pdf = eval(wo, s.wi);
  return s;
}

}  // namespace torrance
