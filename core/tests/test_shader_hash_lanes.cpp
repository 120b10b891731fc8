// shader_hash_lanes.h: the hashes over arrays (which Voronoi and Perlin noise use for speed)
// give bit for bit what shader_hash.h's scalar hashes give, the float mapping included at the
// values where a conversion rounds.
#include "torrance/shader/shader_hash.h"
#include "torrance/shader/shader_hash_lanes.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

namespace torrance {
namespace {

using namespace shader;

uint32_t bits(float f) {
  uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return u;
}

TEST(ShaderHashLanes, UnitFloatIsTheCorrectlyRoundedConversion) {
  // Around each power of two the conversion starts rounding (ties to even), and at the top it
  // rounds up to 2^32 (the mapping's 1).
  std::vector<uint32_t> values = {0u, 1u, 0xffffu, 0x10000u, 0xffffffffu, 0xffffff7fu, 0xffffff80u, 0xffffff81u};
  for (int e = 24; e < 32; ++e)
    for (uint32_t d = 0; d < 600; ++d) {
      values.push_back((1u << e) + d);
      values.push_back((1u << e) - d);
    }
  std::mt19937 rng(5);
  for (int i = 0; i < 100000; ++i) values.push_back(uint32_t(rng()));
  for (uint32_t n : values) ASSERT_EQ(bits(lanes::to_unit_float(n)), bits(uint_to_float_incl(n))) << n;
}

TEST(ShaderHashLanes, EveryLaneIsTheScalarHash) {
  constexpr int N = 64;
  uint32_t x[N], y[N], z[N], w[N];
  std::mt19937 rng(9);
  for (int i = 0; i < N; ++i) x[i] = rng(), y[i] = rng(), z[i] = rng(), w[i] = rng();
  x[0] = y[0] = z[0] = w[0] = 0u;
  x[1] = bits(-0.0f), y[1] = bits(1.0f), z[1] = bits(-1.0f), w[1] = bits(2.0f);
  float out[N], out2[N];
  lanes::hash1<N>(x, out);
  for (int i = 0; i < N; ++i) EXPECT_EQ(bits(out[i]), bits(hash_uint_to_float(x[i])));
  lanes::hash2<N>(x, y, out);
  for (int i = 0; i < N; ++i) EXPECT_EQ(bits(out[i]), bits(hash_uint2_to_float(x[i], y[i])));
  lanes::hash3<N>(x, y, z, out);
  for (int i = 0; i < N; ++i) EXPECT_EQ(bits(out[i]), bits(hash_uint3_to_float(x[i], y[i], z[i])));
  lanes::hash4<N>(x, y, z, w, out);
  for (int i = 0; i < N; ++i) EXPECT_EQ(bits(out[i]), bits(hash_uint4_to_float(x[i], y[i], z[i], w[i])));
  lanes::hash2_with<N>(x, 77u, out);
  for (int i = 0; i < N; ++i) EXPECT_EQ(bits(out[i]), bits(hash_uint2_to_float(x[i], 77u)));
  lanes::hash3_with<N>(x, y, 77u, out);
  for (int i = 0; i < N; ++i) EXPECT_EQ(bits(out[i]), bits(hash_uint3_to_float(x[i], y[i], 77u)));
  lanes::hash4_with_two<N>(x, y, z, bits(1.0f), bits(2.0f), out, out2);
  for (int i = 0; i < N; ++i) {
    EXPECT_EQ(bits(out[i]), bits(hash_uint4_to_float(x[i], y[i], z[i], bits(1.0f))));
    EXPECT_EQ(bits(out2[i]), bits(hash_uint4_to_float(x[i], y[i], z[i], bits(2.0f))));
  }
}

}  // namespace
}  // namespace torrance
