// Suns seen in flat mirrors, glossy planes and glossy spheres: next-event estimation of a sun's
// light reflected once by a surface with a delta or narrow specular lobe (a mirror, a polished
// floor, a metal ball).
//
// Such light reaches a diffuse or glossy point x only along paths x -> plane -> sun, which
// ordinary NEE cannot sample at x, and BSDF sampling at x finds only when its direction happens to
// land in the sun's small image in the plane: the caustic fireflies of a low sun over a mirror
// or a polished floor. Reflection in a plane keeps solid angle, so the sun's image is a second sun
// seen along the reflected direction, and this strategy samples it:
//
//  * Perfect mirror (a material that is a delta reflection and nothing else): pick a direction d
//    in the sun's cone, aim x at its image wi = d - 2 (d.n) n, check that the first thing wi
//    meets is the mirror and that nothing hides the sun from there, and weigh by the mirror's
//    reflectance. BSDF sampling at x followed by the mirror's delta reflection finds the same
//    paths: both strategies weigh them by the power heuristic over the BSDF's pdf of wi at x and
//    this strategy's pdf (the cone's density times the choice of the pair), so the weights sum to 1.
//  * Glossy plane (opaque, specular GGX alpha at most kMaxGlossyAlpha, one sun in the scene): aim
//    x uniformly into a cone about the sun's mirror image, widened by the lobe (half-angle = the
//    sun's + 2 atan(3 alpha), where GGX's D has fallen to 1 %), then at the plane point estimate
//    the sun's light through the plane's BSDF (NEE and BSDF sampling). Against BSDF sampling at x
//    the same weighting applies, the sun's light found at the plane point after a BSDF-sampled
//    direction (by NEE or by BSDF sampling there) taking the BSDF's share (bsdf_share), this
//    strategy the rest.
//  * Glossy sphere (a material making one sphere, same conditions): the same with the cone about
//    the sphere's highlight seen from x, the point whose normal halves the directions to x and to
//    the sun (a few fixed-point steps from the sphere's centre), of the angular size the
//    sun and the lobe give it there: a convex mirror's image of the sun is small and moves with x.
//
// Suns of angle 0 are left out: no BSDF-sampled path can reach a delta sun through a plane's
// delta lobe, so Cycles renders no such light, and Torrance matches it. Only world-space meshes
// are examined for planes (instanced geometry is not), and the strategy is not used in scenes with
// alpha (a BSDF-sampled path passes transparent surfaces this strategy's rays would stop at).
#pragma once

#include "torrance/material_bsdf.h"
#include "torrance/scene.h"

#include <vector>

namespace torrance {

class MirrorImages {
 public:
  // Glossy reflectors up to roughness 0.3 (Principled) are sampled.
  static constexpr float kMaxGlossyAlpha = 0.09f;

  // The scene's reflectors -- planar mirrors, glossy planes and glossy spheres (bsdfs: the
  // render's, one per material) -- and its suns.
  MirrorImages(const Scene& scene, const std::vector<MaterialBsdf>& bsdfs);
  bool empty() const { return reflectors_.empty() || suns_.empty(); }
  size_t num_reflectors() const { return reflectors_.size(); }
  // The reflector made of material `material` (an index for the queries below), or -1.
  int reflector_of(uint32_t material) const {
    return material < reflector_of_material_.size() ? reflector_of_material_[material] : -1;
  }
  bool is_mirror(int reflector) const { return reflectors_[size_t(reflector)].mirror; }
  const MaterialBsdf& bsdf(int reflector) const { return *reflectors_[size_t(reflector)].bsdf; }
  bool is_sphere(int reflector) const { return reflectors_[size_t(reflector)].radius > 0.0f; }

  struct Sample {
    Vec3 wi{0.0f};      // from the shading point towards the sun's image in the reflector
    float pdf = 0.0f;   // the solid-angle density of wi, the pair's choice included
    int reflector = -1;
    // Mirrors: the direction from the mirror to the sun (wi reflected) and the sun's radiance
    // over its cone's density. Glossy reflectors: the sun, for NEE at the reflector's point.
    Vec3 to_sun{0.0f};
    Vec3 sun_weight{0.0f};
    const SunLight* sun = nullptr;
  };
  // One direction towards a sun's image in a reflector, the (reflector, sun) pair chosen among
  // those p sees (p off a plane on the side the sun shines on, both faces reflecting; outside a sphere)
  // in proportion to pair_weight, at the rate run_probability. False: none this time.
  bool sample(const Vec3& p, float u_pair, const Vec2& u, Sample& out) const;
  // The reflectance of mirror `reflector` for light arriving from direction to_sun.
  Vec3 reflectance(int reflector, const Vec3& to_sun) const;
  // Mirrors: what the suns send along `dir` (from a point on mirror `reflector`, unoccluded) to a
  // path that left p with BSDF density bsdf_pdf: their radiance weighted against this strategy.
  Vec3 suns_through(int reflector, const Vec3& p, const Vec3& dir, float bsdf_pdf) const;
  // Glossy reflectors: the share of the sun's light found at the point of glossy `reflector` that a
  // BSDF-sampled direction wi (density bsdf_pdf) from p reached: the power heuristic against this
  // strategy's density of wi (1 where it does not sample wi).
  float bsdf_share(int reflector, const Vec3& p, const Vec3& wi, float bsdf_pdf) const;

 private:
  struct Reflector {
    Vec3 point, normal;  // a sphere: its centre (normal unused)
    const MaterialBsdf* bsdf;
    bool mirror;
    float image_one_minus_cos;  // glossy plane: of the sun's image cone's half-angle (sun + lobe)
    float radius = 0.0f;        // > 0: a sphere
    float highlight_half = 0.0f;  // sphere: the angular radius of its highlight's normals
    float reflectance = 1.0f;     // its specular reflectance at normal incidence, roughly
  };
  bool sees(const Reflector& reflector, const SunLight& sun, const Vec3& p) const;
  // How often sample() at p picks the pair (reflector, sun), relative to total_weight(p): 0 where
  // p does not see it, else the reflectance, times r^2 / (4 d^2) for a sphere (the share
  // of the sun's power a convex mirror of radius r sends to distance d).
  float pair_weight(const Reflector& reflector, const SunLight& sun, const Vec3& p) const;
  float total_weight(const Vec3& p) const;
  // The strategy runs at p with probability min(1, kRunScale x total_weight(p)): where the
  // reflectors can send only a little of the sun's light (a small ball far away), it mostly leaves
  // that light to BSDF sampling rather than spend rays on it.
  static constexpr float kRunScale = 10.0f;
  static float run_probability(float total);
  // Glossy: the cone the strategy aims p into at `reflector` (its axis, 1 - cos of its half-angle).
  void image_cone(const Reflector& reflector, const Vec3& p, Vec3& axis, float& one_minus_cos) const;
  // Glossy: the density with which the strategy aims p along wi at `reflector` (given the pair).
  float image_cone_pdf(const Reflector& reflector, const Vec3& p, const Vec3& wi) const;

  std::vector<Reflector> reflectors_;
  std::vector<int> reflector_of_material_;
  std::vector<const SunLight*> suns_;
};

}  // namespace torrance
