// Lights seen in flat mirrors, glossy planes, boxes, sheets and spheres: next-event estimation of a
// light reflected once by a surface with a delta or narrow specular lobe (a mirror, a polished
// floor, a metal or plastic ball). Mirrors reflect suns; glossy planes and spheres reflect suns,
// point and spot lights with a radius, and area lights.
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
//  * Glossy plane (opaque, specular GGX alpha at most kMaxGlossyAlpha): aim x uniformly into a
//    cone about the light's mirror image (a sun's reflected direction; a lamp's mirrored position,
//    seen from x as the lamp is seen from x's mirror image), widened by the lobe (half-angle = the
//    light's + 2 atan(3 alpha), where GGX's D has fallen to 1 %), then at the plane point estimate
//    the light through the plane's BSDF (NEE and BSDF sampling). Against BSDF sampling at x the
//    same weighting applies, the light found at the plane point after a BSDF-sampled direction
//    (by NEE or by BSDF sampling there) taking the BSDF's share (bsdf_share), this strategy the
//    rest. (Mirrors reflect suns only: Cycles' point light is a disk facing the point it lights,
//    which a mirrored lamp would face differently from the mirror's point.)
//  * Glossy sphere (a material making one sphere, same conditions): the same with the cone about
//    the sphere's highlight seen from x, the point whose normal halves the directions to x and to
//    the light (a few fixed-point steps from the sphere's centre), of the angular size the
//    light and the lobe give it there: a convex mirror's image of a light is small and moves with x.
//    Then NEE of that light and BSDF sampling at the sphere's point, as for a glossy plane.
//
//  * Glossy boxes and sheets: a material made of a few exact planes (Scene::material_planes) is
//    a reflector per plane, the plane a hit belongs to the one nearest it (reflector_at); one
//    nearly flat sheet (a wavy water surface, normals within Scene::kMaxPlaneTilt of their mean)
//    is a glossy plane whose image cone is widened by twice its normals' tilt. Pairs of the
//    shading point's own material are left out.
//
//  * Lamps' bright spots on matte planes (lamp_spots.cpp): a lamp hanging close to a large matte
//    plane (a ceiling light) lights a small spot of it brightly, and that spot is a second light
//    for the room that BSDF sampling finds rarely from afar (interior comparison scene: paths
//    through it carried 17 % of the light and ~40 % of the variance). The strategy aims at points
//    of the spot drawn by the lamp's irradiance there, then estimates the lamp at that point as
//    at a glossy plane.
//
// Each (reflector, light) pair is chosen in proportion to the light it can send to x (pair_weight),
// and a path that met a reflector after a BSDF-sampled direction keeps, of each paired light's
// light found there, its own share (PathShare); lights in no pair are the path's alone.
//
// Delta lights (suns of angle 0, point lights of radius 0) are left out: no BSDF-sampled path can
// reach them through a delta lobe, so Cycles renders no such light, and Torrance matches it. Only
// world-space meshes are examined for planes (instanced geometry is not), and the strategy is not
// used in scenes with alpha (a BSDF-sampled path passes transparent surfaces this strategy's rays
// would stop at).
#pragma once

#include "torrance/lights/lights.h"
#include "torrance/bsdfs/material_bsdf.h"
#include "torrance/scene/scene.h"

#include <atomic>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace torrance {

class MirrorImages {
 public:
  // Glossy reflectors up to roughness 0.3 (Principled) are sampled.
  static constexpr float kMaxGlossyAlpha = 0.09f;
  // At most this many (reflector, light) pairs, the brightest reflections first: each costs a
  // little at every shading point.
  static constexpr size_t kMaxPairs = 32;

  // The scene's reflectors -- planar mirrors, glossy planes and glossy spheres (bsdfs: the
  // render's, one per material) -- and the lights they reflect.
  MirrorImages(const Scene& scene, const std::vector<MaterialBsdf>& bsdfs);
  bool empty() const { return pairs_.empty(); }
  size_t num_reflectors() const { return reflectors_.size(); }
  size_t num_pairs() const { return pairs_.size(); }
  size_t num_spots() const;  // of those, lamps' spots on matte planes
  // The reflector at `position` on material `material` (an index for the queries below), or -1: a
  // material making several planes (a box) is a reflector per plane, the one nearest `position`.
  int reflector_at(uint32_t material, const Vec3& position) const;
  bool is_reflector(uint32_t material) const {
    return material < first_reflector_.size() && first_reflector_[material] >= 0;
  }
  // Whether some kept (reflector, light) pair has a reflector of this material and light `light`
  // (a Lights index): the strategy finds that light through it. The lights a smooth reflector
  // has no pair with (a mirror box's lamps: mirrors pair with suns only) leave their caustics
  // through it to the other strategies (caustics.h's light tracer).
  bool reflects_light(uint32_t material, size_t light) const {
    return material < first_reflector_.size() && light < num_lights_ &&
           reflects_light_[size_t(material) * num_lights_ + light];
  }
  bool is_mirror(int reflector) const { return reflectors_[size_t(reflector)].mirror; }
  const MaterialBsdf& bsdf(int reflector) const { return *reflectors_[size_t(reflector)].bsdf; }
  bool is_sphere(int reflector) const { return reflectors_[size_t(reflector)].radius > 0.0f; }

  struct Sample {
    Vec3 wi{0.0f};      // from the shading point towards the light's image in the reflector
    float pdf = 0.0f;   // the solid-angle density of wi, the pair's choice included
    int reflector = -1;
    size_t light = 0;   // the light's NEE strategy index in Lights: at a glossy reflector, NEE of it
    // Mirrors: the direction from the mirror to the sun (wi reflected) and the sun's radiance
    // over its cone's density.
    Vec3 to_sun{0.0f};
    Vec3 sun_weight{0.0f};
  };
  // Where the strategy runs: a shading point p on material `material` (shading normal n; pairs
  // with a reflector of its own material are left out: a sheet does not sample its own glints),
  // and the path's weight there (the largest channel of its throughput, 1 at the camera's hit).
  struct Origin {
    Vec3 p, n;
    uint32_t material;
    float path_weight;
  };
  // The pairs' weights at an origin summed, and the rate the strategy runs at there (kRunScale).
  struct Odds {
    float total = 0.0f, run = 0.0f;
  };
  Odds odds(const Origin& at, float* weights = nullptr) const;
  // The same, weighing every pair rather than those the pair grid keeps for at.p (for tests: the
  // two agree bit for bit).
  Odds odds_of_every_pair(const Origin& at, float* weights = nullptr) const;
  // How many pairs odds() weighs at p (the pair grid's set for p's cell; all of them outside it).
  size_t pairs_weighed_at(const Vec3& p) const;
  // One direction from the origin towards a light's image in a reflector, the (reflector, light)
  // pair chosen among those it sees in proportion to pair_weight, at the rate odds() gives.
  // False: none this time.
  bool sample(const Origin& at, float u_pair, const Vec2& u, Sample& out) const;
  // The reflectance of mirror `reflector` for light arriving from direction to_sun.
  Vec3 reflectance(int reflector, const Vec3& to_sun) const;
  // The share of light `light` (a Lights index) found after a BSDF-sampled direction wi (density
  // bsdf_pdf) from `at` met `reflector` -- at a glossy reflector by NEE or BSDF sampling there,
  // after a mirror along the reflected ray: the power heuristic against this strategy's density
  // of wi (1 where it does not sample wi, or the pair does not exist); odds: odds(at).
  float bsdf_share(int reflector, const Origin& at, const Odds& odds, const Vec3& wi, float bsdf_pdf,
                   size_t light) const;

  // What a path keeps of the lights found at (and right after) the reflector it has just met.
  class PathShare final : public LightShare {
   public:
    explicit PathShare(const MirrorImages* images) : images_(images) {}
    void clear() { reflector_ = -1; }
    // The path left `from` along wi with BSDF density bsdf_pdf and met `reflector`.
    void met(int reflector, const Origin& from, const Vec3& wi, float bsdf_pdf) {
      reflector_ = reflector, from_ = from, wi_ = wi, bsdf_pdf_ = bsdf_pdf, odds_known_ = false;
    }
    // Null when the path keeps every light's light whole.
    const LightShare* active() const { return reflector_ >= 0 ? this : nullptr; }
    float of(size_t light) const override {
      if (!odds_known_) odds_ = images_->odds(from_), odds_known_ = true;  // once per reflector met
      return images_->bsdf_share(reflector_, from_, odds_, wi_, bsdf_pdf_, light);
    }

   private:
    const MirrorImages* images_;
    int reflector_ = -1;
    Origin from_{};
    Vec3 wi_{0.0f};
    float bsdf_pdf_ = 0.0f;
    mutable Odds odds_;
    mutable bool odds_known_ = false;
  };

 private:
  struct Reflector {
    Vec3 point, normal;  // a sphere: its centre (normal unused)
    const MaterialBsdf* bsdf;
    uint32_t material;
    bool mirror;
    float radius = 0.0f;  // > 0: a sphere
    float lobe = 0.0f;    // glossy: how far the lobe widens a light's image (2 atan(3 alpha))
    // A plane: how far its normals tilt from `normal` and its points stray from its plane (a
    // sheet), the sphere bounding it.
    float tilt = 0.0f, depth = 0.0f;
    // Glossy planes: how far the lobe and the tilt widen a light's image (at most pi/2), its sine
    // and 1 - its cosine.
    float widen = 0.0f, widen_sin = 0.0f, widen_cos = 1.0f, widen_one_minus_cos = 0.0f;
    Vec3 bound_center{0.0f};
    float bound_radius = std::numeric_limits<float>::infinity();
    bool matte = false;  // a matte plane: the bright spots lamps close to it make (lamp_spots.cpp)
  };
  // A light the strategy aims at: a non-delta sun, a point or spot light with a radius, an area light.
  struct Source {
    size_t index;  // its NEE strategy index in Lights
    const SunLight* sun = nullptr;
    const PointLight* point = nullptr;
    const AreaLight* area = nullptr;
    float sun_radius = 0.0f;  // a sun's angular radius
    float size = 0.0f;        // a lamp's radius (an area light's extent)
    Vec3 position() const { return point ? point->position() : area->center(); }  // not for a sun
    Vec3 toward(const Vec3& x) const;          // unit direction from x to the light (its centre)
    // Whether the light is on the positive side of the plane through `origin` with normal n.
    bool above(const Vec3& origin, const Vec3& n) const;
    float angular_radius(const Vec3& x) const;  // of the light seen from x (at most pi/2)
    // Its luminance on a surface at x with normal n (default: facing it), unshadowed, roughly.
    float irradiance(const Vec3& x) const { return irradiance(x, toward(x)); }
    float irradiance(const Vec3& x, const Vec3& n) const;
  };
  struct Pair {
    int reflector, source;
    // A sphere: its reflectance x the light's irradiance at its centre; a plane: its reflectance.
    float strength;
    // A plane: whether the light is on its normal's side; a plane and a sun: the image cone,
    // the same from every point (image_cone).
    bool light_above = false, fixed_cone = false;
    Vec3 axis{0.0f};
    float one_minus_cos = 0.0f, sin_cone = 0.0f;
    Vec3 light_image{0.0f};  // a glossy plane and a lamp: the lamp mirrored in the plane
    // A matte plane and a lamp: the point of the plane nearest the lamp, and the lamp's distance.
    Vec3 spot{0.0f};
    float height = 0.0f;
  };
  // The pair grid (mirror_images_grid.cpp). A plane's pair weighs 0 from most of space (behind
  // the plane, or where the light's image cone misses the plane's bounds), yet odds() would weigh
  // every pair at every path vertex: suzanne's glossy box makes 12 pairs, of which a vertex sees
  // ~1 (weighing them was ~6 % of its render; with the grid its core time is x0.96 at 64 spp).
  // So space is cut into cells over the scene's bounds, and each cell keeps the set of pairs
  // that some point in it may see, found by a conservative version of pair_weight's tests the
  // first time a vertex falls into the cell; odds() weighs only those. The others would weigh
  // exactly 0 there, so every sum is the same bit for bit. Points outside the grid weigh every
  // pair.
  static constexpr size_t kGridCells = 16384;   // about; the cells near cubes
  static constexpr uint64_t kCellKnown = 1ull << 63;  // a cell's set is computed (kMaxPairs <= 32)
  void build_pair_grid(const Scene& scene);
  uint64_t pairs_seen_from(const Vec3& p) const;  // the set (bit i: pair i) odds() weighs at p
  // The pairs some point of the box centre +- half may see (a superset: never leaves one out).
  uint64_t pairs_possible(const Vec3& centre, const Vec3& half) const;
  bool may_weigh(const Pair& pair, const Vec3& centre, const Vec3& half) const;
  uint64_t every_pair() const { return pairs_.size() >= 64 ? ~0ull : (1ull << pairs_.size()) - 1; }
  Odds weigh(const Origin& at, uint64_t pairs, float* weights) const;
  Vec3 grid_lo_{0.0f}, grid_hi_{-1.0f}, grid_cell_{1.0f};  // lo > hi: no grid
  int grid_n_[3] = {0, 0, 0};
  std::unique_ptr<std::atomic<uint64_t>[]> grid_;  // per cell: kCellKnown | its set, or 0 (not yet)

  // How often sample() at p picks the pair, relative to their sum (odds): 0 where p does
  // not see it (p off a plane on the light's side, both faces reflecting, and the light's image
  // cone meeting the plane's bounds; outside a sphere; p on the reflector's material), else
  // the light the reflector can send to p: a plane's strength x the light's irradiance at p's mirror
  // image (what the light's image brings to p); a sphere's strength x r^2 / (4 d^2) (the share of
  // the light it catches that a convex mirror of radius r sends to distance d).
  float pair_weight(const Pair& pair, const Origin& at) const {
    PlaneSight sight;
    return pair_weight(pair, at, sight);
  }
  // A plane reflector seen from a shading point p, the same for each of its pairs (odds() weighs
  // a box's faces light by light): p's height over the plane, the way to its bounds' centre, and
  // sqrt(d^2 - r^2) for bounds of radius r at distance d (< 0: p inside them).
  struct PlaneSight {
    int reflector = -1;
    float side = 0.0f;
    Vec3 to_bounds{0.0f};
    float clearance = -1.0f;
  };
  float pair_weight(const Pair& pair, const Origin& at, PlaneSight& sight) const;
  // Whether the light's image cone seen from p (image_cone) meets the plane's bounds, p outside them.
  bool image_meets_bounds(const Pair& pair, const Reflector& reflector, const Source& source, const Vec3& p,
                          const PlaneSight& sight) const;
  // The strategy runs at p with probability min(1, kRunScale x the pair weights' sum / direct) x
  // path_weight (at most 1), direct: the paired lights' own irradiance at p on its shading normal
  // n: where the reflectors send only a little of what the lights bring directly (a small ball
  // far away), it mostly leaves that light to BSDF sampling rather than spend rays on it; and it
  // spends fewer where the path carries little (path_weight: the largest channel of the path's
  // throughput at p, 1 at the camera's hit).
  static constexpr float kRunScale = 10.0f;
  // Glossy: the cone the strategy aims p into for `pair` (its axis, 1 - cos of its half-angle).
  void image_cone(const Pair& pair, const Vec3& p, Vec3& axis, float& one_minus_cos) const;
  // The angle under which a ball of radius r is seen from distance d (pi/2 from inside it).
  static float angular_radius_of(float r, float d) { return r < d ? std::asin(r / d) : 0.5f * kPi; }
  // p reflected in plane `reflector`.
  static Vec3 mirrored(const Reflector& reflector, const Vec3& p) {
    return p - 2.0f * glm::dot(p - reflector.point, reflector.normal) * reflector.normal;
  }
  // The density with which the strategy aims `at` along wi for `pair`, its choice included.
  float pair_pdf(const Pair& pair, const Origin& at, const Odds& odds, const Vec3& wi) const;

  // Lamps' bright spots on matte planes (lamp_spots.cpp). A lamp at height h over a matte plane
  // lights the plane's points y by E(y) = I cos / d^2, a spot of radius ~h that sends a large
  // share of the lamp's light back into the room and that BSDF sampling finds rarely from afar
  // (a ceiling lamp's bright ceiling). From every path vertex the strategy aims at points
  // of the spot drawn by E: directions from the lamp, uniform over the half-space towards the
  // plane, met with the plane; then NEE and BSDF sampling of the lamp there, as at a glossy plane.
  // A lamp (a point light with a radius, not a spot) pairs with a plane when it hangs within
  // kSpotReach of the plane's bounding radius over a point inside those bounds and the plane
  // sends back at least kMinSpotShare of the light all lights bring (2 albedo I against 4 pi I
  // summed over the lamps, plus each sun's irradiance over the largest plane's disk: among dozens
  // of lamps or under a sun no one spot matters); the kMaxSpots pairs that send the most
  // back are kept (each costs a little at every vertex).
  static constexpr float kSpotReach = 0.25f;
  static constexpr float kMinSpotShare = 0.05f;
  static constexpr size_t kMaxSpots = 4;
  // The planes of the matte materials that make the kept pairs become reflectors; returns the pairs.
  std::vector<Pair> lamp_spots(const Scene& scene, const std::vector<MaterialBsdf>& bsdfs,
                               const std::vector<uint32_t>& matte);
  // The light the spot sends to a point p above the plane, as a small Lambertian emitter of the
  // light the plane reflects (2 albedo I cos / d^2 from the spot's centre at distance d), over
  // kRunScale.
  float spot_weight(const Pair& pair, const Vec3& p) const;
  // The solid-angle density at p of aiming along wi (the plane point wi meets, drawn by E), and
  // one such direction.
  float spot_pdf(const Pair& pair, const Vec3& p, const Vec3& wi) const;
  bool sample_spot(const Pair& pair, const Vec3& p, const Vec2& u, Vec3& wi) const;

  std::vector<Reflector> reflectors_;
  std::vector<Source> sources_;
  std::vector<Pair> pairs_;
  std::vector<int> first_reflector_;  // per material: its first reflector (a box's planes follow), or -1
  std::vector<int> num_reflectors_;   // per material
  std::vector<bool> reflects_light_;  // [material * num_lights_ + light]: reflects_light()
  std::vector<int> pair_of_;  // [reflector * num_lights_ + light]: the pair's index, or -1
  size_t num_lights_ = 0;
};

}  // namespace torrance
