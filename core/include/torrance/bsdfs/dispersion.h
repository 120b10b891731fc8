// Dispersion as Cycles 5.x renders it (Blender 5.x's Principled BSDF inputs "Transmission
// Dispersion Scale" and "Transmission Dispersion Abbe Number"; Blender 4.x and the Glass BSDF have
// none). Material::dispersion is their quotient, the inverse Abbe number V^-1 = Scale / Abbe
// (Scale clamped to [0, 1], Abbe to >= 0; 0: none).
//
// A path draws one wavelength lambda (um) from a fixed density p(lambda) (a logistic fit of the
// luminance of D65 over [0.38, 0.78] um) and keeps it for all its bounces. At the first vertex
// whose shader holds a dispersive transmission closure the path turns monochromatic: its
// throughput is multiplied once by rgb(lambda) / p(lambda), rgb(lambda) the colour of D65 light
// at lambda (CIE 1931 x, y, z times D65's power, to Rec. 709, scaled so that the integral over
// lambda is white: E[weight] = (1, 1, 1) up to the fit). From then on every dispersive closure it
// meets refracts with the IOR at lambda, Cauchy's law through the IOR n_d given at the d line
// (587.6 nm) and the Abbe number V = (n_d - 1) / (n_F - n_C) (OpenPBR 1.1's Eq. 55-56):
//   n(lambda) = A + B / lambda^2,  B = (n_d - 1) V^-1 / (1/lambda_F^2 - 1/lambda_C^2),
//   A = n_d - B / lambda_d^2.
// Only the refracting IOR disperses: the closure's F0 stays F0(n_d) x Specular Tint
// (principled_glass_v2.h).
#pragma once

#include "torrance/bsdfs/bsdf.h"

namespace torrance::dispersion {

// The wavelength a path keeps, drawn from its number u in [0, 1), and the weight its throughput
// takes at its first dispersive vertex.
struct Wavelength {
  float micrometres = 0.0f;
  Vec3 weight{1.0f};  // rgb(lambda) / p(lambda)
};
Wavelength sample_wavelength(float u);
// The density of sample_wavelength over [0.38, 0.78] um relative to the uniform one there, at the
// fit's number u (p = 1 for a uniform choice; the weight divides by it).
float wavelength_density(float u);
// rgb(lambda) of D65 light at lambda um (0 outside [0.38, 0.78) um), integrating to white over
// [0.38, 0.78] um divided by its width 0.4 um.
Vec3 d65_colour(float micrometres);

// The IOR at lambda um of a material of IOR ior (the front side's, > 0) at the d line and inverse
// Abbe number inv_abbe (Cauchy, as above); ior itself when inv_abbe is 0.
float cauchy_ior(float ior, float inv_abbe, float micrometres);

// Whether material m has a dispersive transmission closure under model (Principled v2's
// transmission with dispersion > 0: not a Glass node, not Thin Wall, some transmission left by
// its metallic); only those take the path's wavelength.
bool disperses(const Material& m, BrdfModel model);
// The refracting IOR of m's transmission at its wavelength (Material::wavelength; 0: the d line).
inline float refracting_ior(const Material& m) {
  return m.dispersion > 0.0f && m.wavelength > 0.0f ? cauchy_ior(m.ior, m.dispersion, m.wavelength) : m.ior;
}

}  // namespace torrance::dispersion
