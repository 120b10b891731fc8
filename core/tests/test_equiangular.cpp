// Equiangular sampling toward a light (media/equiangular.h) and its use in a walk through a
// homogeneous medium (media/medium_walk.h): the density integrates to one over the segment and
// matches what sample() draws, degenerate segments give no NaN, Volume Sampling combines as
// Cycles', and the single scattering of a point light seen along a ray through fog converges to
// its quadrature with distance, equiangular and MIS sampling alike, MIS with far less noise.
#include "fog_single_scattering.h"
#include "media/medium_walk.h"
#include "torrance/media/equiangular.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace torrance {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// ∫ pdf over [tmin, tmax] by the midpoint rule in the angle seen from the light (exact
// substitution t = delta + D tan(theta), so it holds for an endless segment too).
double integral_of_pdf(const EquiangularSegment& s, const Vec3& origin, const Vec3& dir, const Vec3& light,
                       float tmin, float tmax) {
  const double delta = glm::dot(light - origin, dir);
  const double d = glm::length(light - origin - dir * float(delta));
  const double a = std::atan2(tmin - delta, d), b = std::atan2(double(tmax) - delta, d);
  constexpr int kN = 200000;
  double sum = 0.0;
  for (int i = 0; i < kN; ++i) {
    const double theta = a + (b - a) * (i + 0.5) / kN;
    const double t = delta + d * std::tan(theta);
    const double dt_dtheta = d / (std::cos(theta) * std::cos(theta));
    sum += double(s.pdf(float(t))) * dt_dtheta * (b - a) / kN;
  }
  return sum;
}

struct Case {
  Vec3 light;
  float tmin, tmax;
};

const Case kCases[] = {
    {Vec3(1.0f, 0.5f, 3.0f), 0.0f, 10.0f},     // beside the segment
    {Vec3(0.0f, 0.02f, 2.0f), 0.5f, 4.0f},     // almost on it
    {Vec3(0.3f, 0.0f, 25.0f), 0.0f, 5.0f},     // ahead of its end
    {Vec3(0.5f, 0.0f, -3.0f), 1.0f, 2.0f},     // behind its start
    {Vec3(2.0f, 1.0f, 4.0f), 0.0f, kInf},      // an endless segment (the world's medium)
};

TEST(Equiangular, PdfIntegratesToOneOverTheSegment) {
  const Vec3 origin(0.0f), dir(0.0f, 0.0f, 1.0f);
  for (const Case& c : kCases) {
    const EquiangularSegment s(origin, dir, c.light, c.tmin, c.tmax);
    ASSERT_TRUE(s.valid());
    EXPECT_NEAR(integral_of_pdf(s, origin, dir, c.light, c.tmin, c.tmax), 1.0, 1e-3) << c.light.z;
    EXPECT_EQ(s.pdf(c.tmin - 0.1f), 0.0f);  // nothing outside
    if (std::isfinite(c.tmax)) EXPECT_EQ(s.pdf(c.tmax + 0.1f), 0.0f);
  }
}

// sample(u) returns pdf(t) and its cdf is u: ∫_tmin^t pdf (midpoint rule in t) == u.
TEST(Equiangular, SampleAgreesWithPdf) {
  const Vec3 origin(0.0f), dir(0.0f, 0.0f, 1.0f);
  for (const Case& c : kCases) {
    if (!std::isfinite(c.tmax)) continue;
    const EquiangularSegment s(origin, dir, c.light, c.tmin, c.tmax);
    for (float u : {0.05f, 0.3f, 0.5f, 0.77f, 0.96f}) {
      float pdf = 0.0f;
      const float t = s.sample(u, pdf);
      ASSERT_GE(t, c.tmin);
      ASSERT_LE(t, c.tmax);
      EXPECT_FLOAT_EQ(pdf, s.pdf(t));
      constexpr int kN = 100000;
      double cdf = 0.0;
      for (int i = 0; i < kN; ++i) cdf += double(s.pdf(c.tmin + (t - c.tmin) * (i + 0.5f) / kN)) * (t - c.tmin) / kN;
      EXPECT_NEAR(cdf, u, 2e-3) << "light z " << c.light.z << " u " << u;
    }
  }
}

TEST(Equiangular, DegenerateSegmentsGiveNoNaN) {
  const Vec3 origin(0.0f), dir(0.0f, 0.0f, 1.0f);
  float pdf = 1.0f;
  // The light on the ray, inside the segment: uniform in t (the angle is all or nothing).
  const EquiangularSegment on(origin, dir, Vec3(0.0f, 0.0f, 2.0f), 0.0f, 4.0f);
  ASSERT_TRUE(on.valid());
  float t = on.sample(0.25f, pdf);
  EXPECT_FLOAT_EQ(t, 1.0f);
  EXPECT_FLOAT_EQ(pdf, 0.25f);
  // On the ray's line behind the start: uniform too.
  const EquiangularSegment behind(origin, dir, Vec3(0.0f, 0.0f, -2.0f), 0.0f, 4.0f);
  t = behind.sample(0.5f, pdf);
  EXPECT_TRUE(std::isfinite(t) && std::isfinite(pdf) && pdf > 0.0f);
  // On the line of an endless segment: no density can be drawn.
  const EquiangularSegment endless(origin, dir, Vec3(0.0f, 0.0f, 5.0f), 0.0f, kInf);
  EXPECT_FALSE(endless.valid());
  t = endless.sample(0.5f, pdf);
  EXPECT_EQ(pdf, 0.0f);
  EXPECT_TRUE(std::isfinite(t));
  EXPECT_EQ(endless.pdf(1.0f), 0.0f);
  // A zero-length segment, a reversed one, a NaN light.
  for (const EquiangularSegment& s :
       {EquiangularSegment(origin, dir, Vec3(1.0f), 2.0f, 2.0f), EquiangularSegment(origin, dir, Vec3(1.0f), 3.0f, 2.0f),
        EquiangularSegment(origin, dir, Vec3(std::nanf("")), 0.0f, 1.0f)}) {
    EXPECT_FALSE(s.valid());
    t = s.sample(0.5f, pdf);
    EXPECT_EQ(pdf, 0.0f);
    EXPECT_TRUE(std::isfinite(t));
    EXPECT_EQ(s.pdf(2.0f), 0.0f);
  }
  // A light far from a short segment (the angle below precision): uniform, finite.
  const EquiangularSegment far(origin, dir, Vec3(1e6f, 0.0f, 0.0f), 0.0f, 1e-3f);
  t = far.sample(0.5f, pdf);
  EXPECT_TRUE(std::isfinite(t) && std::isfinite(pdf) && pdf > 0.0f);
}

TEST(Equiangular, VolumeSamplingCombinesAsCycles) {
  using V = VolumeSampling;
  auto combined = [](std::initializer_list<V> methods) {
    VolumeSamplingCombiner c;
    for (V m : methods) c.add(m);
    return c.method;
  };
  EXPECT_EQ(combined({}), V::Distance);
  EXPECT_EQ(combined({V::Equiangular}), V::Equiangular);
  EXPECT_EQ(combined({V::Equiangular, V::Equiangular}), V::Equiangular);
  EXPECT_EQ(combined({V::Distance, V::Distance}), V::Distance);
  EXPECT_EQ(combined({V::Distance, V::Equiangular}), V::MultipleImportance);
  EXPECT_EQ(combined({V::Distance, V::MultipleImportance}), V::MultipleImportance);
}

// Single scattering along a camera ray through an endless fog (the world's medium) of a point
// light of intensity I beside the ray: L = ∫ sigma_s T(t) p I T(r) / r^2 dt (isotropic p), by
// quadrature; estimated by walk_media with each Volume Sampling, the light's part at the walk's
// scattering point (direct_weight) and at its equiangular points (aim).
constexpr float kSigmaS = 0.08f, kSigmaA = 0.02f, kIntensity = 1.0f;
const Vec3 kLight(0.25f, 0.0f, 6.0f);

double direct_at(const Vec3& p) {
  const Vec3 d = kLight - p;
  const float r2 = glm::dot(d, d);
  return kIntensity * std::exp(-(kSigmaS + kSigmaA) * std::sqrt(r2)) / r2 / (4.0 * M_PI);
}

test::Estimate single_scattering(VolumeSampling method, int n) {
  HomogeneousMedium fog;
  fog.sigma_s = Vec3(kSigmaS);
  fog.sigma_a = Vec3(kSigmaA);
  fog.sampling = method;
  DirectAim aim;
  aim.light_point = kLight;
  return test::fog_single_scattering(fog, aim, direct_at, n, 7u, 3u);
}

double single_scattering_quadrature() {
  // ∫_0^∞ sigma_s e^{-sigma_t t} direct(t) dt, in the angle seen from the light (t = delta + D tan).
  const double delta = kLight.z, d = glm::length(Vec3(kLight.x, kLight.y, 0.0f));
  const double a = std::atan2(-delta, d), b = M_PI / 2;
  constexpr int kN = 400000;
  double sum = 0.0;
  for (int i = 0; i < kN; ++i) {
    const double theta = a + (b - a) * (i + 0.5) / kN;
    const double t = delta + d * std::tan(theta);
    const double dt = d / (std::cos(theta) * std::cos(theta)) * (b - a) / kN;
    sum += kSigmaS * std::exp(-(kSigmaS + kSigmaA) * t) * direct_at(Vec3(0.0f, 0.0f, float(t))) * dt;
  }
  return sum;
}

TEST(Equiangular, SingleScatteringConvergesWithEveryVolumeSampling) {
  const double expected = single_scattering_quadrature();
  constexpr int kN = 1 << 16;
  const test::Estimate distance = single_scattering(VolumeSampling::Distance, kN);
  const test::Estimate equiangular = single_scattering(VolumeSampling::Equiangular, kN);
  const test::Estimate mis = single_scattering(VolumeSampling::MultipleImportance, kN);
  for (const test::Estimate& e : {distance, equiangular, mis}) {
    EXPECT_NEAR(e.mean, expected, 4.0 * e.std_error + 1e-3 * expected) << "std error " << e.std_error;
    EXPECT_NEAR(e.mean, expected, 0.05 * expected);
  }
  // A light close to the ray: equiangular sampling (alone or in MIS) is far less noisy.
  EXPECT_LT(equiangular.std_error, 0.2 * distance.std_error);
  EXPECT_LT(mis.std_error, 0.3 * distance.std_error);
  std::printf("single scattering %.6g: distance %.6g +- %.2g, equiangular %.6g +- %.2g, MIS %.6g +- %.2g\n",
              expected, distance.mean, distance.std_error, equiangular.mean, equiangular.std_error, mis.mean,
              mis.std_error);
}

}  // namespace
}  // namespace torrance
