#include "torrance/bsdfs/albedo.h"

#include "torrance/util/sampling.h"

namespace torrance {

double directional_albedo_quadrature(const MaterialBsdf& bsdf, const Vec3& wo, float alpha, int n_theta, int n_phi) {
  if (wo.z <= 0.0f) return 0.0;
  const double split = std::atan(8.0 * std::max(double(alpha), 1e-4));
  const double half_pi = M_PI / 2;
  double sum = 0.0;
  // Two theta_h ranges, each with the midpoint rule: [0, split] mapped so that points crowd near
  // the peak (theta = split * u^2), and [split, pi/2] uniform.
  for (int part = 0; part < 2; ++part)
    for (int i = 0; i < n_theta; ++i) {
      const double u = (i + 0.5) / n_theta;
      double theta, dtheta;
      if (part == 0) {
        theta = split * u * u;
        dtheta = split * 2 * u / n_theta;
      } else {
        theta = split + (half_pi - split) * u;
        dtheta = (half_pi - split) / n_theta;
      }
      const double sin_t = std::sin(theta), cos_t = std::cos(theta);
      for (int j = 0; j < n_phi; ++j) {
        const double phi = (j + 0.5) / n_phi * 2 * M_PI;
        const Vec3 h(float(sin_t * std::cos(phi)), float(sin_t * std::sin(phi)), float(cos_t));
        const float wo_h = glm::dot(wo, h);
        if (wo_h <= 0.0f) continue;
        const Vec3 wi = 2.0f * wo_h * h - wo;
        if (wi.z <= 0.0f) continue;
        const double dw_h = sin_t * dtheta * (2 * M_PI / n_phi);
        sum += double(bsdf.eval(wo, wi).x) * 4.0 * wo_h * dw_h;
      }
    }
  return sum;
}

double directional_albedo_sampled(const MaterialBsdf& bsdf, const Vec3& wo, int n, uint32_t seed) {
  double sum = 0.0;
  Rng rng(seed, 0, 77);
  for (int i = 0; i < n; ++i) {
    const float u = rng.next_1d();
    const BsdfSample s = bsdf.sample(wo, u, rng.next_2d());
    if (s.valid()) sum += s.weight.x;
  }
  return sum / n;
}

}  // namespace torrance
