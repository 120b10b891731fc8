#include "torrance/subsurface/burley_disk.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace torrance {

namespace {

constexpr float kTruncateCdf = 0.9963790093708328f;  // cdf(16), Cycles' BURLEY_TRUNCATE_CDF

// x with cdf(x) = xi (Cycles' bssrdf_burley_root_find: its start and 10 Newton steps).
float burley_root(float xi) {
  float x = xi <= 0.9f ? std::exp(xi * xi * 2.4f) - 1.0f : 15.0f;
  for (int i = 0; i < 10; ++i) {
    const float e3 = std::exp(-x / 3.0f), e = e3 * e3 * e3;
    const float f = 1.0f - 0.25f * e - 0.75f * e3 - xi, df = 0.25f * e + 0.25f * e3;
    if (std::abs(f) < 1e-6f || df == 0.0f) break;
    x = std::max(x - f / df, 0.0f);
  }
  return x;
}

Vec3 channel_d(const SubsurfaceLobe& lobe) {
  Vec3 d;
  for (int c = 0; c < 3; ++c) d[c] = lobe.weight[c] > 0.0f ? lobe.radius[c] * (0.25f / kPi) : 0.0f;
  return d;
}

}  // namespace

float burley_eval(float d, float r) {
  if (r >= kBurleyTruncate * d) return 0.0f;
  const float e3 = std::exp(-r / (3.0f * d)), e = e3 * e3 * e3;
  return (e + e3) / (4.0f * d);
}

float burley_pdf(float d, float r) { return r == 0.0f ? 0.0f : burley_eval(d, r) / kTruncateCdf; }

void burley_sample(float d, float xi, float& r, float& h) {
  const float rm = kBurleyTruncate * d;
  r = burley_root(xi * kTruncateCdf) * d;
  h = safe_sqrt(rm * rm - r * r);
}

WalkExit burley_disk(WalkBoundary& boundary, const SubsurfaceLobe& lobe, const Vec3& position, const Vec3& normal,
                     bool backfacing, const Vec3& throughput, Rng& rng) {
  WalkExit out;
  const Vec3 d = channel_d(lobe);
  const int channels = int(d.x > 0.0f) + int(d.y > 0.0f) + int(d.z > 0.0f);
  if (channels == 0) return out;
  Vec2 u = rng.next_2d();
  // The axis: the normal (1/2) or a tangent (1/4 each); pick[k]: the probability of axes[k].
  const Frame frame(normal);
  std::array<Vec3, 3> axes{normal, frame.to_world(Vec3(1.0f, 0.0f, 0.0f)), frame.to_world(Vec3(0.0f, 1.0f, 0.0f))};
  std::array<float, 3> pick{0.5f, 0.25f, 0.25f};
  if (u.y < 0.5f) {
    u.y *= 2.0f;
  } else if (u.y < 0.75f) {
    std::swap(axes[0], axes[1]);
    std::swap(pick[0], pick[1]);
    u.y = (u.y - 0.5f) * 4.0f;
  } else {
    std::swap(axes[0], axes[2]);
    std::swap(pick[0], pick[2]);
    u.y = (u.y - 0.75f) * 4.0f;
  }
  // The channel (reusing u.x) and the point on the disk.
  float xi = u.x * float(channels), sampled = 0.0f;
  for (int c = 0, seen = 0; c < 3; ++c) {
    if (!(d[c] > 0.0f)) continue;
    if (xi < float(seen + 1)) {
      xi -= float(seen);
      sampled = d[c];
      break;
    }
    ++seen;
  }
  float disk_r, height;
  burley_sample(sampled, std::min(xi, 0.99999994f), disk_r, height);
  const float phi = 2.0f * kPi * u.y;
  const Vec3 origin = position + axes[0] * height + disk_r * (std::cos(phi) * axes[1] + std::sin(phi) * axes[2]);

  std::array<ProbeHit, kMaxProbeHits> hits;
  const int found = boundary.probe(origin, -axes[0], 2.0f * height, hits.data(), kMaxProbeHits);
  if (found == 0) return out;
  // At most kBurleyMaxHits of them, a uniform subset (Cycles' reservoir), in the order found.
  std::array<int, kMaxProbeHits> order;
  for (int i = 0; i < found; ++i) order[size_t(i)] = i;
  const int used = std::min(found, kBurleyMaxHits);
  for (int i = 0; i < used && found > kBurleyMaxHits; ++i)
    std::swap(order[size_t(i)], order[size_t(i + int(rng.next_1d() * float(found - i)) % (found - i))]);
  std::sort(order.begin(), order.begin() + used);
  const float pdf_disk = (burley_pdf(d.x, disk_r) + burley_pdf(d.y, disk_r) + burley_pdf(d.z, disk_r)) / float(channels);
  if (!(pdf_disk > 0.0f)) return out;
  std::array<Vec3, kBurleyMaxHits> weights;
  float sum = 0.0f;
  for (int k = 0; k < used; ++k) {
    const ProbeHit& hit = hits[size_t(order[size_t(k)])];
    float pdf_axis[3];
    for (int a = 0; a < 3; ++a) pdf_axis[a] = pick[size_t(a)] * std::abs(glm::dot(axes[size_t(a)], hit.normal));
    float w = pdf_axis[0] / (pdf_axis[0] * pdf_axis[0] + pdf_axis[1] * pdf_axis[1] + pdf_axis[2] * pdf_axis[2]);
    if (found > kBurleyMaxHits) w *= float(found) / float(kBurleyMaxHits);
    const float r = glm::length(origin - axes[0] * hit.t - position);
    const Vec3 eval(burley_pdf(d.x, r), burley_pdf(d.y, r), burley_pdf(d.z, r));
    weights[size_t(k)] = std::isfinite(w) ? eval / pdf_disk * w : Vec3(0.0f);
    sum += (std::abs(weights[size_t(k)].x) + std::abs(weights[size_t(k)].y) + std::abs(weights[size_t(k)].z)) / 3.0f;
  }
  if (!(sum > 0.0f)) return out;
  // One of them in proportion to its mean weight.
  const float target = rng.next_1d() * sum;
  float partial = 0.0f;
  for (int k = 0; k < used; ++k) {
    const Vec3& w = weights[size_t(k)];
    const float mean = (std::abs(w.x) + std::abs(w.y) + std::abs(w.z)) / 3.0f;
    if (target < partial + mean || k == used - 1) {
      if (!(mean > 0.0f)) return out;
      const int index = order[size_t(k)];
      const ProbeHit& hit = hits[size_t(index)];
      boundary.keep(index);
      out.exited = true;
      out.position = origin - axes[0] * hit.t;
      out.direction = backfacing ? -hit.normal : hit.normal;
      out.throughput = throughput * w * (sum / mean);
      out.steps = 1;
      return out;
    }
    partial += mean;
  }
  return out;
}

}  // namespace torrance
