// Suns seen in flat mirrors: next-event estimation of a sun's light reflected once by a planar
// perfect mirror (a material that is a delta reflection and nothing else, lying in one plane:
// a mirror, a polished metal floor of roughness 0).
//
// Such light reaches a diffuse or glossy point x only along paths x -> mirror -> sun, which
// ordinary NEE cannot sample (the mirror is a delta lobe) and BSDF sampling at x finds only when
// its direction happens to land in the sun's small mirror image: the caustic fireflies of a
// low sun over a mirror floor. Reflection in a plane keeps solid angle, so the sun's image is a
// second sun of the same cone seen along the reflected direction, and NEE can sample it: pick a
// direction d in the sun's cone, aim x at its mirror image wi = d - 2 (d.n) n, check that the
// first thing wi meets is the mirror and that nothing hides the sun from there, and weigh
// by the mirror's reflectance. BSDF sampling at x still finds the same paths; both strategies'
// weights come from the power heuristic over the same two densities (the BSDF's pdf of wi at x and
// this strategy's pdf, the sun's cone density times the choice of the pair), so they sum to 1.
// Suns of angle 0 are left out: no BSDF-sampled path can reach a delta sun through a mirror,
// so Cycles renders no such light, and Torrance matches it.
//
// Only world-space meshes are examined for planes (instanced geometry is not), and the strategy is
// not used in scenes with alpha (a BSDF-sampled path passes transparent surfaces this strategy's
// rays would stop at).
#pragma once

#include "torrance/material_bsdf.h"
#include "torrance/scene.h"

#include <vector>

namespace torrance {

class MirrorImages {
 public:
  // The scene's planar mirrors (bsdfs: the render's, one per material) and its suns.
  MirrorImages(const Scene& scene, const std::vector<MaterialBsdf>& bsdfs);
  bool empty() const { return mirrors_.empty() || suns_.empty(); }
  size_t num_mirrors() const { return mirrors_.size(); }
  // The mirror made of material `material`, or -1.
  int mirror_of(uint32_t material) const {
    return material < mirror_of_material_.size() ? mirror_of_material_[material] : -1;
  }

  struct Sample {
    Vec3 wi{0.0f};      // from the shading point towards the sun's image in the mirror
    Vec3 to_sun{0.0f};  // from the mirror towards the sun (wi reflected)
    Vec3 weight{0.0f};  // the sun's radiance over pdf (its irradiance for a delta sun)
    float pdf = 0.0f;   // the solid-angle density of wi, pair choice included; 0: a delta sun
    int mirror = -1;
  };
  // One direction towards a sun's image in a mirror, the (mirror, sun) pair chosen uniformly among
  // those p sees: p off the mirror's plane on the side the sun shines on (a mirror reflects on
  // both faces). False: p sees none.
  bool sample(const Vec3& p, float u_pair, const Vec2& u, Sample& out) const;
  // The reflectance of `mirror` for light arriving from direction to_sun.
  Vec3 reflectance(int mirror, const Vec3& to_sun) const;
  // What the suns send along `dir` (from a point on `mirror`, unoccluded), as a path that left
  // p with BSDF density bsdf_pdf and was reflected by the mirror: the suns' radiance weighted
  // against this strategy at p by the power heuristic.
  Vec3 suns_through(int mirror, const Vec3& p, const Vec3& dir, float bsdf_pdf) const;

 private:
  struct Mirror {
    Vec3 point, normal;
    const MaterialBsdf* bsdf;
  };
  // Whether p sees sun s in mirror m (the side test of sample()).
  bool sees(const Mirror& m, const SunLight& s, const Vec3& p) const;
  size_t pairs_seen(const Vec3& p) const;

  std::vector<Mirror> mirrors_;
  std::vector<int> mirror_of_material_;
  std::vector<const SunLight*> suns_;
};

}  // namespace torrance
