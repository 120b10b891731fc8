// Scene::add_points and the hits on points: Embree's sphere points, shaded as Cycles shades its
// point clouds (kernel/geom/point_intersect.h point_shader_setup: the normal from the centre out
// through the hit, no UVs, no dP/du; back faces are never hit).
#include "points/point_set.h"

#include "scene/scene_internal.h"
#include "torrance/scene/unsampled_emitter.h"
#include "torrance/util/limits.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace torrance {

using namespace scene_detail;

namespace {

// Cycles culls a sphere's back faces (its point intersector keeps only the front hit), so a ray
// that starts inside a point, or on its surface going in, passes through it. Embree's Ng on a
// sphere point is the hit's offset from the centre. Only point geometry runs this.
void cull_back_faces(const RTCFilterFunctionNArguments* args) {
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const float dot = RTCRayN_dir_x(args->ray, n, i) * RTCHitN_Ng_x(args->hit, n, i) +
                      RTCRayN_dir_y(args->ray, n, i) * RTCHitN_Ng_y(args->hit, n, i) +
                      RTCRayN_dir_z(args->ray, n, i) * RTCHitN_Ng_z(args->hit, n, i);
    if (!(dot < 0.0f)) args->valid[i] = 0;
  }
}

bool usable_point(const float* centre, float radius) {
  for (int k = 0; k < 3; ++k)
    if (!std::isfinite(centre[k]) || std::abs(centre[k]) > kMaxCoordinate) return false;
  return std::isfinite(radius) && radius > 0.0f && radius <= kMaxCoordinate;
}

}  // namespace

uint32_t Scene::add_points(const float* centres, const float* radii, size_t num_points, int64_t material,
                           const float* attributes, const int32_t* attribute_ids, size_t num_attributes) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add points");
  if (num_points > UINT32_MAX / 2) throw std::invalid_argument("too many points");
  if (material < 0 || size_t(material) >= materials_.size())
    throw std::invalid_argument("point material " + std::to_string(material) + " does not exist");
  if (num_attributes > 64) throw std::invalid_argument("a point set has at most 64 attributes");
  require_memory(double(num_points) * (sizeof(glm::vec4) + double(num_attributes) * sizeof(Vec3)), "points");
  auto set = std::make_unique<PointSet>();
  set->material = uint32_t(material);
  const MaterialTextures& textures = material_textures_[size_t(material)];
  set->emits = textures.textured_emission() || materials_[size_t(material)].emission != Vec3(0.0f);
  set->attribute_ids.assign(attribute_ids, attribute_ids + num_attributes);
  set->points.reserve(num_points);
  set->attributes.reserve((num_points + 2) * num_attributes);
  for (size_t i = 0; i < num_points; ++i) {
    const float* c = centres + 3 * i;
    if (!usable_point(c, radii[i])) continue;  // skipped, as documented (the add-on reports them)
    set->points.emplace_back(c[0], c[1], c[2], radii[i]);
    for (size_t a = 0; a < num_attributes; ++a) {
      const float* v = attributes + 3 * (a * num_points + i);
      const Vec3 x(v[0], v[1], v[2]);
      set->attributes.push_back(is_finite(x) ? x : Vec3(0.0f));
    }
  }
  set->attributes.resize(set->attributes.size() + 2 * num_attributes, Vec3(0.0f));
  const uint32_t id = uint32_t(point_sets_.size());
  if (!set->points.empty()) {
    // As Embree's tutorials build a geometry: new, buffers, filters, commit, attach.
    RTCGeometry geom = rtcNewGeometry(device_of(device_), RTC_GEOMETRY_TYPE_SPHERE_POINT);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, set->points.data(), 0,
                               sizeof(glm::vec4), set->points.size());
    rtcSetGeometryIntersectFilterFunction(geom, cull_back_faces);
    rtcSetGeometryOccludedFilterFunction(geom, cull_back_faces);
    rtcCommitGeometry(geom);
    const uint32_t geom_id = uint32_t(geometry_owner_.size());
    rtcAttachGeometryByID(scene_of(scene_), geom, geom_id);
    rtcReleaseGeometry(geom);
    check_device("committing points");
    geometry_owner_.push_back(id | kPointsBit);
    dirty_ = true;
  }
  point_sets_.push_back(std::move(set));
  return id;
}

size_t Scene::num_points() const {
  size_t n = 0;
  for (const auto& s : point_sets_) n += s->points.size();
  return n;
}

void Scene::point_hit(uint32_t set_index, uint32_t prim, const Vec3& origin, const Vec3& dir, float t,
                      SurfaceHit& hit) const {
  const PointSet& set = *point_sets_[set_index];
  const glm::vec4& point = set.points[prim];
  const Vec3 centre(point);
  hit = SurfaceHit{};
  hit.t = t;
  hit.on_point = true;
  hit.object_settings = set.settings;
  hit.material = set.material;
  hit.emitter = set.emits ? kUnsampledEmitter : -1;
  hit.prim = prim;
  // Cycles' normal: from the centre out through the hit (the ray's reverse should they meet).
  const Vec3 out = origin + t * dir - centre;
  const float len = glm::length(out);
  const Vec3 n = len > 0.0f && std::isfinite(len) ? out / len : -glm::normalize(dir);
  hit.geometric_normal = n;
  hit.shading_normal = n;
  hit.position = centre + point.w * n;  // on the sphere, more accurate than origin + t * dir
  hit.primitive_info = point;           // Point Info's Position and Radius
  const size_t layers = set.attribute_ids.size();
  if (layers > 0) {
    hit.corner_attributes = &set.attributes[size_t(prim) * layers];
    hit.attribute_ids = set.attribute_ids.data();
    hit.num_attributes = int(layers);
    hit.corner_weights = Vec3(1.0f, 0.0f, 0.0f);  // the point's own row (rows 1 and 2 weigh 0)
  }
}

}  // namespace torrance
