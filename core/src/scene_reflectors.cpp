// Scene::material_plane and material_sphere: whether a material lies in one plane or makes one
// sphere (the reflectors of mirror_images.h).
#include "scene_internal.h"

#include <algorithm>
#include <limits>

namespace torrance {

namespace {

// Whether a prototype's material table lists `material` (its instances are not examined).
template <typename Bindings>
bool in_a_material_table(const Bindings& bindings, uint32_t material) {
  for (const auto& b : bindings)
    if (std::find(b.materials.begin(), b.materials.end(), material) != b.materials.end()) return true;
  return false;
}

// Calls f(mesh, i) for every triangle i of `material` in the world-space meshes.
template <typename Meshes, typename F>
void for_each_triangle(const Meshes& meshes, uint32_t material, F&& f) {
  for (const auto& mesh : meshes)
    for (size_t i = 0; i < mesh->triangles.size(); ++i)
      if (mesh->material_ids[i] == material) f(*mesh, i);
}

}  // namespace

std::optional<Scene::Plane> Scene::material_plane(uint32_t material) const {
  if (in_a_material_table(bindings_, material)) return std::nullopt;
  // The plane of the largest triangle, then every triangle's corners against it.
  double best_area = 0.0;
  Plane plane;
  float scale = 0.0f;
  for_each_triangle(meshes_, material, [&](const Mesh& mesh, size_t i) {
    const glm::uvec3& t = mesh.triangles[i];
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    for (const Vec3& p : {a, b, c}) scale = std::max(scale, max_component(glm::abs(p)));
    const glm::dvec3 cross = glm::cross(glm::dvec3(b - a), glm::dvec3(c - a));
    const double area = glm::length(cross);
    if (area > best_area) {
      best_area = area;
      plane.point = a;
      plane.normal = Vec3(cross / area);
    }
  });
  if (!(best_area > 0.0) || !is_finite(plane.normal)) return std::nullopt;
  const float tolerance = 1e-5f * std::max(scale, 1.0f);
  bool in_plane = true;
  for_each_triangle(meshes_, material, [&](const Mesh& mesh, size_t i) {
    const glm::uvec3& t = mesh.triangles[i];
    // The triangle's own side (its winding may face either way) for its corner normals.
    const Vec3& a = mesh.positions[t[0]];
    const Vec3 winding = glm::cross(mesh.positions[t[1]] - a, mesh.positions[t[2]] - a);
    const float side = glm::dot(winding, plane.normal) < 0.0f ? -1.0f : 1.0f;
    for (int k = 0; k < 3; ++k) {
      in_plane &= std::abs(glm::dot(mesh.positions[t[k]] - plane.point, plane.normal)) <= tolerance;
      if (!mesh.corner_normals.empty()) {
        const Vec3& n = mesh.corner_normals[3 * i + size_t(k)];
        in_plane &= n == Vec3(0.0f) || glm::dot(n, side * plane.normal) >= 1.0f - 1e-6f;
      }
    }
  });
  if (!in_plane) return std::nullopt;
  return plane;
}

std::optional<Scene::Sphere> Scene::material_sphere(uint32_t material) const {
  if (in_a_material_table(bindings_, material)) return std::nullopt;
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  auto each_vertex = [&](auto&& f) {
    for_each_triangle(meshes_, material, [&](const Mesh& mesh, size_t i) {
      for (int k = 0; k < 3; ++k) f(mesh.positions[mesh.triangles[i][k]]);
    });
  };
  each_vertex([&](const Vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  });
  if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) return std::nullopt;
  const Vec3 extent = hi - lo;
  const float radius = (extent.x + extent.y + extent.z) / 6.0f;
  if (max_component(glm::abs(extent - Vec3(2.0f * radius))) > 0.01f * radius) return std::nullopt;
  const Vec3 center = 0.5f * (lo + hi);
  bool on_sphere = true;
  each_vertex([&](const Vec3& p) { on_sphere &= std::abs(glm::length(p - center) - radius) <= 0.005f * radius; });
  if (!on_sphere || !is_finite(center) || !(radius > 0.0f)) return std::nullopt;
  return Sphere{center, radius};
}

}  // namespace torrance
