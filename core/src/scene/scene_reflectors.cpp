// Scene::material_planes, material_sphere and material_bounds (the last: light tracing's targets,
// caustics.h). The first two: whether a material makes a few planes, one nearly
// flat sheet or one sphere (the reflectors of mirror_images.h).
#include "scene/scene_internal.h"

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

namespace {

// A triangle of a reflector candidate: corners, unit normal (as it winds), area, corner normals.
struct Face {
  Vec3 a, b, c;
  Vec3 normal;
  double area;
  const Vec3* corner_normals;  // three, or null (flat)
};

// The sphere about the box lo..hi.
void bounding_sphere(const Vec3& lo, const Vec3& hi, Scene::Plane& plane) {
  plane.center = 0.5f * (lo + hi);
  plane.radius = 0.5f * glm::length(hi - lo);
}

// Up to Scene::kMaxPlanes exact planes, the largest faces first (their normals are the most
// precise); empty if the faces need more or a corner normal leaves its plane.
std::vector<Scene::Plane> exact_planes(const std::vector<Face>& faces, float tolerance) {
  std::vector<Scene::Plane> planes;
  std::vector<Vec3> lo, hi;
  for (const Face& f : faces) {
    size_t j = 0;
    for (; j < planes.size(); ++j) {
      const Scene::Plane& q = planes[j];
      if (std::abs(glm::dot(f.normal, q.normal)) >= 1.0f - 1e-6f &&
          std::abs(glm::dot(f.a - q.point, q.normal)) <= tolerance &&
          std::abs(glm::dot(f.b - q.point, q.normal)) <= tolerance &&
          std::abs(glm::dot(f.c - q.point, q.normal)) <= tolerance)
        break;
    }
    if (j == planes.size()) {
      if (planes.size() == Scene::kMaxPlanes) return {};
      Scene::Plane plane;
      plane.point = f.a;
      plane.normal = f.normal;
      planes.push_back(plane);
      lo.push_back(f.a);
      hi.push_back(f.a);
    }
    // The face's own side (its winding may face either way) for its corner normals.
    const Vec3 n = glm::dot(f.normal, planes[j].normal) < 0.0f ? -planes[j].normal : planes[j].normal;
    for (int k = 0; k < 3; ++k) {
      if (f.corner_normals && f.corner_normals[k] != Vec3(0.0f) && glm::dot(f.corner_normals[k], n) < 1.0f - 1e-6f)
        return {};
      const Vec3& p = k == 0 ? f.a : k == 1 ? f.b : f.c;
      lo[j] = glm::min(lo[j], p);
      hi[j] = glm::max(hi[j], p);
    }
  }
  for (size_t j = 0; j < planes.size(); ++j) bounding_sphere(lo[j], hi[j], planes[j]);
  return planes;
}

// Whether the faces' normals fall into at most Scene::kMaxPlanes directions (either way) when
// normals within ~2.6 degrees count as one: a necessary condition for exact_planes (its faces of
// one plane agree within ~0.1 degree), checked in one pass that stops at the first direction too
// many -- a curved sheet of many faces then skips exact_planes' sort by area.
bool few_directions(const std::vector<Face>& faces) {
  std::vector<Vec3> directions;
  for (const Face& f : faces) {
    bool known = false;
    for (const Vec3& d : directions)
      if (std::abs(glm::dot(f.normal, d)) >= 1.0f - 1e-3f) {
        known = true;
        break;
      }
    if (known) continue;
    if (directions.size() == Scene::kMaxPlanes) return false;
    directions.push_back(f.normal);
  }
  return true;
}

// One nearly flat sheet: every face normal (turned to agree with `up`, the largest face's) and
// corner normal within Scene::kMaxPlaneTilt of the area-weighted mean normal; empty otherwise.
std::vector<Scene::Plane> one_sheet(const std::vector<Face>& faces, const Vec3& up) {
  auto agreeing = [&](const Face& f) { return glm::dot(f.normal, up) < 0.0f ? -1.0f : 1.0f; };
  glm::dvec3 sum_normal(0.0), sum_centroid(0.0);
  double sum_area = 0.0;
  Vec3 lo = faces.front().a, hi = lo;
  for (const Face& f : faces) {
    sum_normal += f.area * glm::dvec3(agreeing(f) * f.normal);
    sum_centroid += f.area * glm::dvec3(f.a + f.b + f.c) / 3.0;
    sum_area += f.area;
    for (const Vec3& p : {f.a, f.b, f.c}) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  }
  Scene::Plane sheet;
  sheet.normal = Vec3(glm::normalize(sum_normal));
  sheet.point = Vec3(sum_centroid / sum_area);
  if (!is_finite(sheet.normal) || !is_finite(sheet.point)) return {};
  float min_cos = 1.0f;
  for (const Face& f : faces) {
    const float side = agreeing(f);
    min_cos = std::min(min_cos, side * glm::dot(f.normal, sheet.normal));
    if (f.corner_normals)
      for (int k = 0; k < 3; ++k)
        if (f.corner_normals[k] != Vec3(0.0f))
          min_cos = std::min(min_cos, side * glm::dot(glm::normalize(f.corner_normals[k]), sheet.normal));
  }
  if (!(min_cos >= std::cos(Scene::kMaxPlaneTilt))) return {};
  sheet.tilt = std::acos(std::min(min_cos, 1.0f));
  for (const Face& f : faces)
    for (const Vec3& p : {f.a, f.b, f.c})
      sheet.depth = std::max(sheet.depth, std::abs(glm::dot(p - sheet.point, sheet.normal)));
  bounding_sphere(lo, hi, sheet);
  return {sheet};
}

}  // namespace

std::vector<Scene::Plane> Scene::material_planes(uint32_t material) const {
  if (in_a_material_table(bindings_, material)) return {};
  std::vector<Face> faces;
  size_t triangles = 0;  // of this material: one pass over the ids spares the faces' regrowth
  for_each_triangle(meshes_, material, [&](const Mesh&, size_t) { ++triangles; });
  faces.reserve(triangles);
  float scale = 0.0f;
  for_each_triangle(meshes_, material, [&](const Mesh& mesh, size_t i) {
    const glm::uvec3& t = mesh.triangles[i];
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    for (const Vec3& p : {a, b, c}) scale = std::max(scale, max_component(glm::abs(p)));
    const glm::dvec3 cross = glm::cross(glm::dvec3(b - a), glm::dvec3(c - a));
    const double area = glm::length(cross);
    if (!(area > 0.0)) return;  // a degenerate face is never hit
    faces.push_back(Face{a, b, c, Vec3(cross / area), area,
                         mesh.corner_normals.empty() ? nullptr : &mesh.corner_normals[3 * i]});
  });
  if (faces.empty()) return {};
  auto larger = [](const Face& x, const Face& y) { return x.area > y.area; };
  if (!few_directions(faces)) {
    const Vec3 up = std::min_element(faces.begin(), faces.end(), larger)->normal;  // the first largest face's
    return one_sheet(faces, up);
  }
  std::stable_sort(faces.begin(), faces.end(), larger);
  std::vector<Plane> planes = exact_planes(faces, 1e-5f * std::max(scale, 1.0f));
  return planes.empty() ? one_sheet(faces, faces.front().normal) : planes;
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

std::optional<Scene::Sphere> Scene::material_bounds(uint32_t material) const {
  if (in_a_material_table(bindings_, material)) return std::nullopt;
  Vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for_each_triangle(meshes_, material, [&](const Mesh& mesh, size_t i) {
    for (int k = 0; k < 3; ++k) {
      lo = glm::min(lo, mesh.positions[mesh.triangles[i][k]]);
      hi = glm::max(hi, mesh.positions[mesh.triangles[i][k]]);
    }
  });
  if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z) || !is_finite(lo) || !is_finite(hi)) return std::nullopt;
  const Vec3 center = 0.5f * (lo + hi);
  float radius2 = 0.0f;
  for_each_triangle(meshes_, material, [&](const Mesh& mesh, size_t i) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 d = mesh.positions[mesh.triangles[i][k]] - center;
      radius2 = std::max(radius2, glm::dot(d, d));
    }
  });
  return Sphere{center, std::sqrt(radius2) * 1.001f + 1e-6f};
}

}  // namespace torrance
