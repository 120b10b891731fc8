// Bounds every request is checked against on the way in (issue 15): the memory one request may
// take, and how far from the origin a coordinate may lie.
#pragma once

#include "torrance/util/math.h"

#include <cstddef>
#include <string>

namespace torrance {

// The most memory one request (a render, a texture, a mesh) may allocate: half the physical
// memory, or TORRANCE_MEMORY_BUDGET bytes when that variable is set (read on every call).
size_t memory_budget();

// Throws std::invalid_argument("<what> needs 12.3 GiB, more than the memory budget of ...") when
// `bytes` exceeds memory_budget(), so a request that cannot fit fails before it allocates.
void require_memory(double bytes, const std::string& what);

// Embree rejects (and Debian's build asserts on) rays whose origin has a coordinate beyond about
// 1.8e18; positions are kept far inside that, so hit points and their offsets stay valid.
inline constexpr float kMaxCoordinate = 1e12f;
// Throws std::invalid_argument("<what> contains NaN or Inf" / "... lies beyond ...").
void require_position(const Vec3& p, const std::string& what);

// v / |v| without overflow or underflow in |v| (finite, non-zero v); zero vector otherwise.
Vec3 robust_normalize(const Vec3& v);

}  // namespace torrance
