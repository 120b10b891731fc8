// The phase a conductor's reflection adds under a thin film (thin_film.h's over_conductor, Cycles
// 5.x's film over metals): its sign decides where the interference fringes fall, so it is pinned
// here against a calculation written out independently of thin_film.cpp: the exact (infinite)
// Airy sum of the complex amplitude reflection coefficients of ambient | film | metal, with the
// metal's index n + ik (fields exp(i(kz - wt)): an absorbing medium has Im(n) > 0), per
// wavelength, integrated against each Rec. 709 colour-matching function (CIE 1931 turned to
// Rec. 709) and normalised by that function's integral, s and p averaged. The same sum with the
// metal's phase shift of the other sign (its amplitudes conjugated, the film's path phase kept:
// the two time conventions mixed) misses it by far more than the tolerance (the core truncates
// the sum after three orders and reads a table).
#include "torrance/bsdfs/thin_film.h"
#include "torrance/shader/shader_convert.h"  // cie_1931, xyz_to_rec709

#include <gtest/gtest.h>

#include <complex>

namespace torrance {
namespace {

using Cd = std::complex<double>;

// The transmitted n cos of a wave entering index `to` (complex) from a medium where n sin is
// `n_sin`: sqrt(to^2 - n_sin^2) on the branch that decays into the medium (Im >= 0).
Cd n_cos_in(Cd to, double n_sin) {
  Cd r = std::sqrt(to * to - n_sin * n_sin);
  if (r.imag() < 0.0) r = -r;
  return r;
}

struct Amplitudes {
  Cd s, p;
};

// Fresnel amplitude reflection from index a into index b (either complex) given both n cos.
Amplitudes amplitudes(Cd a, Cd a_cos, Cd b, Cd b_cos) {
  // a_cos = a cos(theta_a), b_cos = b cos(theta_b).
  const Cd cos_a = a_cos / a, cos_b = b_cos / b;
  return {(a * cos_a - b * cos_b) / (a * cos_a + b * cos_b), (b * cos_a - a * cos_b) / (b * cos_a + a * cos_b)};
}

// Reflectance of ambient (1) | film (index film, d nm) | metal at incidence cos_i, wavelength l;
// flip: the metal's phase shift of the other sign.
double airy_reflectance(double cos_i, double film, double d, Cd metal, double l, bool flip) {
  const double n_sin = std::sqrt(1.0 - cos_i * cos_i);  // conserved across the layers (Snell)
  const Cd ambient_cos(cos_i), film_cos = n_cos_in(film, n_sin), metal_cos = n_cos_in(metal, n_sin);
  const Amplitudes top = amplitudes(1.0, ambient_cos, film, film_cos);
  Amplitudes bottom = amplitudes(film, film_cos, metal, metal_cos);
  if (flip) bottom = {std::conj(bottom.s), std::conj(bottom.p)};
  const Cd round_trip = std::exp(Cd(0.0, 4.0 * 3.14159265358979323846 * d / l) * film_cos);
  auto airy = [&](Cd r12, Cd r23) { return std::norm((r12 + r23 * round_trip) / (1.0 + r12 * r23 * round_trip)); };
  return 0.5 * (airy(top.s, bottom.s) + airy(top.p, bottom.p));
}

// Per Rec. 709 channel c: sum over 380..780 nm of cmf_c R / sum of cmf_c, metal index n_c + i k_c.
Vec3 reference(double cos_i, double film, double d, const Vec3& n, const Vec3& k, bool flip) {
  Vec3 out;
  for (int c = 0; c < 3; ++c) {
    double num = 0.0, den = 0.0;
    for (int step = 0; step <= 800; ++step) {
      const double l = 380.0 + 0.5 * step;
      const double w = shader::xyz_to_rec709(shader::cie_1931(float(l)))[c];
      num += w * airy_reflectance(cos_i, film, d, Cd(n[c], k[c]), l, flip);
      den += w;
    }
    out[c] = float(num / den);
  }
  return out;
}

TEST(ThinFilmConductor, PhaseShiftMatchesTheComplexAirySum) {
  // Gold-like n, k under 420 nm of IOR 1.45 (Cycles 5.x's table, the exact conductor Fresnel).
  const Vec3 n(0.18f, 0.42f, 1.37f), k(3.42f, 2.35f, 1.77f);
  const ThinFilm film{420.0f, 1.45f, true};
  double worst = 0.0, worst_conjugate = 0.0;
  for (float cos_i : {1.0f, 0.75f, 0.4f}) {
    const Vec3 got = film.over_conductor(cos_i, n, k, Vec3(-1.0f));
    const Vec3 want = reference(cos_i, 1.45, 420.0, n, k, false);
    const Vec3 conjugate = reference(cos_i, 1.45, 420.0, n, k, true);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(got[c], want[c], 4e-3f) << "cos " << cos_i << " channel " << c;
      worst = std::max(worst, double(std::abs(got[c] - want[c])));
      worst_conjugate = std::max(worst_conjugate, double(std::abs(got[c] - conjugate[c])));
    }
  }
  std::printf("film over gold: worst |core - Airy| %.5f; against the metal's phase of the other sign %.4f\n", worst,
              worst_conjugate);
  // The test can tell the conventions apart: they differ by far more than its tolerance.
  EXPECT_GT(worst_conjugate, 0.03);
}

}  // namespace
}  // namespace torrance
