// Scene: prototypes (object-space meshes in their own BVH) and their instances.
#include "scene/scene_internal.h"

#include "torrance/util/limits.h"

#include <stdexcept>
#include <string>

namespace torrance {

using namespace scene_detail;

uint32_t Scene::add_prototype(const float* positions, size_t num_vertices, const int64_t* triangles,
                              size_t num_triangles, const float* corner_normals, const int64_t* slots,
                              const float* corner_uvs) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a prototype");
  auto prototype = std::make_unique<Prototype>();
  prototype->mesh = make_mesh(positions, num_vertices, triangles, num_triangles, corner_normals, slots, corner_uvs,
                              true);
  if (num_vertices > 0) {
    prototype->lo = prototype->hi = prototype->mesh->positions[0];
    for (const Vec3& p : prototype->mesh->positions) {
      prototype->lo = glm::min(prototype->lo, p);
      prototype->hi = glm::max(prototype->hi, p);
    }
  }
  if (num_triangles > 0) {
    prototype->scene = rtcNewScene(device_of(device_));
    rtcSetSceneFlags(prototype->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(prototype->scene, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry geom = static_cast<RTCGeometry>(new_triangle_geometry(*prototype->mesh));
    rtcAttachGeometryByID(prototype->scene, geom, 0);
    rtcReleaseGeometry(geom);
    check_device("adding a prototype's mesh");
    // Its BVH is built by commit(), on the thread that renders, not on the caller's (Blender's
    // main thread for the viewport); once, whatever happens to its instances later.
    dirty_ = true;
  }
  prototypes_.push_back(std::move(prototype));
  return uint32_t(prototypes_.size() - 1);
}

namespace {
std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}
}  // namespace

// What an instance's matrix may do (issue 15's bounds, for instancing): every entry finite and
// within kMaxCoordinate (1e12) -- the translation is the object's origin, a column of the 3x3
// part the world image of a unit object axis -- and the prototype's vertex bounds, transformed,
// within 1e12 of the origin too, as add_mesh requires of world-space vertices. So hit points and
// their offsets stay valid rays for Embree, whatever the matrix.
void Scene::check_transform(const float* m, uint32_t prototype, const std::string& which) const {
  for (int k = 0; k < 12; ++k)
    if (!std::isfinite(m[k])) throw std::invalid_argument(which + " has a NaN or Inf entry");
  for (int k = 0; k < 12; ++k)
    if (std::abs(m[k]) > kMaxCoordinate)
      throw std::invalid_argument(which + " has an entry of " + number(m[k]) + " (row " + std::to_string(k / 4) +
                                  ", column " + std::to_string(k % 4) + "); entries must lie within 1e12");
  const Prototype& proto = *prototypes_[prototype];
  if (proto.mesh->positions.empty()) return;
  for (int r = 0; r < 3; ++r) {  // the exact world bounds of the object-space box, row by row
    double lo = m[4 * r + 3], hi = lo;
    for (int c = 0; c < 3; ++c) {
      const double a = double(m[4 * r + c]) * proto.lo[c], b = double(m[4 * r + c]) * proto.hi[c];
      lo += std::min(a, b);
      hi += std::max(a, b);
    }
    if (std::max(std::abs(lo), std::abs(hi)) > double(kMaxCoordinate))
      throw std::invalid_argument(which + " places prototype " + std::to_string(prototype) + " beyond 1e12 from " +
                                  "the origin (world " + "xyz"[r] + " from " + number(lo) + " to " + number(hi) + ")");
  }
}

namespace {

}  // namespace

// Sets the instance's matrix, in Embree too, and hides it while the matrix is singular.
void Scene::place_instance(Instance& instance, const float* transform) {
  std::copy_n(transform, 12, instance.transform.begin());
  const bool was_hidden = instance.hidden;
  instance.hidden = singular(instance.transform);
  if (instance.hidden != was_hidden) hidden_instances_ += instance.hidden ? 1 : size_t(-1);
  if (instance.geometry == kNoGeometry) {
    instance.motion.clear();  // a new transform ends its motion blur (nothing to place)
    return;
  }
  RTCGeometry geom = rtcGetGeometry(scene_of(scene_), instance.geometry);
  if (!instance.motion.empty()) {  // a new transform ends its motion blur
    instance.motion.clear();
    rtcSetGeometryTimeStepCount(geom, 1);
  }
  if (!instance.hidden) {
    rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, instance.transform.data());
    rtcCommitGeometry(geom);
  }
  if (instance.hidden != was_hidden) {
    if (instance.hidden)
      rtcDisableGeometry(geom);
    else
      rtcEnableGeometry(geom);
  }
  if (bindings_[instance.binding].num_emissive > 0) emitters_dirty_ = true;
  dirty_ = true;
}

uint32_t Scene::add_instances(uint32_t prototype, const float* transforms, size_t count, const int64_t* materials,
                              size_t table_size, bool per_instance_tables) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add instances");
  if (prototype >= prototypes_.size())
    throw std::invalid_argument("prototype " + std::to_string(prototype) + " does not exist (the scene has " +
                                std::to_string(prototypes_.size()) + " prototypes)");
  if (table_size == 0) throw std::invalid_argument("the material table of instances must not be empty");
  const size_t num_tables = per_instance_tables ? count : (count > 0 ? 1 : 0);
  // Per instance its record, an Embree instance geometry and its share of the top-level BVH
  // (~512 bytes); per table entry the binding's copy and its key (8 bytes).
  require_memory(double(count) * 512.0 + double(num_tables) * double(table_size) * 8.0,
                 std::to_string(count) + " instances" +
                     (per_instance_tables ? " with material tables of " + std::to_string(table_size) + " entries"
                                          : std::string()));
  for (size_t i = 0; i < num_tables * table_size; ++i)
    if (materials[i] < 0 || uint64_t(materials[i]) >= materials_.size())
      throw std::invalid_argument("material table entry " + std::to_string(i) + " is material " +
                                  std::to_string(materials[i]) + " but the scene has " +
                                  std::to_string(materials_.size()) + " materials");
  for (size_t i = 0; i < count; ++i) check_transform(transforms + 12 * i, prototype, "transform " + std::to_string(i));
  if (instances_.size() + count >= kInstanceBit || geometry_owner_.size() + count >= kInstanceBit)
    throw std::invalid_argument("too many instances (2^31 at most)");

  // The distinct tables, each a binding shared by all instances using it.
  std::vector<uint32_t> binding_of(num_tables);
  std::vector<uint32_t> key(1 + table_size);
  key[0] = prototype;
  for (size_t t = 0; t < num_tables; ++t) {
    for (size_t k = 0; k < table_size; ++k) key[1 + k] = uint32_t(materials[t * table_size + k]);
    auto [it, inserted] = binding_ids_.try_emplace(key, uint32_t(bindings_.size()));
    if (inserted) {
      Binding b;
      b.prototype = prototype;
      b.materials.assign(key.begin() + 1, key.end());
      bindings_.push_back(std::move(b));
    }
    binding_of[t] = it->second;
  }

  const Prototype& proto = *prototypes_[prototype];
  const uint32_t first = uint32_t(instances_.size());
  instances_.reserve(instances_.size() + count);
  if (proto.scene) geometry_owner_.reserve(geometry_owner_.size() + count);
  for (size_t i = 0; i < count; ++i) {
    Instance inst;
    inst.binding = binding_of[per_instance_tables ? i : 0];
    std::copy_n(transforms + 12 * i, 12, inst.transform.begin());
    inst.hidden = singular(inst.transform);
    if (proto.scene) {
      RTCGeometry geom = rtcNewGeometry(device_of(device_), RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(geom, proto.scene);
      rtcSetGeometryTimeStepCount(geom, 1);
      if (!inst.hidden) rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, inst.transform.data());
      rtcCommitGeometry(geom);
      inst.geometry = uint32_t(geometry_owner_.size());
      rtcAttachGeometryByID(scene_of(scene_), geom, inst.geometry);
      if (inst.hidden) rtcDisableGeometry(geom);
      rtcReleaseGeometry(geom);
      geometry_owner_.push_back(uint32_t(instances_.size()) | kInstanceBit);
    }
    hidden_instances_ += inst.hidden;
    instances_.push_back(inst);
  }
  check_device("adding instances");
  live_instances_ += count;
  dirty_ = true;
  emitters_dirty_ = true;
  return first;
}

const Scene::Instance& Scene::live_instance(int64_t id, const char* during) const {
  if (id < 0 || uint64_t(id) >= instances_.size() || instances_[size_t(id)].binding == kRemoved)
    throw std::invalid_argument(std::string(during) + ": instance " + std::to_string(id) +
                                (id >= 0 && uint64_t(id) < instances_.size() ? " was removed"
                                                                              : " does not exist"));
  return instances_[size_t(id)];
}

void Scene::set_instance_transforms(const int64_t* ids, const float* transforms, size_t count) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("move instances");
  for (size_t i = 0; i < count; ++i) {
    const Instance& inst = live_instance(ids[i], "set_instance_transforms");
    check_transform(transforms + 12 * i, bindings_[inst.binding].prototype,
                    "transform " + std::to_string(i) + " (instance " + std::to_string(ids[i]) + ")");
  }
  for (size_t i = 0; i < count; ++i) place_instance(instances_[size_t(ids[i])], transforms + 12 * i);
  check_device("moving instances");
}

void Scene::remove_instances(const int64_t* ids, size_t count) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("remove instances");
  for (size_t i = 0; i < count; ++i) live_instance(ids[i], "remove_instances");
  for (size_t i = 0; i < count; ++i) {
    Instance& inst = instances_[size_t(ids[i])];
    if (inst.binding == kRemoved) continue;  // listed twice
    if (inst.geometry != kNoGeometry) {
      rtcDetachGeometry(scene_of(scene_), inst.geometry);
      geometry_owner_[inst.geometry] = kNoOwner;
    }
    if (bindings_[inst.binding].num_emissive > 0) emitters_dirty_ = true;
    hidden_instances_ -= inst.hidden;
    inst.binding = kRemoved;
    inst.emitter_base = -1;
    --live_instances_;
  }
  check_device("removing instances");
  dirty_ = true;
}

size_t Scene::num_material_tables() const { return bindings_.size(); }

}  // namespace torrance
