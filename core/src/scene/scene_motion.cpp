// Motion blur of world-space meshes (Scene::set_mesh_motion) and of deforming prototypes (their
// object-space vertices, Scene::set_prototype_motion): several time steps of positions and corner
// normals as Embree's multi-segment linear motion triangles (inside the instanced scene for a
// prototype: Embree carries the ray's time through the instance), a hit's corners at the ray's
// time (motion_corners, called by triangle_hit), and instances' transform motion.
#include "scene/scene_motion.h"

#include "scene/ray_queries.h"
#include "scene/scene_internal.h"
#include "torrance/util/limits.h"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace torrance {

using namespace scene_detail;

namespace {
constexpr size_t kMaxMotionSteps = 129;  // Embree's limit (RTC_MAX_TIME_STEP_COUNT)
}

uint32_t Scene::mesh_geometry_id(uint32_t mesh) const {
  const auto it = std::find(geometry_owner_.begin(), geometry_owner_.end(), mesh);
  return it == geometry_owner_.end() ? kNoGeometry : uint32_t(it - geometry_owner_.begin());
}

size_t Scene::mesh_vertex_count(uint32_t mesh) const {
  if (mesh >= meshes_.size()) throw std::invalid_argument("no mesh " + std::to_string(mesh));
  return meshes_[mesh]->positions.size();
}

size_t Scene::mesh_triangle_count(uint32_t mesh) const {
  if (mesh >= meshes_.size()) throw std::invalid_argument("no mesh " + std::to_string(mesh));
  return meshes_[mesh]->triangles.size();
}

size_t Scene::prototype_vertex_count(uint32_t prototype) const {
  if (prototype >= prototypes_.size()) throw std::invalid_argument("no prototype " + std::to_string(prototype));
  return prototypes_[prototype]->mesh->positions.size();
}

size_t Scene::prototype_triangle_count(uint32_t prototype) const {
  if (prototype >= prototypes_.size()) throw std::invalid_argument("no prototype " + std::to_string(prototype));
  return prototypes_[prototype]->mesh->triangles.size();
}

namespace {

// Motion arrays as set_mesh_motion and set_prototype_motion keep them: steps x n positions (one
// vertex of spare capacity for Embree's 16-byte load of the last one) and steps x corners unit
// normals (empty without normals), checked as add_mesh checks its own.
void read_motion(size_t steps, size_t n, size_t corners, const float* positions, const float* corner_normals,
                 std::vector<Vec3>& moved, std::vector<Vec3>& normals) {
  if (steps < 2 || steps > kMaxMotionSteps)
    throw std::invalid_argument("motion needs 2 to 129 time steps, got " + std::to_string(steps));
  moved.reserve(steps * n + 1);
  for (size_t i = 0; i < steps * n; ++i) {
    const Vec3 p(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    if (!is_finite(p))
      throw std::invalid_argument("motion step " + std::to_string(i / n) + ", vertex " + std::to_string(i % n) +
                                  " has a NaN or Inf coordinate");
    require_position(p, "motion step " + std::to_string(i / n) + ", vertex " + std::to_string(i % n));
    moved.push_back(p);
  }
  if (corner_normals) {
    normals.resize(steps * corners);
    for (size_t i = 0; i < steps * corners; ++i) {
      const Vec3 v(corner_normals[3 * i], corner_normals[3 * i + 1], corner_normals[3 * i + 2]);
      if (!is_finite(v)) throw std::invalid_argument("motion normals hold a NaN or Inf");
      const float len = glm::length(v);
      normals[i] = len > 1e-12f ? v / len : Vec3(0.0f);  // as add_mesh's corner normals
    }
  }
}

// Embree's triangle geometry geom moving through `steps` x n positions (multi-segment linear
// motion, Embree reading them where they are), committed.
void share_motion(RTCGeometry geom, uint32_t steps, const std::vector<Vec3>& positions, size_t n) {
  rtcSetGeometryTimeStepCount(geom, steps);
  for (size_t s = 0; s < steps; ++s)
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, unsigned(s), RTC_FORMAT_FLOAT3, positions.data() + s * n,
                               0, sizeof(Vec3), n);
  rtcCommitGeometry(geom);
}

}  // namespace

void Scene::set_mesh_motion(uint32_t mesh_id, size_t steps, const float* positions, const float* corner_normals) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a mesh's motion");
  if (mesh_id >= meshes_.size()) throw std::invalid_argument("set_mesh_motion: no mesh " + std::to_string(mesh_id));
  Mesh& mesh = *meshes_[mesh_id];
  std::vector<Vec3> moved, normals;
  read_motion(steps, mesh.positions.size(), 3 * mesh.triangles.size(), positions, corner_normals, moved, normals);
  const uint32_t geom_id = mesh_geometry_id(mesh_id);
  mesh.motion_positions = std::move(moved);
  mesh.motion_normals = std::move(normals);
  mesh.motion_steps = uint32_t(steps);
  if (geom_id == kNoGeometry) return;  // no triangles: nothing to trace
  share_motion(rtcGetGeometry(scene_of(scene_), geom_id), mesh.motion_steps, mesh.motion_positions, mesh.positions.size());
  check_device("setting a mesh's motion");
  has_motion_ = true;
  dirty_ = true;
  emitters_dirty_ = true;  // its emissive triangles now move (build_mesh_light)
}

void Scene::set_prototype_motion(uint32_t prototype_id, size_t steps, const float* positions,
                                 const float* corner_normals) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a prototype's motion");
  if (prototype_id >= prototypes_.size())
    throw std::invalid_argument("set_prototype_motion: no prototype " + std::to_string(prototype_id));
  Prototype& proto = *prototypes_[prototype_id];
  Mesh& mesh = *proto.mesh;
  std::vector<Vec3> moved, normals;
  read_motion(steps, mesh.positions.size(), 3 * mesh.triangles.size(), positions, corner_normals, moved, normals);
  // Its instances must place every step within bounds, as add_instances checked its frame's.
  const Vec3 lo = proto.lo, hi = proto.hi;
  for (size_t i = 0; i < steps * mesh.positions.size(); ++i) {
    proto.lo = glm::min(proto.lo, moved[i]);
    proto.hi = glm::max(proto.hi, moved[i]);
  }
  try {
    for (const Instance& inst : instances_) {
      if (inst.binding == kRemoved || bindings_[inst.binding].prototype != prototype_id) continue;
      check_transform(inst.transform.data(), prototype_id, "an instance of the moving prototype");
      for (const auto& m : inst.motion) check_transform(m.data(), prototype_id, "an instance of the moving prototype");
    }
  } catch (...) {
    proto.lo = lo;
    proto.hi = hi;
    throw;
  }
  mesh.motion_positions = std::move(moved);
  mesh.motion_normals = std::move(normals);
  mesh.motion_steps = uint32_t(steps);
  if (!proto.scene) return;  // no triangles: nothing to trace
  share_motion(rtcGetGeometry(proto.scene, 0), mesh.motion_steps, mesh.motion_positions, mesh.positions.size());
  // Its BVH is (re)built with the time steps by the next commit, and the instances of it taken
  // into the top-level BVH again with its new bounds.
  if (proto.built)
    for (const Instance& inst : instances_)
      if (inst.binding != kRemoved && inst.geometry != kNoGeometry && bindings_[inst.binding].prototype == prototype_id)
        rtcCommitGeometry(rtcGetGeometry(scene_of(scene_), inst.geometry));
  proto.built = false;
  check_device("setting a prototype's motion");
  has_motion_ = true;
  dirty_ = true;
  emitters_dirty_ = true;  // its instances' emissive triangles now move (build_mesh_light)
}

size_t Scene::set_instance_motion(const int64_t* ids, size_t count, size_t steps, const float* transforms) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set instances' motion");
  if (steps < 2 || steps > kMaxMotionSteps)
    throw std::invalid_argument("motion needs 2 to 129 time steps, got " + std::to_string(steps));
  for (size_t i = 0; i < count; ++i) {
    const Instance& inst = live_instance(ids[i], "set_instance_motion");
    for (size_t s = 0; s < steps; ++s)
      check_transform(transforms + 12 * (s * count + i), bindings_[inst.binding].prototype,
                      "motion step " + std::to_string(s) + " of instance " + std::to_string(ids[i]));
  }
  size_t still = 0;
  for (size_t i = 0; i < count; ++i) {
    Instance& inst = instances_[size_t(ids[i])];
    // A step of zero (or nearly zero) scale, e.g. a particle born or dying during the shutter,
    // is one Embree can not trace: that instance stays where it is.
    bool traceable = true;
    for (size_t s = 0; s < steps && traceable; ++s) {
      std::array<float, 12> step;
      std::copy_n(transforms + 12 * (s * count + i), 12, step.begin());
      traceable = !singular(step);
    }
    if (!traceable) {
      ++still;
      continue;
    }
    inst.motion.resize(steps);
    for (size_t s = 0; s < steps; ++s) std::copy_n(transforms + 12 * (s * count + i), 12, inst.motion[s].begin());
    if (inst.geometry == kNoGeometry || inst.hidden) continue;
    RTCGeometry geom = rtcGetGeometry(scene_of(scene_), inst.geometry);
    rtcSetGeometryTimeStepCount(geom, unsigned(steps));
    for (size_t s = 0; s < steps; ++s)
      rtcSetGeometryTransform(geom, unsigned(s), RTC_FORMAT_FLOAT3X4_ROW_MAJOR, inst.motion[s].data());
    rtcCommitGeometry(geom);
    if (bindings_[inst.binding].num_emissive > 0) emitters_dirty_ = true;
  }
  check_device("setting instances' motion");
  if (count > still) has_motion_ = true;
  dirty_ = true;
  return still;
}

std::array<float, 12> Scene::instance_transform(const Instance& inst) const {
  if (inst.motion.size() < 2) return inst.transform;
  // As Embree's instance motion: the matrices' entries linear between the two steps around it.
  const float t = std::clamp(ray_queries::time(), 0.0f, 1.0f) * float(inst.motion.size() - 1);
  const size_t step = std::min(size_t(t), inst.motion.size() - 2);
  const float f = t - float(step);
  std::array<float, 12> m;
  for (int k = 0; k < 12; ++k) m[k] = (1.0f - f) * inst.motion[step][k] + f * inst.motion[step + 1][k];
  return m;
}

namespace scene_detail {

void motion_corners(const MotionArrays& m, const glm::uvec3& tri, uint32_t prim, Corners& c) {
  const float t = std::clamp(ray_queries::time(), 0.0f, 1.0f) * float(m.steps - 1);
  const size_t step = std::min(size_t(t), size_t(m.steps - 2));
  const float f = t - float(step);
  const Vec3* a = m.positions + step * m.num_vertices;
  const Vec3* b = a + m.num_vertices;
  for (int k = 0; k < 3; ++k) c.p[k] = (1.0f - f) * a[tri[k]] + f * b[tri[k]];
  if (m.corner_normals) {
    const Vec3* na = m.corner_normals + step * m.num_corners + 3 * size_t(prim);
    const Vec3* nb = na + m.num_corners;
    for (int k = 0; k < 3; ++k) c.n[k] = (1.0f - f) * na[k] + f * nb[k];
    c.has_n = true;
  }
}

}  // namespace scene_detail
}  // namespace torrance
