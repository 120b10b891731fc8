// The Sheen BSDF node's Microfiber distribution (Blender 4.0+) as Cycles 4.x/5.x renders it
// (closure/bsdf_sheen.h): Zeltner, Burley and Chiang's "Practical Multiple-Scattering Sheen Using
// Linearly Transformed Cosines" (2022). For a viewer at cos_o and roughness r (clamped to
// [1e-3, 1]) three numbers are read from a 32 x 32 table over (cos_o, r) (sheen_ltc_table.h):
// the LTC's a and b and the lobe's albedo R. In a frame whose x axis is wo's tangential
// direction (y = z x x), a light direction l = (x, y, z) gets
//
//   f cos = colour * R * D(l),   D(l) = z / pi * (a / |M^-1 l|^2)^2,   |M^-1 l|^2 = (a x + b z)^2 + (a y)^2 + z^2,
//
// the cosine lobe transformed by M (D integrates to at most 1 over the hemisphere), and is
// sampled exactly by D: a uniform point d of the disk, z_d = sqrt(1 - |d|^2), l the normalised
// ((d_x - z_d b) / a, d_y / a, z_d). Everything it reflects is "diffuse" (Cycles' LABEL_DIFFUSE).
// The table is read at each query for its wo (three bilinear lookups). See bsdf.h for the
// conventions (eval includes the cosine).
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance {

class SheenBsdf {
 public:
  SheenBsdf() = default;
  SheenBsdf(const Vec3& color, float roughness);

  LobeEval eval_lobes(const Vec3& wo, const Vec3& wi) const;
  Vec3 eval(const Vec3& wo, const Vec3& wi) const { return eval_lobes(wo, wi).total(); }
  float pdf(const Vec3& wo, const Vec3& wi) const;
  BsdfSample sample(const Vec3& wo, float u_lobe, const Vec2& u) const;
  // What a mixture samples it by: its colour's luminance times its albedo at normal incidence.
  float sampling_albedo() const;

  // The lobe for one viewer wo (also a layer of PRINCIPLED_V2, principled_sheen.h).
  struct Lobe {
    Vec3 weight{0.0f};  // colour * R: its albedo (0: nothing reflected)
    Vec3 x, y;          // the LTC frame's tangents (z: the normal)
    float a = 1.0f, b = 0.0f;
    bool reflects() const { return max_component(weight) > 0.0f; }
    float density(const Vec3& wi) const;  // D(l) for wi in the shading frame (wi.z > 0)
    Vec3 sample(const Vec2& u) const;     // a direction drawn from D (z <= 0: none)
  };
  Lobe lobe(const Vec3& wo) const { return oriented(lobe_at(wo.z), wo); }
  Lobe lobe_at(float cos_o) const;                    // its weight, a and b (the frame unset)
  static Lobe oriented(Lobe l, const Vec3& wo);       // l with the frame of wo

 private:
  Vec3 color_{0.0f};
  float roughness_ = 1.0f;
};

}  // namespace torrance
