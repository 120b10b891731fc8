// The Principled BSDF's Thin Wall (Blender 5.x) as Cycles 5.x renders it: the surface is an
// infinitely thin sheet (OpenPBR's thin-walled case), seen alike from both sides, so there is no
// inside, no refraction and no random walk. What replaces the closures of a solid surface
// (svm/closure.h, closure/bsdf_microfacet.h's thin glass, closure/bsdf_oren_nayar.h's thin
// subsurface):
//
//   Transmission (weight transmission (1 - metallic), under the coat and sheen as the glass of
//   a solid surface): a slab of IOR ior between two faces. Each face reflects
//   F(c) = mix(f0, 1, s(c)) (f0 = F0(ior) Specular Tint, s as principled_glass_v2.h, c = wo.z)
//   and lets 1 - F through; the slab's inside absorbs C = base^(1 / cos_t) (base clamped to
//   [0, 1], the transmittance at normal incidence; cos_t the refracted cosine at ior). Summing
//   the light bouncing between the faces:
//       T = C (1 - F)^2 / (1 - (F C)^2),     R = F + T F C.
//   R weighs a GGX reflection of alpha = roughness^2 (isotropic: Anisotropic does not act),
//   T a GGX "reflection" about -n of the view mirrored through the surface, i.e. a lobe around
//   the straight-through direction -wo, of the roughened alpha_t = clamp(3.4 alpha (eta - 1)
//   (eta - 1/2)^2 / eta^3, 0, 1) (Kulla & Conty 2017: two refractions). Both lobes carry the
//   albedo compensation 1 + F_ms (1 - E) / E whatever the distribution (Cycles always applies
//   it to these closures), with F_ss = Specular Tint for R and 1 for T (so T's is 1 / E).
//   A lobe of alpha below ggx_tables::kDeltaAlpha is a delta: a mirror, or straight through.
//   As Cycles, rays other than the camera's see a smooth sheet's T as transparent (Cycles
//   allocates a Transparent closure instead): shadow rays pass it (integrator/thin_wall_shadow.h)
//   and the path tracer takes the straight pass (BsdfSample::straight_through) as a transparent
//   step; the camera's ray sees the delta lobe.
//
//   Thin Film (thin_film.h; Cycles 5.x's film, its cutoff): each face's F is the film's
//   reflectance over the slab scaled by the tint as a solid glass's (tinted_film_fresnel): the
//   front at c over IOR ior, the back at cos_t, seen from inside, over 1 / ior with the film's
//   IOR / ior (Cycles' adjust_thin_film_ior_at_backface); then
//       T = C (1 - F1)(1 - F2) / (1 - (F2 C)^2),     R = F1 + T F2 C,
//   which without a film is the sum above (F1 = F2 = F). A white slab keeps R + T = 1.
//
//   Subsurface (weight the subsurface layer's, ViewTerms::translucent + the diffuse share): the
//   walk becomes a diffuse reflection of weight (1 - g) / 2 and a diffuse transmission (about -n)
//   of weight (1 + g) / 2, g = Subsurface Anisotropy (each clamped to [0, 1]): Lambertian at
//   Diffuse Roughness 0, else Cycles' Oren-Nayar pair (oren_nayar_eon.h of the base colour and
//   Diffuse Roughness; the transmission is its reflection of the light mirrored through the
//   surface, Cycles' rough translucent closure). The reflection share joins the diffuse layer
//   (principled_v2.cpp); the transmission is the third lobe here, sampled by the cosine.
//
// Frame: the shading frame turned to the viewer (wo.z > 0); wi.z < 0 is the far side. eval()
// includes |cos_i| (bsdf.h). Sampling picks a lobe by the luminance of its weight, then R and T
// by their visible normals, the translucent lobe by the cosine.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/oren_nayar_eon.h"
#include "torrance/bsdfs/thin_film.h"

namespace torrance {

class ThinWallV2 {
 public:
  ThinWallV2(float roughness, float ior, const Vec3& specular_tint, const Vec3& base_color,
             const ThinFilm& film = ThinFilm{}, float diffuse_roughness = 0.0f);

  // The slab's reflectance and transmittance for a viewer at cos c (Cycles' bsdf_thin_glass_fresnel).
  struct Slab {
    Vec3 reflect{0.0f}, transmit{0.0f};
  };
  Slab slab(float c) const;

  // The lobes' weights seen from wo (glass: the transmission's closure weight with its layers;
  // translucent: the translucent lobe's weight), and the lobe choice.
  struct View {
    Vec3 wo{0.0f, 0.0f, 1.0f};
    Vec3 reflect{0.0f}, transmit{0.0f}, translucent{0.0f};  // weights, albedo scale included
    float p_reflect = 0.0f, p_transmit = 0.0f, p_translucent = 0.0f;
  };
  View at(const Vec3& wo, const Vec3& glass, const Vec3& translucent) const;

  LobeEval eval(const View& v, const Vec3& wi) const;  // transmitted light in glossy, translucent in diffuse
  float pdf(const View& v, const Vec3& wi) const;
  BsdfSample sample(const View& v, float u_lobe, const Vec2& u) const;

  float alpha() const { return alpha_; }
  float transmission_alpha() const { return alpha_t_; }
  bool reflection_is_delta() const;
  bool transmission_is_delta() const;

 private:
  Vec3 f0_, base_;
  float alpha_, alpha_t_, roughness_, roughness_t_, ior_;
  Vec3 fss_reflect_;
  ThinFilm film_, film_inside_;  // on the front face, and on the back seen from inside (IOR / ior)
  EnergyPreservingOrenNayar translucency_;  // the translucent lobe (Lambert at Diffuse Roughness 0)
  // A face's F: the dielectric's generalized Schlick term or, with a film, the tinted film's.
  Vec3 face_fresnel(float c, float eta, const ThinFilm& film) const;
};

}  // namespace torrance
