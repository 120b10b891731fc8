// The Mapping and Vector Rotate nodes' rotation matrix (shader_vector.h's euler_rows): a zero
// angle skips the library's cosine and sine (cos_sin), which must give the same bits as calling
// them, -0 included (sin(-0) is -0, and the matrix's products keep that sign).
#include "torrance/shader/shader_vector.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

namespace torrance {
namespace {

// Cycles' euler_to_mat3 rows, the library's cosine and sine at every angle.
glm::mat3 reference_rows(const Vec3& e) {
  const float cx = std::cos(e.x), cy = std::cos(e.y), cz = std::cos(e.z);
  const float sx = std::sin(e.x), sy = std::sin(e.y), sz = std::sin(e.z);
  glm::mat3 rows;
  rows[0] = Vec3(cy * cz, sy * sx * cz - cx * sz, sy * cx * cz + sx * sz);
  rows[1] = Vec3(cy * sz, sy * sx * sz + cx * cz, sy * cx * sz - sx * cz);
  rows[2] = Vec3(-sy, cy * sx, cy * cx);
  return rows;
}

bool same_bits(const glm::mat3& a, const glm::mat3& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST(ShaderVector, EulerRowsAreTheLibrarysAtZeroAngles) {
  const float angles[] = {0.0f, -0.0f, 0.3f, -1.2f, 3.14159265f, 1e-30f, -1e-30f};
  for (float x : angles)
    for (float y : angles)
      for (float z : angles) {
        const Vec3 e(x, y, z);
        EXPECT_TRUE(same_bits(shader::euler_rows(e), reference_rows(e))) << x << " " << y << " " << z;
      }
}

TEST(ShaderVector, MappingOfZeroRotationKeepsTheSignOfZero) {
  // Point mapping of (-0, 1, -0) by no rotation: -0 + 0 * 1 + ... as Cycles' products give it.
  const Vec3 v(-0.0f, 1.0f, -0.0f), location(0.0f), scale(1.0f);
  for (const Vec3& rotation : {Vec3(0.0f), Vec3(-0.0f), Vec3(0.0f, -0.0f, 0.0f)}) {
    const Vec3 got = shader::mapping(2, v, location, rotation, scale);
    const glm::mat3 r = reference_rows(rotation);
    const Vec3 want(glm::dot(r[0], v), glm::dot(r[1], v), glm::dot(r[2], v));
    EXPECT_EQ(std::memcmp(&got, &want, sizeof got), 0)
        << got.x << " " << got.y << " " << got.z << " / " << want.x << " " << want.y << " " << want.z;
  }
}

}  // namespace
}  // namespace torrance
