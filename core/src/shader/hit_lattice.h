// The few sample points a shader op that traces rays takes at a hit. Ambient Occlusion: a
// Fibonacci lattice over the unit square, shifted by the hit's own random offset (its position's
// and view's bits hashed: a pixel's samples meet different points). Bevel (kind Net): an
// Owen-scrambled Sobol (0, m, 2)-net, the points Cycles' path_branched_rng_2D gives a hit's
// branches (an aligned run of PMJ02 points): Bevel normalises the sum of its few samples, so its
// mean depends on how they are spread, not only on their distribution. Its scramble comes from
// the path's sample shift where the globals carry one (ShaderGlobals::sample_shift), else from
// the hit's hash.
#pragma once

#include "torrance/shader/shader_hash.h"
#include "torrance/shader/shader_program.h"
#include "torrance/util/owen_sobol.h"

#include <cmath>

namespace torrance::shader {

class HitLattice {
 public:
  enum class Kind { Lattice, Net };
  HitLattice(const ShaderGlobals& g, int count, uint32_t salt = 0u, Kind kind = Kind::Lattice)
      : seed_(hash_uint4(float_bits(g.position.x), float_bits(g.position.y), float_bits(g.position.z),
                         (float_bits(g.incoming.x) ^ float_bits(g.incoming.y)) + salt)),
        shift_u_(float(hash_uint2(seed_, 0u) >> 8) * 0x1p-24f),
        shift_v_(float(hash_uint2(seed_, 1u) >> 8) * 0x1p-24f),
        count_(count),
        kind_(kind),
        net_seed_(g.has_sample_shift ? hash_uint2(float_bits(g.sample_shift.x), float_bits(g.sample_shift.y))
                                     : hash_uint2(seed_, 2u)) {}
  // Point k of count, in [0, 1)^2.
  Vec2 operator()(int k) const {
    if (kind_ == Kind::Net) return owen_sobol_2d(uint32_t(k), net_seed_);
    constexpr float kGoldenFraction = 0.618033988749895f;
    const float u = (float(k) + 0.5f) / float(count_) + shift_u_;
    const float v = float(k) * kGoldenFraction + shift_v_;
    return Vec2(u - std::floor(u), v - std::floor(v));
  }
  // A random number of the hit for other uses (the local queries' reservoirs).
  uint32_t seed(uint32_t k) const { return hash_uint2(seed_, k + 3u); }

 private:
  uint32_t seed_;
  float shift_u_, shift_v_;
  int count_;
  Kind kind_;
  uint32_t net_seed_;
};

}  // namespace torrance::shader
