#include "torrance/bsdfs/thin_film.h"

#include "torrance/bsdfs/ggx_tables.h"     // f0_from_ior
#include "torrance/bsdfs/metal_fresnel.h"  // F82Tint
#include "torrance/shader/shader_convert.h"  // cie_1931, xyz_to_rec709
#include "torrance/util/smoothstep.h"

#include <array>
#include <complex>
#include <vector>

namespace torrance {

namespace {

using Complex = std::complex<float>;

// The film's index as Cycles blends it towards the ambient 1 for films thinner than `full` nm.
float blended_ior(const ThinFilm& f, float full) {
  return f.thickness < full ? 1.0f + (f.ior - 1.0f) * smooth_step(0.0f, full, f.thickness) : f.ior;
}

// One dielectric interface at incidence cos_i (> 0) into relative index eta: the s and p
// reflectances, whether each amplitude is negative (a phase shift of pi), and the transmitted
// cosine (> 0); tir without a transmitted wave.
struct Interface {
  Vec2 r{1.0f};
  bool flip_s = false, flip_p = false;
  float cos_t = 0.0f;
  bool tir = true;
};

Interface dielectric_interface(float cos_i, float eta) {
  Interface out;
  const float eta_cos_t_sq = eta * eta - (1.0f - cos_i * cos_i);
  if (!(eta_cos_t_sq > 0.0f)) return out;
  out.tir = false;
  out.cos_t = std::sqrt(eta_cos_t_sq) / eta;
  const float amp_s = (cos_i - eta * out.cos_t) / (cos_i + eta * out.cos_t);
  const float amp_p = (eta * cos_i - out.cos_t) / (eta * cos_i + out.cos_t);
  out.r = Vec2(amp_s * amp_s, amp_p * amp_p);
  out.flip_s = amp_s < 0.0f;
  out.flip_p = amp_p < 0.0f;
  return out;
}

// The Airy sum's coefficients for reflectances r12 (top) and r23 (bottom): C0, and C1 (Cm for m
// > 1 is C1 times the amplitude ratio^(m - 1)).
struct AirySeries {
  float c0 = 1.0f, c1 = 0.0f, ratio = 0.0f;
};

AirySeries airy_series(float r12, float r23) {
  AirySeries a;
  const float r123 = r12 * r23;
  if (!(r123 < 1.0f)) return a;  // no light in the film: all reflected
  const float t121 = 1.0f - r12;
  const float rs = t121 * t121 * r23 / (1.0f - r123);
  a.ratio = std::sqrt(r123);
  a.c0 = r12 + rs;
  a.c1 = (rs - t121) * a.ratio;
  return a;
}

constexpr int kOrders = 3;  // Cycles truncates the sum after m = 3

// ---- Cycles 4.x: Belcour & Barla's Gaussian fit of the CIE XYZ functions' spectrum ----------

// Re(exp(i shift) S_xyz(opd)), each XYZ function's transform a Gaussian in the wave number
// (1/m): amplitude, centre and variance per component, plus a second Gaussian for x's blue lobe;
// normalised by their common integral (the Y function's).
Vec3 sensitivity_xyz(float opd, float shift) {
  const float phase = kTwoPi * opd * 1e-9f;
  const Vec3 amplitude(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
  const Vec3 centre(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
  const Vec3 variance(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
  Vec3 xyz;
  for (int c = 0; c < 3; ++c)
    xyz[c] = amplitude[c] * std::sqrt(kTwoPi * variance[c]) * std::cos(centre[c] * phase + shift) *
             std::exp(-phase * phase * variance[c]);
  xyz.x += 1.64408e-8f * std::cos(2.2399e+06f * phase + shift) * std::exp(-4.5282e+09f * phase * phase);
  return xyz * (1.0f / 1.0685e-7f);
}

Vec3 airy_xyz(float r12, float r23, float opd, float phi) {
  if (r23 == 1.0f) return Vec3(1.0f);
  const AirySeries a = airy_series(r12, r23);
  Vec3 r(a.c0);
  float cm = a.c1;
  for (int m = 1; m <= kOrders; ++m, cm *= a.ratio) r += 2.0f * cm * sensitivity_xyz(float(m) * opd, float(m) * phi);
  return r;
}

Vec3 over_dielectric_cycles4(const ThinFilm& f, float cos_i, float eta) {
  const float n2 = blended_ior(f, 30.0f);
  const Interface top = dielectric_interface(cos_i, n2);
  if (top.tir) return Vec3(1.0f);
  const Interface bottom = dielectric_interface(top.cos_t, eta / n2);
  if (bottom.tir) return Vec3(1.0f);
  const float opd = 2.0f * n2 * f.thickness * top.cos_t;
  // phi = pi - phi12 + phi23 per polarisation.
  const float phi_s = kPi - (top.flip_s ? kPi : 0.0f) + (bottom.flip_s ? kPi : 0.0f);
  const float phi_p = kPi - (top.flip_p ? kPi : 0.0f) + (bottom.flip_p ? kPi : 0.0f);
  Vec3 xyz = 0.5f * (airy_xyz(top.r.x, bottom.r.x, opd, phi_s) + airy_xyz(top.r.y, bottom.r.y, opd, phi_p));
  xyz *= Vec3(0.95047f, 1.0f, 1.08883f);  // illuminant E's CMFs to the D65 working white
  return glm::clamp(shader::xyz_to_rec709(xyz), Vec3(0.0f), Vec3(1.0f));
}

// ---- Cycles 5.x: the Rec. 709 functions' transform, tabulated ------------------------------

constexpr int kTableSize = 512;
constexpr float kTableOpd = 60000.0f / kTwoPi;  // nm: the last entry's OPD (clamped beyond)

struct SensitivityTable {
  std::array<Vec3, kTableSize> re, im;
};

// S(x) = sum cmf(l) exp(2 pi i x / l) / sum cmf(l) per Rec. 709 channel, the CIE 1931 functions
// turned to Rec. 709 every 0.5 nm from 380 to 780 nm (double precision sums).
SensitivityTable build_table() {
  std::vector<std::pair<double, glm::dvec3>> cmf;
  for (int i = 0; i <= 800; ++i) {
    const double l = 380.0 + 0.5 * i;
    cmf.emplace_back(l, glm::dvec3(shader::xyz_to_rec709(shader::cie_1931(float(l)))));
  }
  SensitivityTable t;
  glm::dvec3 dc(0.0);
  for (const auto& s : cmf) dc += s.second;
  for (int j = 0; j < kTableSize; ++j) {
    const double x = double(kTableOpd) * j / (kTableSize - 1);
    glm::dvec3 re(0.0), im(0.0);
    for (const auto& [l, w] : cmf) {
      const double phase = 2.0 * 3.14159265358979323846 * x / l;
      re += w * std::cos(phase);
      im += w * std::sin(phase);
    }
    t.re[size_t(j)] = Vec3(re / dc);
    t.im[size_t(j)] = Vec3(im / dc);
  }
  return t;
}

const SensitivityTable& table() {
  static const SensitivityTable t = build_table();
  return t;
}

// The sensitivities S(m opd) of the orders m = 1 .. kOrders (re, im per channel).
struct Sensitivities {
  std::array<Vec3, kOrders> re, im;
  explicit Sensitivities(float opd) {
    for (int m = 1; m <= kOrders; ++m) thin_film::sensitivity_rec709(float(m) * opd, re[m - 1], im[m - 1]);
  }
};

// Re(phasor^m S(m opd)) summed as the Airy series of one channel.
float airy_channel(int c, float r12, float r23, const Sensitivities& s, Complex phasor) {
  const AirySeries a = airy_series(r12, r23);
  float r = a.c0, cm = a.c1;
  Complex turn = phasor;
  for (int m = 0; m < kOrders; ++m, cm *= a.ratio, turn *= phasor)
    r += 2.0f * cm * (turn.real() * s.re[m][c] - turn.imag() * s.im[m][c]);
  return r;
}

float sign_of(bool flip) { return flip ? -1.0f : 1.0f; }

// A conductor n + ik under a dielectric of index eta1 at cos_i: the s and p reflectances and
// phasors exp(i phi) (Born & Wolf's amplitudes, with n + ik); f82 >= 0: the reflectances are the
// F82 model through F0 of (n, k) / eta1 and f82.
struct ConductorInterface {
  Vec2 r{1.0f};
  Complex phasor_s{1.0f, 0.0f}, phasor_p{1.0f, 0.0f};
};

ConductorInterface conductor_interface(float cos_i, float eta1, float n, float k, float f82) {
  ConductorInterface out;
  const float eta1_sq = eta1 * eta1, two_nk = 2.0f * n * k, n2_k2 = n * n - k * k;
  const float t1 = n2_k2 - eta1_sq * (1.0f - cos_i * cos_i);
  const float t2 = std::sqrt(t1 * t1 + two_nk * two_nk);
  const float u_sq = std::max(0.5f * (t2 + t1), 0.0f), v_sq = std::max(0.5f * (t2 - t1), 0.0f);
  const float u = std::sqrt(u_sq), v = std::sqrt(v_sq);
  const float a = eta1 * cos_i;
  auto ratio = [](float num, float den) { return den != 0.0f ? num / den : 0.0f; };
  if (f82 >= 0.0f) {
    const float nr = n / eta1, kr_sq = (k / eta1) * (k / eta1);
    const float f0 = ((nr - 1.0f) * (nr - 1.0f) + kr_sq) / ((nr + 1.0f) * (nr + 1.0f) + kr_sq);
    out.r = Vec2(F82Tint::through(Vec3(f0), Vec3(f82)).eval(cos_i).x);
  } else {
    const float rs = ratio((a - u) * (a - u) + v_sq, (a + u) * (a + u) + v_sq);
    const float t3 = n2_k2 * cos_i, t4 = two_nk * cos_i;
    const float rp = ratio((t3 - eta1 * u) * (t3 - eta1 * u) + (t4 - eta1 * v) * (t4 - eta1 * v),
                           (t3 + eta1 * u) * (t3 + eta1 * u) + (t4 + eta1 * v) * (t4 + eta1 * v));
    out.r = Vec2(rs, rp);
  }
  // The amplitudes' phases: numerator times the denominator's conjugate.
  const Complex s(a * a - u_sq - v_sq, -2.0f * a * v);
  const float eps_sq = (n * n + k * k) * (n * n + k * k);
  const Complex p(eps_sq * cos_i * cos_i - eta1_sq * (u_sq + v_sq), 2.0f * a * (two_nk * u - n2_k2 * v));
  out.phasor_s = std::abs(s) > 0.0f ? s / std::abs(s) : Complex(1.0f, 0.0f);
  out.phasor_p = std::abs(p) > 0.0f ? p / std::abs(p) : Complex(1.0f, 0.0f);
  return out;
}

}  // namespace

void thin_film::sensitivity_rec709(float x, Vec3& re, Vec3& im) {
  const SensitivityTable& t = table();
  const float index = clamp01(x / kTableOpd) * float(kTableSize - 1);
  const int i = std::min(int(index), kTableSize - 1), next = std::min(i + 1, kTableSize - 1);
  const float w = index - float(i);
  re = glm::mix(t.re[size_t(i)], t.re[size_t(next)], w);
  im = glm::mix(t.im[size_t(i)], t.im[size_t(next)], w);
}

Vec3 ThinFilm::over_dielectric(float cos_i, float eta) const {
  if (!cycles5) return over_dielectric_cycles4(*this, cos_i, eta);
  const float n2 = blended_ior(*this, 1.0f);
  const Interface top = dielectric_interface(cos_i, n2);
  if (top.tir) return Vec3(1.0f);
  const Interface bottom = dielectric_interface(top.cos_t, eta / n2);
  if (bottom.tir) return Vec3(1.0f);
  const Sensitivities s(2.0f * n2 * thickness * top.cos_t);  // at the optical path difference
  // exp(i (pi + phi23 - phi12)): real for dielectrics.
  const Complex phasor_s(-sign_of(top.flip_s) * sign_of(bottom.flip_s), 0.0f);
  const Complex phasor_p(-sign_of(top.flip_p) * sign_of(bottom.flip_p), 0.0f);
  Vec3 out;
  for (int c = 0; c < 3; ++c)
    out[c] = clamp01(0.5f * (airy_channel(c, top.r.x, bottom.r.x, s, phasor_s) +
                             airy_channel(c, top.r.y, bottom.r.y, s, phasor_p)));
  return out;
}

Vec3 ThinFilm::over_conductor(float cos_i, const Vec3& n, const Vec3& k, const Vec3& f82) const {
  const float n2 = blended_ior(*this, 1.0f);
  const Interface top = dielectric_interface(cos_i, n2);
  if (top.tir) return Vec3(1.0f);
  const Sensitivities s(2.0f * n2 * thickness * top.cos_t);
  Vec3 out;
  for (int c = 0; c < 3; ++c) {
    const ConductorInterface bottom = conductor_interface(top.cos_t, n2, n[c], k[c], f82[c]);
    const Complex phasor_s = bottom.phasor_s * -sign_of(top.flip_s);
    const Complex phasor_p = bottom.phasor_p * -sign_of(top.flip_p);
    out[c] = clamp01(0.5f * (airy_channel(c, top.r.x, bottom.r.x, s, phasor_s) +
                             airy_channel(c, top.r.y, bottom.r.y, s, phasor_p)));
  }
  return out;
}

void conductor_from_f82(const Vec3& f0, const Vec3& f82, Vec3& n, Vec3& k) {
  for (int c = 0; c < 3; ++c) {
    const float r = std::min(f0[c], 0.999f), sqrt_r = std::sqrt(std::max(r, 0.0f));
    n[c] = glm::mix((1.0f + sqrt_r) / (1.0f - sqrt_r), (1.0f - r) / (1.0f + r), f82[c]);
    const float k_sq = (r * (n[c] + 1.0f) * (n[c] + 1.0f) - (n[c] - 1.0f) * (n[c] - 1.0f)) / (1.0f - r);
    k[c] = std::sqrt(std::max(k_sq, 0.0f));
  }
}

Vec3 tinted_film_fresnel(const Vec3& film, const Vec3& f0, float eta) {
  const float f0_real = ggx_tables::f0_from_ior(eta);
  if (!(f0_real > 1e-5f) || film == Vec3(1.0f)) return film;
  Vec3 out = film;
  for (int c = 0; c < 3; ++c) {
    const float s = clamp01((film[c] - 1.0f) / (f0_real - 1.0f));
    out[c] *= glm::mix(1.0f, f0[c] / f0_real, s);
  }
  return out;
}

}  // namespace torrance
