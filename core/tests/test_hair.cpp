// Hair: strands as Embree curves (Scene::add_curves, hair/scene_curves.cpp) and the Principled
// Hair BSDF (hair/principled_hair_bsdf.h): hits on a known strand, the strand letting its own
// transmitted light through, degenerate strands, and the BSDF's sampling and energy; Huang hair
// seen outside its ellipse as a transparent surface (no fireflies behind it).
#include "torrance/hair/principled_hair_bsdf.h"
#include "integrator/path_tracer.h"  // has_alpha
#include "torrance/integrator/integrator.h"
#include "torrance/bsdfs/mixture.h"
#include "torrance/scene/scene.h"

#include "scene_helpers.h"
#include "test_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace torrance {
namespace {

// A straight strand along x from -1 to 1 at height z (4 keys), radius r.
uint32_t add_straight_strand(Scene& scene, float z, float r, CurveShape shape) {
  if (scene.num_materials() == 0) scene.add_material(Material{});
  const float keys[] = {-1, 0, z, -0.3f, 0, z, 0.3f, 0, z, 1, 0, z};
  const float radii[] = {r, r, r, r};
  const int64_t offsets[] = {0, 4};
  return scene.add_curves(keys, radii, 4, offsets, 1, nullptr, shape);
}

Ray down_from(float x, float y, float z) {
  Ray ray;
  ray.origin = Vec3(x, y, z);
  ray.dir = Vec3(0, 0, -1);
  return ray;
}

TEST(Hair, RoundStrandHitHasTheTubesNormalAndTheStrandsTangent) {
  Scene scene;
  add_straight_strand(scene, 0.0f, 0.1f, CurveShape::Round);
  scene.commit();
  EXPECT_EQ(scene.num_curve_segments(), 3u);
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(down_from(0.1f, 0.0f, 5.0f), hit));
  EXPECT_TRUE(hit.on_curve);
  EXPECT_NEAR(hit.t, 4.9f, 1e-3f);
  EXPECT_NEAR(hit.geometric_normal.z, 1.0f, 1e-3f);
  EXPECT_NEAR(std::abs(hit.tangent.x), 1.0f, 1e-4f);
  // Off the centre line: the tube's surface at y = 0.06 is sqrt(0.1^2 - 0.06^2) = 0.08 high.
  ASSERT_TRUE(scene.intersect(down_from(0.2f, 0.06f, 5.0f), hit));
  EXPECT_NEAR(hit.t, 5.0f - 0.08f, 2e-3f);
  EXPECT_NEAR(hit.geometric_normal.y, 0.6f, 1e-2f);
  EXPECT_NEAR(hit.geometric_normal.z, 0.8f, 1e-2f);
  EXPECT_FALSE(scene.intersect(down_from(0.2f, 0.12f, 5.0f), hit));  // beside it
  EXPECT_FALSE(scene.intersect(down_from(1.3f, 0.0f, 5.0f), hit));   // past its end
}

TEST(Hair, RibbonFacesTheRayWithNormalsRoundedAcrossIt) {
  Scene scene;
  add_straight_strand(scene, 0.0f, 0.1f, CurveShape::Ribbon);
  scene.commit();
  SurfaceHit hit;
  ASSERT_TRUE(scene.intersect(down_from(0.0f, 0.05f, 5.0f), hit));
  EXPECT_TRUE(hit.on_curve);
  EXPECT_NEAR(hit.t, 5.0f, 1e-3f);
  // Half way to the edge: the normal is turned 30 degrees off the view, towards that edge.
  EXPECT_NEAR(std::abs(hit.uv.y), 0.5f, 2e-2f);
  EXPECT_NEAR(hit.shading_normal.z, std::sqrt(0.75f), 2e-2f);
  EXPECT_NEAR(std::abs(hit.shading_normal.y), 0.5f, 2e-2f);
}

// A ray leaving a strand through it (transmission, shadow rays to the far side) does not meet
// the strand it left; the next strand below is met. The rays cross the strands off the middle of
// a segment: on an AVX2-only CPU (AMD EPYC) Embree 3.13.5's ribbon intersector reports no hit for
// a ray along the exact middle (x = 0) of the ribbon 1 m below, and never calls the filter.
TEST(Hair, RaysLeavingAStrandPassThroughItButMeetTheNext) {
  for (CurveShape shape : {CurveShape::Round, CurveShape::Ribbon}) {
    Scene scene;
    add_straight_strand(scene, 0.0f, 0.05f, shape);
    add_straight_strand(scene, -1.0f, 0.05f, shape);
    scene.commit();
    SurfaceHit top;
    ASSERT_TRUE(scene.intersect(down_from(0.137f, 0.0f, 5.0f), top));
    Ray through;
    through.origin = top.position - 1e-4f * top.geometric_normal;
    through.dir = Vec3(0, 0, -1);
    SurfaceHit below;
    ASSERT_TRUE(scene.intersect(through, below)) << int(shape);
    EXPECT_NEAR(below.position.z, shape == CurveShape::Round ? -0.95f : -1.0f, 2e-3f) << int(shape);
    // Reflected back up: nothing.
    Ray up;
    up.origin = top.position + 1e-4f * top.geometric_normal;
    up.dir = Vec3(0, 0, 1);
    EXPECT_FALSE(scene.intersect(up, below)) << int(shape);
    EXPECT_FALSE(scene.occluded(up.origin, up.dir, 0.0f, 100.0f)) << int(shape);
  }
}

TEST(Hair, RejectsMalformedCurves) {
  Scene scene;
  const float keys[] = {0, 0, 0, 1, 0, 0};
  EXPECT_THROW(scene.add_curves(keys, std::array<float, 2>{0.1f, 0.1f}.data(), 2,
                                std::array<int64_t, 2>{0, 2}.data(), 1, nullptr, CurveShape::Round),
               std::invalid_argument);  // no material yet
  scene.add_material(Material{});
  const float radii[] = {0.1f, 0.1f}, bad_radii[] = {0.1f, -1.0f};
  const int64_t offsets[] = {0, 2}, short_offsets[] = {0, 1};
  const float nan_keys[] = {0, 0, 0, NAN, 0, 0};
  EXPECT_THROW(scene.add_curves(keys, bad_radii, 2, offsets, 1, nullptr, CurveShape::Round), std::invalid_argument);
  EXPECT_THROW(scene.add_curves(nan_keys, radii, 2, offsets, 1, nullptr, CurveShape::Round), std::invalid_argument);
  EXPECT_THROW(scene.add_curves(keys, radii, 2, short_offsets, 1, nullptr, CurveShape::Round), std::invalid_argument);
  const int64_t no_such_material[] = {5};
  EXPECT_THROW(scene.add_curves(keys, radii, 2, offsets, 1, no_such_material, CurveShape::Round),
               std::invalid_argument);
}

// Zero-length segments (repeated keys), zero radii and one-key curves: finite hits and a
// finite image, with the Principled Hair BSDF on them.
TEST(Hair, DegenerateStrandsRenderFinite) {
  for (CurveShape shape : {CurveShape::Round, CurveShape::Ribbon}) {
    Scene scene;
    Material hair;
    hair.base_color = PrincipledHairBsdf::sigma_from_concentration(0.5f, 0.1f);
    const uint32_t hair_material = scene.add_material(hair);
    Mixture mixture;
    mixture.components.push_back({ClosureType::PrincipledHair, hair_material, {}});
    const int64_t m = scene.add_mixture(mixture);
    // Curve 0: repeated keys; curve 1: zero radius; curve 2: one key; curve 3: all keys equal.
    const std::vector<float> keys = {-1, 0, 0, -1, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0.2f,  // 0
                                     -1, 0.3f, 0, 1, 0.3f, 0,                          // 1
                                     0, -0.3f, 0,                                      // 2
                                     0.5f, 0.5f, 0, 0.5f, 0.5f, 0, 0.5f, 0.5f, 0};     // 3
    const std::vector<float> radii = {0.05f, 0.05f, 0.05f, 0.05f, 0.0f, 0.0f, 0.1f, 0.1f, 0.1f, 0.1f, 0.0f};
    const std::vector<int64_t> offsets = {0, 5, 7, 8, 11};
    const std::vector<int64_t> materials = {m, m, m, m};
    scene.add_curves(keys.data(), radii.data(), 11, offsets.data(), 4, materials.data(), shape);
    scene.lights().add_sun(glm::normalize(Vec3(0.3f, 0.2f, -1)), kPi, Vec3(1.0f), 0.05f);
    test::look_down(scene, 4.0f, 30.0f);
    RenderSettings s;
    s.width = s.height = 24;
    s.samples = 16;
    s.max_bounces = 4;
    const RenderResult r = render(scene, s);
    double lit = 0.0;
    for (float v : r.image.rgba) {
      ASSERT_TRUE(std::isfinite(v));
      lit += v;
    }
    EXPECT_GT(lit, 0.0) << int(shape);
  }
}

// White hair (no absorption) keeps all the energy it scatters (Chiang's A_p sum to 1; M_p and
// N_p are normalised), whatever the roughness and view; absorbing hair keeps less.
TEST(Hair, PrincipledHairWithoutAbsorptionConservesEnergy) {
  for (float roughness : {0.2f, 0.5f, 0.9f})
    for (float cos_o : {0.9f, 0.4f, 0.05f}) {
      PrincipledHairParams p;
      p.roughness = roughness;
      p.radial_roughness = roughness;
      p.offset = 0.0f;
      const Vec3 tangent = glm::normalize(Vec3(1.0f, 0.3f, 0.0f));
      const PrincipledHairBsdf white(p, tangent);
      const Vec3 wo = test::direction(cos_o, 1.1f);
      const double albedo = test::mean_sample_weight(white, wo, 200000, 3);
      EXPECT_NEAR(albedo, 1.0, 0.02) << "r=" << roughness << " cos_o=" << cos_o;
      p.sigma = PrincipledHairBsdf::sigma_from_concentration(0.8f, 0.1f);
      EXPECT_LT(test::mean_sample_weight(PrincipledHairBsdf(p, tangent), wo, 50000, 4), 0.9 * albedo);
    }
}

// Every sample's weight is eval / pdf, its pdf the one pdf() reports, all finite.
TEST(Hair, PrincipledHairSamplesAreEvalOverPdf) {
  PrincipledHairParams p;
  p.sigma = PrincipledHairBsdf::sigma_from_reflectance(Vec3(0.8f, 0.5f, 0.3f), 0.3f);
  p.coat = 0.3f;
  const PrincipledHairBsdf hair(p, glm::normalize(Vec3(0.8f, -0.6f, 0.0f)));
  Rng rng(5, 6, 7);
  for (float cos_o : {1.0f, 0.5f, 0.01f}) {
    const Vec3 wo = test::direction(cos_o, 0.3f);
    for (int i = 0; i < 2000; ++i) {
      const float u = rng.next_1d();
      const BsdfSample s = hair.sample(wo, u, rng.next_2d());
      if (!s.valid()) continue;
      ASSERT_TRUE(is_finite(s.weight));
      EXPECT_NEAR(s.pdf, hair.pdf(wo, s.wi), 1e-4f * (1.0f + s.pdf));
      const Vec3 f = hair.eval(wo, s.wi) / s.pdf;
      EXPECT_NEAR(s.weight.x, f.x, 1e-4f * (1.0f + f.x));
    }
  }
  // Looking along the strand, and grazing it: finite.
  for (const Vec3& wo : {Vec3(0.8f, -0.6f, 0.0f), Vec3(0.0f, 0.0f, 1.0f), Vec3(-0.8f, 0.6f, 1e-6f)}) {
    const Vec3 n = glm::normalize(wo);
    ASSERT_TRUE(is_finite(hair.eval(n, Vec3(0, 0, 1))));
    ASSERT_TRUE(std::isfinite(hair.pdf(n, Vec3(0, 0, 1))));
  }
}

// The parametrisations as Cycles 3.4 reduces them to an absorption coefficient.
TEST(Hair, ParametrisationsMatchCycles) {
  const Vec3 melanin = PrincipledHairBsdf::sigma_from_concentration(1.0f, 0.0f);
  EXPECT_FLOAT_EQ(melanin.x, 0.506f);
  const Vec3 white = PrincipledHairBsdf::sigma_from_reflectance(Vec3(1.0f), 0.3f);
  EXPECT_FLOAT_EQ(white.x, 0.0f);
  // log(0.5) / scale(0.3) squared, scale(x) the fitted polynomial at 0.3 = 5.6215...
  const float scale = (((((0.245f * 0.3f) + 5.574f) * 0.3f - 10.73f) * 0.3f + 2.532f) * 0.3f - 0.215f) * 0.3f + 5.969f;
  EXPECT_NEAR(PrincipledHairBsdf::sigma_from_reflectance(Vec3(0.5f), 0.3f).x,
              std::pow(std::log(0.5f) / scale, 2.0f), 1e-6f);
}

}  // namespace
}  // namespace torrance

namespace torrance {
namespace {

// Random Roughness and Random Color at a strand's random r, as Cycles' svm node: the roughnesses
// times 1 + 2 (r - 0.5) Random Roughness, the melanin times 1 + 2 (r - 0.5) Random Color before
// it becomes an absorption; the middle strand (r = 0.5) unchanged.
TEST(Hair, RandomnessScalesRoughnessAndMelaninPerStrand) {
  HairRandomness h;
  h.coloring = HairRandomness::Coloring::Melanin;
  h.melanin = 0.4f;
  h.melanin_redness = 0.3f;
  h.color = Vec3(0.9f, 0.8f, 0.7f);
  h.random_roughness = 0.5f;
  h.random_color = 0.5f;
  auto melanin_sigma = [&](float melanin, float radial) {
    const float amount = -std::log(1.0f - melanin);
    return PrincipledHairBsdf::sigma_from_concentration(amount * 0.7f, amount * 0.3f) +
           PrincipledHairBsdf::sigma_from_reflectance(h.color, radial);
  };
  float roughness = 0.3f, radial = 0.4f;
  Vec3 sigma = h.sigma_at(0.5f, roughness, radial);
  EXPECT_FLOAT_EQ(roughness, 0.3f);
  EXPECT_NEAR(sigma.z, melanin_sigma(0.4f, 0.4f).z, 1e-5f);
  sigma = h.sigma_at(1.0f, roughness, radial);  // the top strand: x 1.5 each
  EXPECT_FLOAT_EQ(roughness, 0.45f);
  EXPECT_FLOAT_EQ(radial, 0.6f);
  EXPECT_NEAR(sigma.x, melanin_sigma(0.6f, 0.6f).x, 1e-5f);
  EXPECT_NEAR(sigma.z, melanin_sigma(0.6f, 0.6f).z, 1e-5f);
  h.coloring = HairRandomness::Coloring::DirectColor;
  roughness = 0.3f;
  radial = 0.4f;
  sigma = h.sigma_at(0.0f, roughness, radial);  // the bottom strand: x 0.5
  EXPECT_NEAR(sigma.y, PrincipledHairBsdf::sigma_from_reflectance(h.color, 0.2f).y, 1e-6f);
  h.coloring = HairRandomness::Coloring::Absorption;
  h.sigma = Vec3(0.1f, 0.2f, 0.3f);
  EXPECT_EQ(h.sigma_at(0.9f, roughness, radial), h.sigma);
}

// Straight strands along x at height z, one every `spacing` in y over [-half, half], radius r,
// each with the curves' normal attribute straight up: a Huang hair mixture of Aspect Ratio
// `aspect`, whose ellipses' major axes are then vertical. Returns the number of strands.
int add_huang_strands(Scene& scene, float z, float r, float spacing, float half, float aspect) {
  Material hair;
  hair.base_color = Vec3(0.2f, 0.3f, 0.5f);  // absorption coefficient
  hair.roughness = 0.25f;
  hair.hair_aspect_ratio = aspect;
  hair.hair_lobe_weights = Vec3(1.0f, 1.0f, 0.7f);
  Mixture mixture;
  mixture.components.push_back({ClosureType::PrincipledHairHuang, scene.add_material(hair), {}});
  const int64_t m = scene.add_mixture(mixture);
  std::vector<float> keys, radii, normals;
  std::vector<int64_t> offsets{0}, materials;
  for (float y = -half; y <= half + 1e-4f; y += spacing) {
    for (float x : {-3.0f, -1.0f, 1.0f, 3.0f}) {
      keys.insert(keys.end(), {x, y, z});
      normals.insert(normals.end(), {0.0f, 0.0f, 1.0f});
      radii.push_back(r);
    }
    offsets.push_back(int64_t(radii.size()));
    materials.push_back(m);
  }
  scene.add_curves(keys.data(), radii.data(), radii.size(), offsets.data(), materials.size(), materials.data(),
                   CurveShape::Round, nullptr, normals.data());
  return int(materials.size());
}

TEST(HuangHair, SunBehindTheEllipsesGapsMakesNoFireflies) {
  // Issue 38's fireflies: touching tubes of radius 0.02 (elliptical fibres of aspect 0.25, their
  // major axes vertical: from above they fill a quarter of the tubes' width) 1 m above a white
  // floor, under a sun of 1 degree straight above and no world; the camera between them sees the
  // floor alone. Shadow rays stop at the strands (Cycles'). A diffuse bounce that passes a gap and
  // lands in the sun's cone (1 in ~13000) must be weighed by MIS against the floor's NEE, as
  // after any transparent surface (pass_sheet); taken whole, as after a delta bounce, it made
  // single pixels hundreds of times the rest. The floor then keeps the light the fibres scatter
  // onto it, not the sun through the gaps (0.8 / pi x 3 = 0.76 unshadowed), as Cycles renders it.
  Scene scene;
  test::add_quad(scene, {-3, -3, 0}, {3, -3, 0}, {3, 3, 0}, {-3, 3, 0},
                 scene.add_material(test::diffuse_material(Vec3(0.8f))));
  EXPECT_GT(add_huang_strands(scene, 1.0f, 0.02f, 0.04f, 2.0f, 0.25f), 100);
  EXPECT_TRUE(has_alpha(scene));  // the path tracer that passes transparent surfaces
  scene.lights().add_sun(Vec3(0, 0, -1), 3.0f, Vec3(1.0f), 0.0175f);
  test::look_down(scene, 0.5f, 30.0f);
  RenderSettings s;
  s.width = s.height = 24;
  s.samples = 16;
  s.max_bounces = 4;
  const RenderResult r = render(scene, s);
  std::vector<float> lum;
  for (size_t i = 0; i < r.image.rgba.size(); i += 4)
    lum.push_back(luminance(Vec3(r.image.rgba[i], r.image.rgba[i + 1], r.image.rgba[i + 2])));
  std::sort(lum.begin(), lum.end());
  const float median = lum[lum.size() / 2], brightest = lum.back();
  std::printf("  floor: median %.3f, brightest %.3f, darkest %.3f\n", median, brightest, lum.front());
  EXPECT_GT(median, 0.01f);
  EXPECT_LT(median, 0.3f);
  EXPECT_LT(brightest, 20.0f * median);  // at 16 spp the scattered light alone: ~5x
}

}  // namespace
}  // namespace torrance
