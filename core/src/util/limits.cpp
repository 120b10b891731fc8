#include "torrance/util/limits.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace torrance {
namespace {
std::string gib(double bytes) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g GiB", bytes / double(1ull << 30));
  return buf;
}
}  // namespace

size_t memory_budget() {
  if (const char* env = std::getenv("TORRANCE_MEMORY_BUDGET")) {
    char* end = nullptr;
    const unsigned long long v = std::strtoull(env, &end, 10);
    if (end != env && *end == '\0' && v > 0) return size_t(v);
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page <= 0) return size_t(4) << 30;  // unknown: a modest 4 GiB
  return size_t(pages) * size_t(page) / 2;
}

void require_memory(double bytes, const std::string& what) {
  const size_t budget = memory_budget();
  if (!(bytes <= double(budget)))
    throw std::invalid_argument(what + " needs " + gib(bytes) + ", more than the memory budget of " + gib(double(budget)) +
                                " (half the physical memory; TORRANCE_MEMORY_BUDGET overrides)");
}

void require_position(const Vec3& p, const std::string& what) {
  if (!is_finite(p)) throw std::invalid_argument(what + " contains NaN or Inf");
  if (std::abs(p.x) > kMaxCoordinate || std::abs(p.y) > kMaxCoordinate || std::abs(p.z) > kMaxCoordinate)
    throw std::invalid_argument(what + " lies beyond 1e12 from the origin");
}

Vec3 robust_normalize(const Vec3& v) {
  const float m = std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
  if (!(m > 0.0f) || !std::isfinite(m)) return Vec3(0.0f);
  const Vec3 s = v / m;  // largest component +-1: its length cannot overflow or underflow
  return s / glm::length(s);
}

}  // namespace torrance
