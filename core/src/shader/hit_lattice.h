// The few sample points a shader op that traces rays (Ambient Occlusion, Bevel) takes at a hit:
// a Fibonacci lattice over the unit square, shifted by the path's sample shift where the globals
// carry one (ShaderGlobals::sample_shift: stratified over the pixel's samples, as Cycles'
// path_branched_rng_2D spreads a pixel's branches), else by the hit's own random offset (its
// position's and view's bits hashed: a pixel's samples meet different points).
#pragma once

#include "torrance/shader/shader_hash.h"
#include "torrance/shader/shader_program.h"

#include <cmath>

namespace torrance::shader {

class HitLattice {
 public:
  HitLattice(const ShaderGlobals& g, int count, uint32_t salt = 0u)
      : seed_(hash_uint4(float_bits(g.position.x), float_bits(g.position.y), float_bits(g.position.z),
                         (float_bits(g.incoming.x) ^ float_bits(g.incoming.y)) + salt)),
        shift_u_(g.has_sample_shift ? g.sample_shift.x : float(hash_uint2(seed_, 0u) >> 8) * 0x1p-24f),
        shift_v_(g.has_sample_shift ? g.sample_shift.y : float(hash_uint2(seed_, 1u) >> 8) * 0x1p-24f),
        count_(count) {}
  // Point k of count, in [0, 1)^2.
  Vec2 operator()(int k) const {
    constexpr float kGoldenFraction = 0.618033988749895f;
    const float u = (float(k) + 0.5f) / float(count_) + shift_u_;
    const float v = float(k) * kGoldenFraction + shift_v_;
    return Vec2(u - std::floor(u), v - std::floor(v));
  }
  // A random number of the hit for other uses (the local queries' reservoirs).
  uint32_t seed(uint32_t k) const { return hash_uint2(seed_, k + 2u); }

 private:
  uint32_t seed_;
  float shift_u_, shift_v_;
  int count_;
};

}  // namespace torrance::shader
