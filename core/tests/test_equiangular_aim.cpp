// Where equiangular sampling aims (media/equiangular_aim.h): a spot's cone and an area light's
// front cut a line where they should, the light is chosen by how much of it a ray sees, and the
// single scattering of a spot light in fog, sampled with the cone's reach, converges to its
// quadrature with less noise than without it.
#include "fog_single_scattering.h"
#include "media/equiangular_aim.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace torrance {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// Whether x is where the reach says the light shines (brute force, for the tests).
bool reached(const LightReach& r, const Vec3& x) {
  const Vec3 v = x - r.apex;
  if (r.kind == LightReach::Kind::Front) return glm::dot(v, r.axis) > 0.0f;
  if (r.kind == LightReach::Kind::Cone) return glm::dot(v, r.axis) >= r.cos_half * glm::length(v);
  return true;
}

TEST(EquiangularAim, ConeAndFrontCutLinesWhereTheyShould) {
  LightReach cone;
  cone.kind = LightReach::Kind::Cone;
  cone.apex = Vec3(0.3f, -0.2f, 1.0f);
  cone.axis = glm::normalize(Vec3(0.2f, 0.1f, 1.0f));
  cone.cos_half = std::cos(0.4f);
  LightReach front;
  front.kind = LightReach::Kind::Front;
  front.apex = Vec3(0.0f, 0.0f, 2.0f);
  front.axis = glm::normalize(Vec3(0.3f, -1.0f, 0.2f));
  uint32_t state = 12345u;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return float(state >> 8) / float(1u << 24) * 2.0f - 1.0f;
  };
  int inside = 0, checked = 0;
  for (const LightReach& reach : {cone, front})
    for (int i = 0; i < 400; ++i) {
      const Vec3 origin(4.0f * next(), 4.0f * next(), 4.0f * next());
      const Vec3 dir = glm::normalize(Vec3(next(), next(), next()) + Vec3(1e-3f));
      float t0 = -20.0f, t1 = 20.0f;
      const bool some = reach.narrow(origin, dir, t0, t1);
      for (int k = 0; k < 200; ++k) {  // probes along [-20, 20], away from the interval's ends
        const float t = -20.0f + 40.0f * (k + 0.5f) / 200.0f;
        if (some && (std::abs(t - t0) < 1e-2f || std::abs(t - t1) < 1e-2f)) continue;
        const bool in = some && t > t0 && t < t1;
        ASSERT_EQ(in, reached(reach, origin + dir * t)) << "t " << t << " in [" << t0 << ", " << t1 << "]";
        inside += in;
        ++checked;
      }
    }
  EXPECT_GT(inside, checked / 20);  // the lines did cross the reaches
}

TEST(EquiangularAim, ChoosesLightsByWhatTheRaySeesOfThem) {
  Lights lights;
  lights.add_sun(Vec3(0.0f, 0.0f, -1.0f), 3.0f, Vec3(1.0f), 0.0f);  // never aimed at
  lights.add_point(Vec3(1.0f, 0.0f, 5.0f), 100.0f, Vec3(1.0f), 0.0f);
  lights.add_point(Vec3(1.0f, 0.0f, 10.0f), 300.0f, Vec3(1.0f), 0.0f);
  // A spot pointing away from the ray: it can not shine on it.
  lights.add_spot(Vec3(2.0f, 0.0f, 7.0f), Vec3(1.0f, 0.0f, 0.0f), 1000.0f, Vec3(1.0f), 0.0f, 0.5f, 0.0f);
  const Vec3 origin(0.0f), dir(0.0f, 0.0f, 1.0f);
  EXPECT_EQ(aimable_lights(lights), 3u);
  int near = 0, far = 0;
  constexpr int kN = 4000;
  for (int i = 0; i < kN; ++i) {
    AimTarget target;
    ASSERT_TRUE(choose_aim(lights, origin, dir, 0.0f, kInf, (i + 0.5f) / kN, target));
    near += target.point.z == 5.0f;
    far += target.point.z == 10.0f;
  }
  EXPECT_EQ(near + far, kN);  // never the sun nor the spot
  // Both lights 1 m from the endless ray, which they see over the same angle: by intensity, 1 : 3.
  EXPECT_NEAR(double(far) / kN, 0.75, 0.01);
  // A ray the spot's cone crosses and the points hardly see: the spot, mostly.
  AimTarget target;
  ASSERT_TRUE(choose_aim(lights, Vec3(4.0f, -3.0f, 7.0f), Vec3(0.0f, 1.0f, 0.0f), 0.0f, 6.0f, 0.5f, target));
  EXPECT_EQ(target.point, Vec3(2.0f, 0.0f, 7.0f));
  EXPECT_EQ(target.reach.kind, LightReach::Kind::Cone);
}

// Single scattering along a camera ray through endless fog of a spot light beside it whose cone
// (half-angle 0.25 rad) crosses the ray: L = ∫ sigma_s T(t) p I T(r) / r^2 [inside the cone] dt.
constexpr float kSigmaS = 0.08f, kSigmaA = 0.02f;
const Vec3 kSpot(1.5f, 0.0f, 6.0f);
const Vec3 kAxis = glm::normalize(Vec3(-1.0f, 0.0f, 0.4f));
const float kCosHalf = std::cos(0.25f);

double spot_direct_at(const Vec3& p) {
  const Vec3 d = kSpot - p;
  const float r = glm::length(d);
  if (glm::dot(-d / r, kAxis) < kCosHalf) return 0.0;
  return std::exp(-(kSigmaS + kSigmaA) * r) / (r * r) / (4.0 * M_PI);
}

test::Estimate spot_single_scattering(bool with_reach, int n) {
  HomogeneousMedium fog;
  fog.sigma_s = Vec3(kSigmaS);
  fog.sigma_a = Vec3(kSigmaA);
  fog.sampling = VolumeSampling::MultipleImportance;
  DirectAim aim;
  aim.light_point = kSpot;
  if (with_reach) {
    aim.reach.kind = LightReach::Kind::Cone;
    aim.reach.apex = kSpot;
    aim.reach.axis = kAxis;
    aim.reach.cos_half = kCosHalf;
  }
  return test::fog_single_scattering(fog, aim, spot_direct_at, n, 11u, 5u);
}

double spot_quadrature() {
  constexpr int kN = 2000000;
  constexpr double kEnd = 40.0;
  double sum = 0.0;
  for (int i = 0; i < kN; ++i) {
    const double t = kEnd * (i + 0.5) / kN;
    sum += kSigmaS * std::exp(-(kSigmaS + kSigmaA) * t) * spot_direct_at(Vec3(0.0f, 0.0f, float(t))) * kEnd / kN;
  }
  return sum;
}

TEST(EquiangularAim, SpotInFogConvergesWithLessNoiseInsideItsCone) {
  const double expected = spot_quadrature();
  constexpr int kN = 1 << 15;
  const test::Estimate whole = spot_single_scattering(false, kN);
  const test::Estimate cone = spot_single_scattering(true, kN);
  for (const test::Estimate& e : {whole, cone}) {
    EXPECT_NEAR(e.mean, expected, 4.0 * e.std_error + 1e-3 * expected) << "std error " << e.std_error;
    EXPECT_NEAR(e.mean, expected, 0.03 * expected);
  }
  EXPECT_LT(cone.std_error, 0.7 * whole.std_error);
  std::printf("spot single scattering %.6g: MIS over the whole ray %.6g +- %.2g, inside the cone %.6g +- %.2g\n",
              expected, whole.mean, whole.std_error, cone.mean, cone.std_error);
}

}  // namespace
}  // namespace torrance
