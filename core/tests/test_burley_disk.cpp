// Christensen-Burley (core/src/subsurface/burley_disk.cpp, Cycles' disk sampling): the profile's
// eval, pdf and sample agree, and a flat surface returns exactly what enters (a furnace of
// albedo 1 stays 1) whatever the channels' radii, with the probe's three axes.
#include "torrance/subsurface/burley_disk.h"

#include <gtest/gtest.h>

#include <cmath>

namespace torrance {
namespace {

// The half-space z < 0 seen from the probe: the plane z = 0 (normal +z), once.
class Plane : public WalkBoundary {
 public:
  bool nearest(const Vec3&, const Vec3&, float, float&) override { return false; }
  int probe(const Vec3& o, const Vec3& d, float t_max, ProbeHit* hits, int capacity) override {
    if (capacity < 1 || d.z == 0.0f) return 0;
    const float t = -o.z / d.z;
    if (!(t >= 0.0f && t <= t_max)) return 0;
    hits[0].t = t;
    hits[0].normal = Vec3(0.0f, 0.0f, 1.0f);
    return 1;
  }
  void keep(int index) override { kept = index; }
  int kept = -1;
};

// The pdf integrates to 1 over [0, 16 d]; the samples' mean radius is the pdf's.
TEST(BurleyDisk, ProfileSamplesItsPdf) {
  const float d = 0.3f;
  double integral = 0.0, mean = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const float r = (float(i) + 0.5f) / float(n) * kBurleyTruncate * d;
    integral += burley_pdf(d, r) * (kBurleyTruncate * d / n);
    mean += r * burley_pdf(d, r) * (kBurleyTruncate * d / n);
  }
  EXPECT_NEAR(integral, 1.0, 1e-3);
  EXPECT_EQ(burley_pdf(d, 0.0f), 0.0f);
  EXPECT_EQ(burley_eval(d, kBurleyTruncate * d), 0.0f);
  double sampled = 0.0;
  const int m = 100000;
  for (int i = 0; i < m; ++i) {
    float r, h;
    burley_sample(d, (float(i) + 0.5f) / float(m), r, h);
    ASSERT_GE(r, 0.0f);
    ASSERT_LE(r, kBurleyTruncate * d * 1.0001f);
    EXPECT_NEAR(r * r + h * h, kBurleyTruncate * d * kBurleyTruncate * d, 1e-3f);
    sampled += r / m;
  }
  EXPECT_NEAR(sampled, mean, 0.01 * mean);
}

// A flat surface: what enters leaves (the probe meets the plane at the disk point itself), in
// every channel whatever its radius; channels of no radius carry nothing; the exit is on the
// plane, seen along its normal.
TEST(BurleyDisk, FlatSurfaceReturnsWhatEnters) {
  SubsurfaceLobe lobe;
  lobe.burley = true;
  lobe.weight = Vec3(1.0f, 1.0f, 0.0f);
  lobe.albedo = Vec3(1.0f);
  lobe.radius = Vec3(1.0f, 0.1f, 0.5f);
  Plane plane;
  Rng rng(1u, 2u, 3u);
  Vec3 sum(0.0f);
  const int n = 200000;
  int exits = 0;
  for (int i = 0; i < n; ++i) {
    const WalkExit e = burley_disk(plane, lobe, Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), false, lobe.weight, rng);
    if (!e.exited) continue;
    ++exits;
    ASSERT_NEAR(e.position.z, 0.0f, 1e-5f);
    ASSERT_EQ(e.direction, Vec3(0.0f, 0.0f, 1.0f));
    ASSERT_EQ(plane.kept, 0);
    sum += e.throughput / float(n);
  }
  EXPECT_NEAR(exits, n / 2, n / 100);  // the tangent axes run along the plane
  EXPECT_NEAR(sum.x, 1.0f, 0.02f);
  EXPECT_NEAR(sum.y, 1.0f, 0.02f);
  EXPECT_EQ(sum.z, 0.0f);
  const WalkExit back = burley_disk(plane, lobe, Vec3(0.0f), Vec3(0.0f, 0.0f, 1.0f), true, lobe.weight, rng);
  if (back.exited) EXPECT_EQ(back.direction, Vec3(0.0f, 0.0f, -1.0f));
}

}  // namespace
}  // namespace torrance
