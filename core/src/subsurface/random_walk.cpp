#include "torrance/subsurface/random_walk.h"

#include "torrance/media/henyey_greenstein.h"
#include "torrance/bsdfs/microfacet.h"
#include "torrance/subsurface/albedo_inversion.h"
#include "torrance/subsurface/dwivedi_guide.h"

#include <algorithm>
#include <cmath>

namespace torrance {

namespace {

constexpr float kMinAlpha = 0.2f;              // Cycles' min_alpha
constexpr int kSimilaritySteps = 10;           // steps 0..9 keep the anisotropy
constexpr float kThroughputEpsilon = 1e-6f;    // Cycles' VOLUME_THROUGHPUT_EPSILON

// The walk's coefficients: extinction, scattering, their similarity-reduced forms, the
// single-scattering albedo channels are chosen by.
struct Coefficients {
  Vec3 sigma_t, sigma_s, sigma_t_reduced, sigma_s_reduced, alpha;
};

Coefficients coefficients(const SubsurfaceLobe& lobe, Vec3& throughput) {
  const float g = lobe.anisotropy;
  const Vec3 radius = lobe.fixed_radius   ? lobe.radius * (0.25f / kPi)
                      : lobe.plain_radius ? lobe.radius
                                          : walk_radius(lobe.radius, lobe.albedo, lobe.ior);
  const WalkMedium medium = lobe.van_de_hulst ? van_de_hulst_medium(lobe.albedo, radius, g)
                                              : walk_medium(lobe.albedo, radius, g);
  Coefficients k;
  k.sigma_t = medium.sigma_t;
  k.alpha = medium.alpha;
  for (int c = 0; c < 3; ++c) {
    throughput[c] = lobe.albedo[c] != 0.0f ? throughput[c] / lobe.albedo[c] : 0.0f;
    if (k.alpha[c] < kMinAlpha) {
      throughput[c] *= k.alpha[c] / kMinAlpha;
      k.alpha[c] = kMinAlpha;
    }
  }
  k.sigma_s = k.sigma_t * k.alpha;
  k.sigma_s_reduced = k.sigma_s * (1.0f - g);
  k.sigma_t_reduced = k.sigma_t - k.sigma_s + k.sigma_s_reduced;
  return k;
}

// The channel a flight's distance is drawn for, chosen by |throughput x alpha|; pdf: each
// channel's probability.
int choose_channel(const Vec3& throughput, const Vec3& alpha, float u, Vec3& pdf) {
  const Vec3 w = glm::abs(throughput * alpha);
  const float sum = w.x + w.y + w.z;
  pdf = sum > 0.0f ? w / sum : Vec3(1.0f / 3.0f);
  float cdf = 0.0f;
  for (int c = 0; c < 2; ++c) {
    cdf += pdf[c];
    if (u < cdf) return c;
  }
  return 2;
}

// A direction at cos_theta from axis n, azimuth 2 pi u.
Vec3 direction_about(const Vec3& n, float cos_theta, float u) {
  const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
  const float phi = 2.0f * kPi * u;
  return Frame(n).to_world(Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta));
}

// Per channel: the density of a flight of length t with extinction sigma_t ending there (or,
// reaching the surface, its probability).
Vec3 flight_density(const Vec3& sigma_t, float t, bool hit) {
  const Vec3 transmittance = glm::exp(-sigma_t * t);
  return hit ? transmittance : sigma_t * transmittance;
}

// One step's direction and the factors of its flight's mixture density (Cycles' classic and
// guided strategies): guided with probability `guided`, backwards with `backward`.
struct StepDirection {
  Vec3 dir;
  float forward_factor = 0.0f, backward_factor = 0.0f;  // guided pdf / classic pdf
  float forward_stretch = 1.0f, backward_stretch = 1.0f;
  float sample_stretch = 1.0f;  // the stretch the flight's distance is drawn with
};

StepDirection next_direction(const Vec3& dir, const Vec3& normal, float g, const DwivediGuide& guide, bool guided,
                             bool backward, Rng& rng) {
  StepDirection d;
  const Vec2 u = rng.next_2d();
  const HenyeyGreenstein phase(g);
  float cos_theta, hg_pdf;
  if (guided) {
    cos_theta = guide.sample(u.x);
    if (backward) cos_theta = -cos_theta;
    d.dir = direction_about(normal, cos_theta, u.y);
    hg_pdf = phase.pdf(-dir, d.dir);
  } else {
    const PhaseSample ps = phase.sample(-dir, u);
    d.dir = ps.wi;
    hg_pdf = ps.pdf;
    cos_theta = glm::dot(d.dir, normal);
  }
  d.forward_factor = guide.pdf(cos_theta) / hg_pdf;
  d.backward_factor = guide.pdf(-cos_theta) / hg_pdf;
  d.forward_stretch = guide.stretch(cos_theta);
  d.backward_stretch = guide.stretch(-cos_theta);
  if (guided) d.sample_stretch = backward ? d.backward_stretch : d.forward_stretch;
  return d;
}

// The first direction into the mesh (false: none): Lambertian, or Cycles 4.x's rough refraction.
bool entry_direction(const SubsurfaceLobe& lobe, const Vec3& normal, const Vec3& incoming, Rng& rng, Vec3& dir) {
  Vec2 u = rng.next_2d();
  bool lambertian = lobe.entry_alpha < 0.0f;
  if (lobe.entry_half_lambertian) {
    lambertian = u.x < 0.5f;
    u.x = lambertian ? 2.0f * u.x : 2.0f * (u.x - 0.5f);
  }
  if (lambertian) {
    dir = Frame(-normal).to_world(sample_cosine_hemisphere(u));
    return true;
  }
  const Frame frame(normal);
  const Vec3 wi = frame.to_local(incoming);
  if (wi.z <= 0.0f) return false;
  const Vec3 h = ggx::sample_visible_normal(wi, std::max(lobe.entry_alpha, 1e-4f), u);
  const float eta = 1.0f / lobe.ior, cos_h = glm::dot(h, wi);
  const float root = std::sqrt(std::max(1.0f - eta * eta * (1.0f - cos_h * cos_h), 0.0f));
  dir = frame.to_world(glm::normalize(-eta * wi + (eta * cos_h - std::max(root, 1e-7f)) * h));
  return true;
}

}  // namespace

WalkExit random_walk(WalkBoundary& boundary, const SubsurfaceLobe& lobe, const Vec3& position, const Vec3& normal,
                     const Vec3& geometric_normal, const Vec3& incoming, float origin_offset,
                     const Vec3& throughput, Rng& rng) {
  WalkExit out;
  // Into the mesh (a Lambertian transmission: its cosine and pdf cancel; a refraction: weight 1).
  Vec3 dir;
  if (!entry_direction(lobe, normal, incoming, rng, dir) || glm::dot(dir, -geometric_normal) <= 0.0f) return out;

  Vec3 beta = throughput;
  const Coefficients k = coefficients(lobe, beta);
  const DwivediGuide guide(max_component(k.alpha));
  if (!guide.usable()) return out;  // Cycles: no walk at all (its guide would be infinite)
  // Cycles' heuristic share of guided steps (isotropic past the similarity steps: 0.75).
  const float guided_share = 1.0f - std::max(0.5f, std::pow(std::abs(lobe.anisotropy), 0.125f));
  bool opposite = false;  // an opposite side was found within reach of the first flight
  float opposite_distance = 0.0f;
  Vec3 p = position - origin_offset * geometric_normal;
  for (int step = 0; step < kMaxWalkSteps; ++step) {
    const bool reduced = step >= kSimilaritySteps;
    const Vec3& sigma_t = reduced ? k.sigma_t_reduced : k.sigma_t;
    const Vec3& sigma_s = reduced ? k.sigma_s_reduced : k.sigma_s;
    const float guided_fraction = reduced ? 0.75f : guided_share;

    Vec3 channel_pdf;
    const int channel = choose_channel(beta, k.alpha, rng.next_1d(), channel_pdf);
    const float u_distance = rng.next_1d();
    StepDirection d;
    float backward_fraction = 0.0f;
    if (step > 0) {
      const bool guided = rng.next_1d() < guided_fraction;
      bool backward = false;
      if (opposite) {  // towards the far side, the more the deeper the walk is already
        const float x = std::clamp(glm::dot(p - position, -normal), 0.0f, opposite_distance);
        backward_fraction = 1.0f / (1.0f + std::exp((opposite_distance - 2.0f * x) / guide.v));
        backward = rng.next_1d() < backward_fraction;
      }
      d = next_direction(dir, normal, reduced ? 0.0f : lobe.anisotropy, guide, guided, backward, rng);
      dir = d.dir;
    }
    float t = -std::log(1.0f - u_distance) / (sigma_t[channel] * d.sample_stretch);
    float t_surface = 0.0f;
    bool hit;
    if (step == 0) {  // looks 10 mean free paths ahead for the opposite side
      const float reach = std::max(t, 10.0f / std::min(sigma_t.x, std::min(sigma_t.y, sigma_t.z)));
      opposite = boundary.nearest(p, dir, reach, t_surface);
      if (opposite) opposite_distance = glm::dot(p + t_surface * dir - position, -normal);
      hit = opposite && t_surface < t;
    } else {
      hit = boundary.nearest(p, dir, t, t_surface);
    }
    if (hit) t = t_surface;
    p += t * dir;

    Vec3 density = flight_density(sigma_t, t, hit);
    if (step > 0) {  // the mixture of the classic, guided and backward-guided strategies
      Vec3 guided_density = flight_density(d.forward_stretch * sigma_t, t, hit) * d.forward_factor;
      if (opposite)
        guided_density = glm::mix(guided_density,
                                  flight_density(d.backward_stretch * sigma_t, t, hit) * d.backward_factor,
                                  backward_fraction);
      density = glm::mix(density, guided_density, guided_fraction);
    }
    const Vec3 transmittance = glm::exp(-sigma_t * t);
    beta *= (hit ? transmittance : sigma_s * transmittance) / glm::dot(channel_pdf, density);
    out.steps = step + 1;
    if (hit) {
      out.exited = std::isfinite(beta.x) && std::isfinite(beta.y) && std::isfinite(beta.z);
      out.position = p;
      out.direction = dir;
      out.throughput = beta;
      return out;
    }
    if (max_component(beta) < kThroughputEpsilon) return out;
  }
  return out;
}

}  // namespace torrance
