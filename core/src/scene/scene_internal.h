// Scene's private parts, shared by its sources (scene.cpp: device, materials, meshes, BVH,
// tracing; scene_instances.cpp: prototypes and instances; scene_emitters.cpp: the emissive-triangle
// light): the stored meshes, prototypes, instances and the geometry of placing them.
#pragma once

#include "torrance/scene/scene.h"

#include "hair/curve_set.h"
#include "points/point_set.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace torrance {

struct Scene::Mesh {
  std::vector<Vec3> positions;
  std::vector<glm::uvec3> triangles;
  std::vector<Vec3> corner_normals;  // empty => flat
  std::vector<uint32_t> material_ids;
  std::vector<Vec2> corner_uvs;  // empty => no UVs
  // Per-corner attributes the shader programs read (Attribute op): corner (3 * triangle + k)'s
  // layer a at (3 * triangle + k) * attribute_ids.size() + a; attribute_ids names each layer.
  std::vector<Vec3> corner_attributes;
  std::vector<int32_t> attribute_ids;
  std::vector<int32_t> emitter_index;  // per triangle: index in the mesh light, or -1
  ObjectSettings settings;             // of a mesh from add_mesh (scene/object_settings.h)
  // Motion blur (Scene::set_mesh_motion; a prototype's, object-space: set_prototype_motion):
  // motion_steps >= 2 positions per vertex, step s's at [s * positions.size(), ...) (one vertex
  // of spare capacity for Embree), evenly over the shutter's time [0, 1], and the corner normals
  // the same way (empty: none); 0: static.
  uint32_t motion_steps = 0;
  std::vector<Vec3> motion_positions;
  std::vector<Vec3> motion_normals;
};

namespace scene_detail {
constexpr uint32_t kInstanceBit = 0x80000000u;
constexpr uint32_t kCurvesBit = 0x40000000u;  // geometry_owner_: a curve set's index | kCurvesBit
constexpr uint32_t kPointsBit = 0x20000000u;  // geometry_owner_: a point set's index | kPointsBit
constexpr uint32_t kNoOwner = 0xFFFFFFFFu;     // a detached geometry id
constexpr uint32_t kRemoved = 0xFFFFFFFFu;     // Instance::binding once removed
constexpr uint32_t kNoGeometry = 0xFFFFFFFFu;  // Instance::geometry of an empty prototype's instance
}  // namespace scene_detail

// An object-space mesh (material_ids hold material slots) in its own BVH, built once.
struct Scene::Prototype {
  std::unique_ptr<Mesh> mesh;
  RTCScene scene = nullptr;  // nullptr when the mesh has no triangles
  bool built = false;        // its BVH, built by the first commit() after add_prototype
  Vec3 lo{0.0f}, hi{0.0f};   // bounds of its vertices (both 0 without vertices), for transforms
  Prototype() = default;
  Prototype(const Prototype&) = delete;
  Prototype& operator=(const Prototype&) = delete;
  ~Prototype() {
    if (scene) rtcReleaseScene(scene);
  }
};

// A prototype with one slot -> material table; instances share it (16 bytes per instance).
struct Scene::Binding {
  uint32_t prototype = 0;
  std::vector<uint32_t> materials;    // never empty
  std::vector<int32_t> emitter_rank;  // per prototype triangle: rank among the emissive ones, or -1
  uint32_t num_emissive = 0;          // (both set by build_mesh_light)
  uint32_t material(uint32_t slot) const { return materials[std::min<size_t>(slot, materials.size() - 1)]; }
};

struct Scene::Instance {
  std::array<float, 12> transform;  // row-major 3x4, object to world
  uint32_t binding = scene_detail::kRemoved;
  uint32_t geometry = scene_detail::kNoGeometry;  // Embree geometry id in the top-level scene
  int32_t emitter_base = -1;        // mesh-light index of its first emissive triangle, or -1
  bool hidden = false;              // singular transform: disabled in Embree
  ObjectSettings settings;          // scene/object_settings.h
  // Motion blur (Scene::set_instance_motion): its transforms at time steps evenly over the
  // shutter (empty: it stays at `transform`).
  std::vector<std::array<float, 12>> motion;
};

namespace scene_detail {
// The corners of a hit triangle in world space; a mirroring instance's corners 1 and 2 are
// swapped (and the barycentrics with them) exactly as the flattening export does, so that the
// geometric normal keeps its side and everything derived from it matches a world-space copy.
struct Corners {
  Vec3 p[3];
  Vec3 n[3];
  Vec2 uv[3];
  bool has_n = false, has_uv = false;
};

inline double determinant3(const std::array<float, 12>& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], i = m[10];
  return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
}

inline Vec3 transform_point(const std::array<float, 12>& m, const Vec3& p) {
  const double x = p.x, y = p.y, z = p.z;
  return Vec3(float(m[0] * x + m[1] * y + m[2] * z + m[3]), float(m[4] * x + m[5] * y + m[6] * z + m[7]),
              float(m[8] * x + m[9] * y + m[10] * z + m[11]));
}

// Rows of the inverse transpose of the 3x3 part, for normals.
inline std::array<double, 9> normal_matrix(const std::array<float, 12>& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], i = m[10];
  const double inv_det = 1.0 / determinant3(m);
  // inverse(M)^T = cofactor(M) / det(M)
  return {(e * i - f * h) * inv_det, (f * g - d * i) * inv_det, (d * h - e * g) * inv_det,
          (c * h - b * i) * inv_det, (a * i - c * g) * inv_det, (b * g - a * h) * inv_det,
          (b * f - c * e) * inv_det, (c * d - a * f) * inv_det, (a * e - b * d) * inv_det};
}

inline Vec3 transform_normal(const std::array<double, 9>& n, const Vec3& v) {
  const double x = v.x, y = v.y, z = v.z;
  const double rx = n[0] * x + n[1] * y + n[2] * z, ry = n[3] * x + n[4] * y + n[5] * z,
               rz = n[6] * x + n[7] * y + n[8] * z;
  const Vec3 r{float(rx), float(ry), float(rz)};
  const float len = glm::length(r);
  if (len > 1e-12f && std::isfinite(len)) return r / len;
  // M^-T of a large scale (entries up to the 1e12 check_transform allows) shrinks normals below
  // float's reach before they are normalized: normalize in double instead.
  const double dlen = std::sqrt(rx * rx + ry * ry + rz * rz);
  return dlen > 0.0 && std::isfinite(dlen) ? Vec3(float(rx / dlen), float(ry / dlen), float(rz / dlen)) : Vec3(0.0f);
}

// Embree traces an instance in object space: a world ray's origin o becomes M^-1 (o - t), which
// Embree rejects (Debian's build asserts, aborting Blender) beyond about 1.8e18. With o and t
// within kMaxCoordinate (1e12), an inverse entry up to 1e5 keeps it within 3 * 1e5 * 2e12 = 6e17.
inline constexpr double kMaxInverseEntry = 1e5;

// Zero scale in some direction (a common way of hiding instances), or so nearly zero (below 1e-5
// of the prototype in some direction) that Embree could not trace it: nothing to trace.
inline bool singular(const std::array<float, 12>& m) {
  const double det = determinant3(m);
  if (!(std::abs(det) > 1e-30) || !std::isfinite(1.0 / det)) return true;
  for (const double entry : normal_matrix(m))  // the inverse's entries, transposed
    if (!(std::abs(entry) <= kMaxInverseEntry)) return true;
  return false;
}
}  // namespace scene_detail

namespace scene_detail {
inline RTCDevice device_of(void* d) { return static_cast<RTCDevice>(d); }
inline RTCScene scene_of(void* s) { return static_cast<RTCScene>(s); }

// A triangle of a world-space mesh as Corners.
inline Corners mesh_corners(const std::vector<Vec3>& positions, const glm::uvec3& tri, const Vec3* normals,
                            const Vec2* uvs) {
  Corners c;
  for (int k = 0; k < 3; ++k) {
    c.p[k] = positions[tri[k]];
    if (normals) c.n[k] = normals[k];
    if (uvs) c.uv[k] = uvs[k];
  }
  c.has_n = normals != nullptr;
  c.has_uv = uvs != nullptr;
  return c;
}

// A prototype triangle's object-space corners c placed by an instance's matrix: what the
// flattening export would have added as a world-space mesh (positions by M, normals by M^-T,
// corners 1 and 2 swapped when M mirrors). Returns whether they were swapped.
inline bool place_corners(const std::array<float, 12>& m, Corners& c) {
  for (int k = 0; k < 3; ++k) c.p[k] = transform_point(m, c.p[k]);
  if (c.has_n) {
    const std::array<double, 9> nm = normal_matrix(m);
    for (int k = 0; k < 3; ++k) c.n[k] = transform_normal(nm, c.n[k]);
  }
  const bool mirrored = determinant3(m) < 0.0;
  if (mirrored) {
    std::swap(c.p[1], c.p[2]);
    std::swap(c.n[1], c.n[2]);
    std::swap(c.uv[1], c.uv[2]);
  }
  return mirrored;
}

// A still prototype triangle placed by an instance's matrix (place_corners).
inline bool instance_corners(const std::vector<Vec3>& positions, const glm::uvec3& tri, const Vec3* normals,
                             const Vec2* uvs, const std::array<float, 12>& m, Corners& c) {
  c = mesh_corners(positions, tri, normals, uvs);
  return place_corners(m, c);
}
}  // namespace scene_detail

}  // namespace torrance

namespace torrance {

// The objects' own BVHs that the local queries trace (scene_local.cpp): one scene per world-space
// mesh and per prototype, each holding only that mesh (sharing its arrays), built by commit() when
// some shader program traces local rays.
struct Scene::LocalScenes {
  std::vector<RTCScene> meshes;      // per world-space mesh (nullptr: no triangles)
  std::vector<RTCScene> prototypes;  // per prototype, in its object space
  LocalScenes() = default;
  LocalScenes(const LocalScenes&) = delete;
  LocalScenes& operator=(const LocalScenes&) = delete;
  ~LocalScenes() {
    for (RTCScene s : meshes)
      if (s) rtcReleaseScene(s);
    for (RTCScene s : prototypes)
      if (s) rtcReleaseScene(s);
  }
};

}  // namespace torrance
