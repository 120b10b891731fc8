#include "torrance/util/sampling.h"

#include "torrance/util/owen_sobol.h"

#include <emmintrin.h>

#include <array>

namespace torrance {
namespace {

uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Sobol generator matrices for 4 dimensions (direction numbers of Joe & Kuo: dimension 0 is van
// der Corput; then the primitive polynomials x + 1, x^2 + x + 1, x^3 + x + 1 with initial
// m = {1}, {1, 3}, {1, 3, 1}), built once by the standard recurrence.
struct SobolMatrices {
  std::array<std::array<uint32_t, 32>, 4> v{};
  SobolMatrices() {
    for (int k = 0; k < 32; ++k) v[0][k] = 1u << (31 - k);
    const int degree[3] = {1, 2, 3};
    const uint32_t poly_a[3] = {0, 1, 1};  // inner coefficients of the polynomials, as bits
    const std::array<uint32_t, 3> initial_m[3] = {{1, 0, 0}, {1, 3, 0}, {1, 3, 1}};
    for (int d = 0; d < 3; ++d) {
      const int s = degree[d];
      uint32_t m[32];
      for (int k = 0; k < s; ++k) m[k] = initial_m[d][k];
      for (int k = s; k < 32; ++k) {
        uint32_t value = m[k - s] ^ (m[k - s] << s);
        for (int j = 1; j < s; ++j)
          if ((poly_a[d] >> (s - 1 - j)) & 1u) value ^= m[k - j] << j;
        m[k] = value;
      }
      for (int k = 0; k < 32; ++k) v[d + 1][k] = m[k] << (31 - k);
    }
    // The matrix-vector product one index byte at a time, bit-reversed (the Owen scramble below
    // works on reversed values, and reversal commutes with XOR): table[dim][byte][value] is the
    // XOR of the reversed columns selected by that byte's bits.
    for (int d = 0; d < 4; ++d)
      for (int byte = 0; byte < 4; ++byte)
        for (uint32_t value = 0; value < 256; ++value) {
          uint32_t x = 0;
          for (int bit = 0; bit < 8; ++bit)
            if ((value >> bit) & 1u) x ^= reverse_bits(v[d][8 * byte + bit]);
          table[d][byte][value] = x;
        }
  }
  uint32_t table[4][4][256];
};
const SobolMatrices kSobol;

// Sobol point `index` in dimension dim, bit-reversed.
uint32_t reversed_sobol(uint32_t index, int dim) {
  const auto& t = kSobol.table[dim];
  return t[0][index & 0xffu] ^ t[1][(index >> 8) & 0xffu] ^ t[2][(index >> 16) & 0xffu] ^ t[3][index >> 24];
}

// Four uint32 lanes (SSE2, x86-64's baseline): next_4d's four dimensions side by side.
struct Lanes {
  __m128i v;
  Lanes(__m128i x) : v(x) {}
  explicit Lanes(uint32_t x) : v(_mm_set1_epi32(int(x))) {}
  Lanes operator+(Lanes o) const { return _mm_add_epi32(v, o.v); }
  Lanes operator^(Lanes o) const { return _mm_xor_si128(v, o.v); }
  Lanes operator&(uint32_t m) const { return _mm_and_si128(v, _mm_set1_epi32(int(m))); }
  Lanes operator|(Lanes o) const { return _mm_or_si128(v, o.v); }
  Lanes operator>>(int n) const { return _mm_srli_epi32(v, n); }
  Lanes operator<<(int n) const { return _mm_slli_epi32(v, n); }
  Lanes operator*(uint32_t c) const {  // low 32 bits of each product (SSE2 has no pmulld)
    const __m128i k = _mm_set1_epi32(int(c));
    const __m128i even = _mm_mul_epu32(v, k), odd = _mm_mul_epu32(_mm_srli_epi64(v, 32), k);
    return _mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(0, 0, 2, 0)),
                              _mm_shuffle_epi32(odd, _MM_SHUFFLE(0, 0, 2, 0)));
  }
};

// reverse_bits and hash_u32 (sampling.h) of each lane.
Lanes reverse_bits(Lanes x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}
Lanes hash_u32(Lanes x) {
  x = x ^ (x >> 16);
  x = x * 0x7feb352du;
  x = x ^ (x >> 15);
  x = x * 0x846ca68bu;
  return x ^ (x >> 16);
}

// Nested uniform (Owen) scramble in base 2 of x given bit-reversed: a hash in which each bit
// depends only on higher bits of x (the Laine-Karras construction); returns it in natural order.
template <typename U>
U owen_scramble_reversed(U reversed_x, U seed) {
  U x = reversed_x + seed;
  x = x ^ (x * 0x6c50b47cu);
  x = x ^ (x * 0xb82f1e52u);
  x = x ^ (x * 0xc7afe638u);
  x = x ^ (x * 0x8d22f6e6u);
  return reverse_bits(x);
}

}  // namespace

glm::vec4 SobolSampler::next_4d() {
  if (random_) {
    const Vec2 a = rng_.next_2d(), b = rng_.next_2d();
    return glm::vec4(a.x, a.y, b.x, b.y);
  }
  const uint32_t group_seed = hash_combine(pixel_seed_, group_++);
  const uint32_t shuffled = owen_scramble_reversed(reverse_bits(index_), group_seed);
  // Dimension d is scrambled with hash_combine(group_seed, d + 1), all four at once.
  const uint32_t combine = 0x9e3779b9U + (group_seed << 6) + (group_seed >> 2);
  const Lanes seeds = hash_u32(Lanes(group_seed) ^ (Lanes(_mm_setr_epi32(1, 2, 3, 4)) + Lanes(combine)));
  const Lanes points(_mm_setr_epi32(int(reversed_sobol(shuffled, 0)), int(reversed_sobol(shuffled, 1)),
                                    int(reversed_sobol(shuffled, 2)), int(reversed_sobol(shuffled, 3))));
  const Lanes scrambled = owen_scramble_reversed(points, seeds);
  glm::vec4 u;
  _mm_storeu_ps(&u[0], _mm_mul_ps(_mm_cvtepi32_ps((scrambled >> 8).v), _mm_set1_ps(0x1p-24f)));
  return u;
}

Vec2 owen_sobol_2d(uint32_t index, uint32_t seed) {
  const uint32_t x = owen_scramble_reversed(reversed_sobol(index, 0), hash_combine(seed, 1u));
  const uint32_t y = owen_scramble_reversed(reversed_sobol(index, 1), hash_combine(seed, 2u));
  return Vec2(float(x >> 8) * 0x1p-24f, float(y >> 8) * 0x1p-24f);
}

Vec2 sample_concentric_disk(const Vec2& u) {
  const Vec2 p = 2.0f * u - Vec2(1.0f);
  if (p.x == 0.0f && p.y == 0.0f) return Vec2(0.0f);
  float r, theta;
  if (std::abs(p.x) > std::abs(p.y)) {
    r = p.x;
    theta = (kPi / 4.0f) * (p.y / p.x);
  } else {
    r = p.y;
    theta = kPi / 2.0f - (kPi / 4.0f) * (p.x / p.y);
  }
  return r * Vec2(std::cos(theta), std::sin(theta));
}

Vec3 sample_cosine_hemisphere(const Vec2& u) {
  const Vec2 d = sample_concentric_disk(u);
  const float z = safe_sqrt(1.0f - d.x * d.x - d.y * d.y);
  return Vec3(d.x, d.y, std::max(z, 1e-7f));
}

Vec3 sample_uniform_cone(const Vec2& u, float one_minus_cos_max) {
  const float one_minus_cos = u.x * one_minus_cos_max;
  const float cos_theta = 1.0f - one_minus_cos;
  const float sin_theta = safe_sqrt(one_minus_cos * (2.0f - one_minus_cos));
  const float phi = kTwoPi * u.y;
  return Vec3(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
}

namespace {
// The Blackman-Harris window at t in [0, 1] (across [-width, width]): 1 at t = 1/2, 0 at the ends.
double blackman_harris(double t) {
  return 0.35875 - 0.48829 * std::cos(2 * M_PI * t) + 0.14128 * std::cos(4 * M_PI * t) -
         0.01168 * std::cos(6 * M_PI * t);
}
constexpr int kWeightTableSize = 257;
}  // namespace

PixelFilter::PixelFilter(float width, int table_size) : width_(std::max(width, 1e-3f)) {
  // Tabulate the window's CDF finely, then invert it at table_size evenly spaced levels.
  const int n = table_size * 8;
  std::vector<double> cdf(n + 1, 0.0);
  for (int i = 0; i < n; ++i) cdf[i + 1] = cdf[i] + blackman_harris((i + 0.5) / n);
  for (double& c : cdf) c /= cdf[n];
  inverse_cdf_.resize(table_size + 1);
  int j = 0;
  for (int i = 0; i <= table_size; ++i) {
    const double level = double(i) / table_size;
    while (j < n && cdf[j + 1] < level) ++j;
    const double span = cdf[j + 1] - cdf[j];
    const double frac = span > 0 ? (level - cdf[j]) / span : 0.0;
    const double t = (j + std::min(std::max(frac, 0.0), 1.0)) / n;
    inverse_cdf_[i] = float((2.0 * t - 1.0) * width_);
  }
  weights_.resize(kWeightTableSize);
  for (int i = 0; i < kWeightTableSize; ++i)
    weights_[i] = float(std::max(blackman_harris(0.5 + 0.5 * i / (kWeightTableSize - 1.0)), 0.0));
  weights_.back() = 0.0f;
  weight_scale_ = float(kWeightTableSize - 1) / width_;
  double integral = 0.0;
  const int steps = 2048;
  for (int k = 0; k <= steps; ++k) {
    const float d = -width_ + 2.0f * width_ * float(k) / float(steps);
    integral += (k == 0 || k == steps ? 0.5 : 1.0) * weight(d);
  }
  weight_integral_ = integral * 2.0 * double(width_) / steps;
}

float PixelFilter::sample_offset(float u) const {
  const float x = u * float(inverse_cdf_.size() - 1);
  const int i = std::min(int(x), int(inverse_cdf_.size()) - 2);
  const float f = x - float(i);
  return inverse_cdf_[i] * (1.0f - f) + inverse_cdf_[i + 1] * f;
}

}  // namespace torrance
