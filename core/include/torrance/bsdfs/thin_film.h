// Thin-film interference ("Thin Film Thickness" / "Thin Film IOR" of Blender 4.2+'s Principled
// BSDF, 5.x's Metallic and Glass BSDFs) as Cycles renders it: a dielectric film of thickness d
// (nm) and index n2 between the ambient medium (index 1: indices below are relative to it) and
// the surface, whose colour comes from the interference of the light reflected back and forth in
// the film (Belcour & Barla, "A Practical Extension to Microfacet Theory for the Modeling of
// Varying Iridescence", 2017).
//
// Per polarisation (s, p), with R12 (phase phi12) the film's top interface's reflectance at the
// incidence cos1, cos2 the cosine inside the film (Snell), R23 (phase phi23) the substrate's
// reflectance seen from the film at cos2, T121 = 1 - R12 and the optical path difference
// OPD = 2 n2 d cos2, the reflectance at wavelength lambda is the Airy sum
//
//   R(lambda) = C0 + 2 sum_{m >= 1} Cm cos(m (2 pi OPD / lambda + phi)),   phi = pi + phi23 - phi12,
//   C0 = R12 + Rs,  Rs = T121^2 R23 / (1 - R12 R23),  Cm = (Rs - T121) (R12 R23)^(m/2),
//
// truncated after m = 3 (as Cycles). Its colour is R's integral against the colour-matching
// functions; with the sum's terms sinusoidal in the wave number 1/lambda, each is the CMFs'
// Fourier transform S(x) = int cmf(lambda) exp(2 pi i x / lambda) d lambda / int cmf d lambda,
// read at x = m OPD (the sensitivity). The two polarisations' colours are averaged.
//
// Cycles 4.x (ThinFilm::cycles5 false): S from Belcour & Barla's Gaussian fit of the CIE XYZ
// functions (closed form), the XYZ result scaled by the working white (D65 XYZ, illuminant E's
// CMFs to D65), turned to Rec. 709 and clamped to [0, 1]; n2 blends from 1 at d = 0 to itself at
// d = 30 nm (smoothstep); over dielectrics only (Principled's specular and transmission).
// Cycles 5.x (cycles5 true): S tabulated per Rec. 709 channel (the CIE 1931 functions turned to
// Rec. 709, each channel's S(0) = 1) over OPD in [0, 60000 / (2 pi)] nm (clamped beyond, as its
// table), each channel's polarisation mean clamped to [0, 1]; n2 blends over d in [0, 1] nm; and
// over conductors too, the substrate's phase shifts complex (Born & Wolf's conductor Fresnel):
// the Principled metal and the Metallic BSDF's F82 mode with n, k estimated from F0 and F(1/7)
// (Gulbrandsen, "Artist Friendly Metallic Fresnel", 2014) and R23 the F82 model refitted to
// (n, k) / n2, the Physical Conductor with its exact R23.
//
// Total internal reflection at the top (n2 < 1 at grazing) or at the bottom of a dielectric: 1.
// A film of d <= 0.1 nm is no film (Cycles' cutoff): the closures keep their plain Fresnel.
#pragma once

#include "torrance/util/math.h"

namespace torrance {

struct ThinFilm {
  static constexpr float kCutoff = 0.1f;  // nm: thinner is no film
  float thickness = 0.0f;                 // nm
  float ior = 1.33f;
  bool cycles5 = false;  // Cycles 5.x's table and conductors, else 4.x's closed form

  bool active() const { return thickness > kCutoff; }
  // Whether the film lies over conductors too (the Principled's metal, the Metallic BSDF): Cycles
  // 5.x's; 4.x puts it over dielectrics only.
  bool over_conductors() const { return active() && cycles5; }
  // The film's reflectance over a dielectric of relative index eta (substrate / ambient) for
  // incidence cos_i (from the ambient side, > 0).
  Vec3 over_dielectric(float cos_i, float eta) const;
  // Cycles 5.x: over a conductor of index n + ik per channel; f82 >= 0 (per channel): R23 is the
  // F82 model through F0(n, k) and that value at 1/7 (Principled's metal), < 0: the exact one.
  Vec3 over_conductor(float cos_i, const Vec3& n, const Vec3& k, const Vec3& f82) const;
};

// Gulbrandsen's n, k of a metal from its reflectances at normal incidence (f0) and at 1/7 (f82),
// as Cycles 5.x estimates them for a film over F82-tint metal (f0 capped at 0.999).
void conductor_from_f82(const Vec3& f0, const Vec3& f82, Vec3& n, Vec3& k);

// Principled's dielectric with a film (Cycles' generalized Schlick Fresnel): the film's
// reflectance f scaled towards f0 / F0(eta) per channel as far as f lies from 1 towards F0(eta)
// (Specular Tint and Specular IOR Level's artistic F0), untouched where f = 1.
Vec3 tinted_film_fresnel(const Vec3& film, const Vec3& f0, float eta);

namespace thin_film {
// The sensitivity S (the normalised Fourier transform of the colour-matching functions, see
// above) at optical path difference x (nm), per channel: Cycles 5.x's Rec. 709 one (re, im).
void sensitivity_rec709(float x, Vec3& re, Vec3& im);
}  // namespace thin_film

}  // namespace torrance
