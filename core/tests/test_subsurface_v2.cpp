// Principled v2's subsurface and Cycles 4.x/5.x's walk rules (core/src/subsurface/,
// principled_v2.h): how the Subsurface Weight splits the diffuse layer, the lobe Cycles 4.x sets
// up, where a walk falls back to diffuse (4.0-4.4's quarter footprint, a diffuse ancestor) and
// Blender 5.3's Random Walk (van de Hulst's albedo, the radius as given).
#include "torrance/bsdfs/mixture_bsdf.h"
#include "torrance/subsurface/albedo_inversion.h"
#include "torrance/subsurface/random_walk.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace torrance {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Material v2_material(float weight) {
  Material m;
  m.base_color = Vec3(0.8f, 0.5f, 0.2f);
  m.roughness = 0.5f;
  m.subsurface = weight;
  m.subsurface_radius = Vec3(0.1f, 0.05f, 0.02f);
  m.subsurface_fixed_radius = true;
  return m;
}

// The walk's weight and the diffuse's add up to the diffuse layer without subsurface (Cycles:
// base (1 - w) + min(base, 1) w, under the same layers), whatever the view, coat and sheen; the
// channels not walked keep their share as diffuse.
TEST(SubsurfaceV2, WeightSplitsTheDiffuseLayer) {
  for (bool layered : {false, true}) {
    Material plain = v2_material(0.0f);
    if (layered) {
      plain.coat_weight = 0.7f;
      plain.coat_tint = Vec3(0.9f, 0.7f, 0.5f);
      plain.sheen_weight = 0.5f;
      plain.metallic = 0.3f;
    }
    const PrincipledV2Bsdf without(plain);
    for (float w : {0.3f, 1.0f}) {
      Material m = plain;
      m.subsurface = w;
      const PrincipledV2Bsdf with(m);
      for (float cos_o : {1.0f, 0.5f, 0.1f}) {
        const auto a = without.view_terms(cos_o), b = with.view_terms(cos_o);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(b.diffuse[c] + b.subsurface[c], a.diffuse[c], 1e-6f) << w << " " << cos_o;
          EXPECT_NEAR(b.subsurface[c], w * a.diffuse[c], 1e-6f);
        }
        EXPECT_EQ(with.subsurface_weight(cos_o), b.subsurface);
      }
    }
  }
  Material m = v2_material(1.0f);
  m.subsurface_radius = Vec3(0.1f, 0.0f, 0.02f);  // green not walked: diffuse
  const auto t = PrincipledV2Bsdf(m).view_terms(1.0f);
  EXPECT_EQ(t.subsurface.y, 0.0f);
  EXPECT_GT(t.diffuse.y, 0.0f);
  EXPECT_EQ(t.diffuse.x, 0.0f);
  EXPECT_FALSE(PrincipledV2Bsdf(v2_material(0.0f)).has_subsurface());
}

// The lobe as Cycles 4.x's svm/closure.h sets it up: the clamped base colour, the Principled's
// IOR as the Specular IOR Level leaves it (Skin: Subsurface IOR, alpha 1), alpha roughness^2,
// its weight finished by the layers for the view (MixtureBsdf::finish_subsurface).
TEST(SubsurfaceV2, LobeAsCycles4SetsItUp) {
  Material m = v2_material(0.6f);
  m.base_color = Vec3(1.5f, 0.5f, 0.2f);
  m.ior = 1.45f;
  m.specular = 0.5f * ggx_tables::f0_from_ior(1.45f) / 0.04f;  // level 0.5: eta = IOR
  m.subsurface_ior = 2.5f;
  SubsurfaceLobe s = principled_v2_subsurface(m, PrincipledV2Bsdf::dielectric_eta(m), 0);
  EXPECT_NEAR(s.ior, 1.45f, 1e-4f);
  EXPECT_NEAR(s.entry_alpha, 0.25f, 1e-6f);
  EXPECT_EQ(s.albedo, Vec3(1.0f, 0.5f, 0.2f));
  EXPECT_TRUE(s.fixed_radius);
  EXPECT_FALSE(s.exit_fresnel);
  EXPECT_EQ(s.layered_component, 0);
  const MixtureBsdf mixture{MaterialBsdf(m, BrdfModel::PrincipledV2)};
  const Vec3 wo = glm::normalize(Vec3(0.3f, 0.0f, 0.8f));
  mixture.finish_subsurface(s, wo);
  EXPECT_EQ(s.layered_component, -1);
  const Vec3 expected = PrincipledV2Bsdf(m).subsurface_weight(wo.z);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], expected[c], 1e-6f);
  EXPECT_GT(s.choice_probability(), 0.3f);
  EXPECT_LT(s.choice_probability(), 1.0f);
  m.subsurface_skin = true;
  const SubsurfaceLobe skin = principled_v2_subsurface(m, PrincipledV2Bsdf::dielectric_eta(m), 0);
  EXPECT_NEAR(skin.ior, 2.5f, 1e-6f);
  EXPECT_EQ(skin.entry_alpha, 1.0f);
  EXPECT_TRUE(skin.entry_half_lambertian);
  EXPECT_FALSE(skin.fixed_radius);
  m.subsurface_skin = false;
  m.metallic = 1.0f;
  EXPECT_FALSE(principled_v2_subsurface(m, 1.45f, 0).active());
}

// Cycles 4.0-4.4: a radius below a quarter of the ray's footprint, and any after a diffuse
// bounce, is shaded as diffuse; 4.5 keeps only BSSRDF_MIN_RADIUS; 5.x walks after a diffuse
// bounce too; hair and objectless hits never walk.
TEST(SubsurfaceV2, WhereAWalkFallsBackToDiffuse) {
  Material m = v2_material(1.0f);
  WalkState at;
  at.footprint = 0.2f;
  EXPECT_EQ(min_walk_radius(m, at), kMinSubsurfaceRadius);
  m.subsurface_min_footprint = 0.25f;
  EXPECT_NEAR(min_walk_radius(m, at), 0.05f, 1e-7f);
  const Material walked = walked_only(m, min_walk_radius(m, at));
  EXPECT_EQ(walked.subsurface_radius, Vec3(0.1f, 0.05f, 0.0f));
  at.diffuse_ancestor = true;
  EXPECT_EQ(min_walk_radius(m, at), kInf);
  EXPECT_EQ(walked_only(m, kInf).subsurface_radius, Vec3(0.0f));
  m.subsurface_min_footprint = 0.0f;
  m.subsurface_after_diffuse = true;
  EXPECT_EQ(min_walk_radius(m, at), kMinSubsurfaceRadius);
  at.walkable = false;
  EXPECT_EQ(min_walk_radius(m, at), kInf);
}

// d'Eon's van de Hulst mapping: the single-scattering albedo grows with the colour, is 0 at 0 and
// almost 1 at 1, grows with the anisotropy; the extinction is 1 / radius.
TEST(SubsurfaceV2, VanDeHulstMediumIsMonotoneAndBounded) {
  float last = -1.0f;
  for (float c = 0.0f; c <= 1.0001f; c += 0.05f) {
    const WalkMedium m = van_de_hulst_medium(Vec3(c), Vec3(0.5f), 0.0f);
    EXPECT_GE(m.alpha.x, last) << c;
    EXPECT_LE(m.alpha.x, 0.999999f);
    last = m.alpha.x;
  }
  EXPECT_GT(last, 0.999f);
  EXPECT_NEAR(van_de_hulst_medium(Vec3(0.0f), Vec3(1.0f), 0.0f).alpha.x, 0.0f, 1e-3f);
  const float forward = van_de_hulst_medium(Vec3(0.6f), Vec3(1.0f), 0.8f).alpha.x;
  const float backward = van_de_hulst_medium(Vec3(0.6f), Vec3(1.0f), -0.8f).alpha.x;
  EXPECT_GT(forward, van_de_hulst_medium(Vec3(0.6f), Vec3(1.0f), 0.0f).alpha.x);
  EXPECT_LT(backward, van_de_hulst_medium(Vec3(0.6f), Vec3(1.0f), 0.0f).alpha.x);
  EXPECT_NEAR(van_de_hulst_medium(Vec3(0.6f), Vec3(0.25f), 0.8f).sigma_t.x, 4.0f, 1e-5f);
}

// Blender 5.3's Random Walk: a half-space of colour A reflects about A through the walk (the
// mapping is built for it; measured 0.757/0.443/0.165 for 0.8/0.5/0.2 at g = 0, 0.757/0.424/0.132
// at 0.7, 0.769/0.466/0.195 at -0.5: below A where Cycles' min_alpha 0.2 trades albedo for
// throughput), for forward and backward scattering; a white one keeps its energy up to the
// 256-step limit; hard cases stay finite.
class HalfSpace : public WalkBoundary {
 public:
  bool nearest(const Vec3& o, const Vec3& d, float t_max, float& t) override {
    if (!(d.z > 0.0f)) return false;
    t = -o.z / d.z;
    return t > 0.0f && t <= t_max;
  }
};

Vec3 half_space_reflectance(const Material& m, int n) {
  const SubsurfaceLobe lobe = node_subsurface(m);
  HalfSpace h;
  Vec3 sum(0.0f);
  for (int i = 0; i < n; ++i) {
    Rng rng(uint32_t(i), 3u, 9u);
    const Vec3 up(0.0f, 0.0f, 1.0f);
    const WalkExit e = random_walk(h, lobe, Vec3(0.0f), up, up, up, 1e-6f, lobe.weight, rng);
    if (e.exited) sum += e.throughput;
  }
  return sum / float(n);
}

TEST(SubsurfaceV2, VanDeHulstHalfSpaceReflectsItsColour) {
  Material m;
  m.base_color = Vec3(0.8f, 0.5f, 0.2f);
  m.subsurface_radius = Vec3(0.3f, 0.1f, 0.05f);
  m.subsurface_entry_alpha = 1.0f;
  m.subsurface_van_de_hulst = m.subsurface_after_diffuse = true;
  for (float g : {0.0f, 0.7f, -0.5f}) {
    m.subsurface_anisotropy = g;
    EXPECT_EQ(node_subsurface(m).anisotropy, g);
    const Vec3 r = half_space_reflectance(m, 20000);
    for (int c = 0; c < 3; ++c) {
      EXPECT_TRUE(std::isfinite(r[c]));
      EXPECT_NEAR(r[c], m.base_color[c], 0.06f + 0.2f * m.base_color[c]) << "g=" << g << " c=" << c;
    }
    EXPECT_GT(r.x, r.y);
    EXPECT_GT(r.y, r.z);
  }
  m.base_color = Vec3(1.0f);
  m.subsurface_anisotropy = 0.0f;
  const Vec3 white = half_space_reflectance(m, 20000);
  EXPECT_GT(white.x, 0.85f);
  EXPECT_LT(white.x, 1.005f);
  m.subsurface_anisotropy = 5.0f;  // clamped to 0.99
  EXPECT_EQ(node_subsurface(m).anisotropy, 0.99f);
  m.base_color = Vec3(0.5f);
  EXPECT_TRUE(std::isfinite(half_space_reflectance(m, 2000).x));
}

}  // namespace
}  // namespace torrance
