// Voronoi F1's bounded search (src/shader/voronoi_nearest.h) against the search of all 3^D
// cells (voronoi_search.h's f1_all): the same distance, colour and position bit for bit, in 3D
// and 4D, with the float hashes (3.4, 4.x) and the integer ones (5.0+), Randomness 0 to 1, over
// random points, points on and next to cell faces (where bounds and distances tie) and far ones.
#include <gtest/gtest.h>

#include "shader/voronoi_search.h"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

namespace torrance {
namespace {

using namespace shader::voronoi_search;

template <int D>
bool same(const Found<D>& a, const Found<D>& b) {
  return std::memcmp(&a.distance, &b.distance, sizeof(float)) == 0 &&
         std::memcmp(&a.color, &b.color, sizeof(Vec3)) == 0 &&
         std::memcmp(&a.position, &b.position, sizeof(VecN<D>)) == 0;
}

// Random coordinates: most anywhere, some exactly on a face (whole numbers, halves) or one ulp
// off it, some large.
float coordinate(std::mt19937& rng) {
  std::uniform_real_distribution<float> any(-30.0f, 30.0f);
  std::uniform_int_distribution<int> kind(0, 9), whole(-5, 5);
  switch (kind(rng)) {
    case 0: return float(whole(rng));
    case 1: return float(whole(rng)) + 0.5f;
    case 2: return std::nextafter(float(whole(rng)), 100.0f);
    case 3: return std::nextafter(float(whole(rng)), -100.0f);
    case 4: return any(rng) * 1e5f;
    default: return any(rng);
  }
}

template <int D>
int compare(int points, uint32_t seed) {
  std::mt19937 rng(seed);
  const float randomness[] = {0.0f, 0.25f, 1.0f, 0.999f, 0.5f};
  int differ = 0;
  for (int n = 0; n < points; ++n) {
    VecN<D> p;
    for (int k = 0; k < D; ++k) p[k] = coordinate(rng);
    for (float r : randomness)
      for (bool integer : {false, true})
        for (float start : {8.0f, FLT_MAX}) {
          const Params q{0.0f, 1.0f, r, shader::VoronoiMetric::Euclidean, true, start == FLT_MAX, start, integer};
          const Found<D> got = f1<D>(p, q), want = f1_all<D>(p, q);
          if (!same(got, want)) {
            if (++differ <= 5)
              ADD_FAILURE() << D << "D p[0] " << p[0] << " randomness " << r << " integer " << integer << ": distance "
                            << got.distance << " vs " << want.distance;
          }
        }
  }
  return differ;
}

TEST(ShaderVoronoiNearest, TheFullSearchesChoice3D) { EXPECT_EQ(compare<3>(4000, 3), 0); }
TEST(ShaderVoronoiNearest, TheFullSearchesChoice4D) { EXPECT_EQ(compare<4>(1500, 4), 0); }

// Non-finite points (NaN and infinite coordinates): no cell is chosen in either search.
TEST(ShaderVoronoiNearest, NonFinitePoints) {
  const float odd[] = {NAN, INFINITY, -INFINITY};
  for (float v : odd) {
    const Params q{0.0f, 1.0f, 1.0f, shader::VoronoiMetric::Euclidean, true, false, 8.0f, false};
    const VecN<3> p(0.3f, v, 2.0f);
    EXPECT_TRUE(same(f1<3>(p, q), f1_all<3>(p, q))) << v;
  }
}

}  // namespace
}  // namespace torrance
