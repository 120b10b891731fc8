// Scene::add_curves and the hits on hair strands: Embree's round or flat Catmull-Rom curves,
// shaded as Cycles 3.4's curve_shader_setup (kernel/geom/curve_intersect.h) shades its thick
// curves and rounded ribbons.
#include "hair/curve_set.h"

#include "scene/scene_internal.h"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace torrance {

using namespace scene_detail;

namespace {

// The leaving ray of a hit on a strand must not meet that strand where it left it (Cycles skips
// the hit's own segment). Round curves: a hit where the ray leaves a tube (along its outward
// normal) is dropped, so a ray that enters the strand at the hit (transmission) passes through
// it; ribbons, which face every ray: a hit closer than twice the strand's radius is dropped
// (Cycles' own ribbon intersector drops those too). Only curve geometry runs this.
void skip_own_strand(const RTCFilterFunctionNArguments* args) {
  const auto* set = static_cast<const Scene::CurveSet*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const Vec3 dir(RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i), RTCRayN_dir_z(args->ray, n, i));
    bool drop;
    if (set->shape == CurveShape::Round) {
      const Vec3 ng(RTCHitN_Ng_x(args->hit, n, i), RTCHitN_Ng_y(args->hit, n, i), RTCHitN_Ng_z(args->hit, n, i));
      drop = glm::dot(dir, ng) > 0.0f;
    } else {
      const unsigned prim = RTCHitN_primID(args->hit, n, i);
      const float u = RTCHitN_u(args->hit, n, i);
      const float radius = curve_basis::eval(&set->keys[set->segment_key[prim]], u).w;
      drop = RTCRayN_tfar(args->ray, n, i) * glm::length(dir) < 2.0f * radius;
    }
    if (drop) args->valid[i] = 0;
  }
}

}  // namespace

uint32_t Scene::add_curves(const float* keys, const float* radii, size_t num_keys, const int64_t* curve_first,
                           size_t num_curves, const int64_t* materials, CurveShape shape, const float* random,
                           const float* normals) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add curves");
  if (num_keys > UINT32_MAX / 2 || num_curves > UINT32_MAX / 2) throw std::invalid_argument("too many curve keys");
  if (curve_first[0] != 0 || curve_first[num_curves] != int64_t(num_keys))
    throw std::invalid_argument("curve offsets must run from 0 to the number of keys");
  for (size_t i = 0; i < 3 * num_keys; ++i)
    if (!std::isfinite(keys[i]) || std::abs(keys[i]) > 1e12f)
      throw std::invalid_argument("curve keys must be finite and within 1e12 of the origin");
  for (size_t i = 0; i < num_keys; ++i)
    if (!std::isfinite(radii[i]) || radii[i] < 0.0f) throw std::invalid_argument("curve radii must be finite, >= 0");
  if (random)
    for (size_t c = 0; c < num_curves; ++c)
      if (!std::isfinite(random[c])) throw std::invalid_argument("curve random values must be finite");
  if (normals)
    for (size_t i = 0; i < 3 * num_keys; ++i)
      if (!std::isfinite(normals[i])) throw std::invalid_argument("curve normals must be finite");
  auto set = std::make_unique<CurveSet>();
  set->shape = shape;
  set->keys.reserve(num_keys + 2 * num_curves);
  for (size_t c = 0; c < num_curves; ++c) {
    const int64_t first = curve_first[c], end = curve_first[c + 1];
    if (end < first) throw std::invalid_argument("curve offsets must ascend");
    uint32_t material = 0;
    if (materials) {
      if (materials[c] < 0 || size_t(materials[c]) >= materials_.size())
        throw std::invalid_argument("curve material " + std::to_string(materials[c]) + " does not exist");
      material = uint32_t(materials[c]);
    }
    if (end - first < 2) continue;
    auto key = [&](int64_t k) { return glm::vec4(keys[3 * k], keys[3 * k + 1], keys[3 * k + 2], radii[k]); };
    const uint32_t base = uint32_t(set->keys.size());
    set->keys.push_back(key(first));
    for (int64_t k = first; k < end; ++k) set->keys.push_back(key(k));
    set->keys.push_back(key(end - 1));
    if (normals) {  // aligned with keys, the end keys' twice
      auto normal = [&](int64_t k) { return Vec3(normals[3 * k], normals[3 * k + 1], normals[3 * k + 2]); };
      set->key_normal.push_back(normal(first));
      for (int64_t k = first; k < end; ++k) set->key_normal.push_back(normal(k));
      set->key_normal.push_back(normal(end - 1));
    }
    // Intercept and Length as Cycles' curve attributes: the distance along the key polyline.
    double length = 0.0;
    std::vector<double> along{0.0};
    for (int64_t k = first + 1; k < end; ++k) {
      length += double(glm::length(Vec3(key(k)) - Vec3(key(k - 1))));
      along.push_back(length);
    }
    set->key_intercept.push_back(0.0f);
    for (double a : along) set->key_intercept.push_back(length > 0.0 ? float(a / length) : 0.0f);
    set->key_intercept.push_back(set->key_intercept.back());
    for (int64_t s = 0; s + 1 < end - first; ++s) {
      set->segment_key.push_back(base + uint32_t(s));
      set->segment_material.push_back(material);
      set->segment_length.push_back(float(length));
      set->segment_random.push_back(random ? random[c] : 0.0f);
    }
  }
  if (!materials && materials_.empty() && !set->segment_key.empty())
    throw std::invalid_argument("add a material before adding curves");
  const uint32_t id = uint32_t(curve_sets_.size());
  if (!set->segment_key.empty()) {
    RTCGeometry geom = rtcNewGeometry(device_of(device_), shape == CurveShape::Round
                                                              ? RTC_GEOMETRY_TYPE_ROUND_CATMULL_ROM_CURVE
                                                              : RTC_GEOMETRY_TYPE_FLAT_CATMULL_ROM_CURVE);
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, set->keys.data(), 0,
                               sizeof(glm::vec4), set->keys.size());
    rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, set->segment_key.data(), 0,
                               sizeof(uint32_t), set->segment_key.size());
    rtcSetGeometryUserData(geom, set.get());
    rtcSetGeometryIntersectFilterFunction(geom, skip_own_strand);
    rtcSetGeometryOccludedFilterFunction(geom, skip_own_strand);
    rtcCommitGeometry(geom);
    const uint32_t geom_id = uint32_t(geometry_owner_.size());
    rtcAttachGeometryByID(scene_of(scene_), geom, geom_id);
    rtcReleaseGeometry(geom);
    check_device("committing curves");
    geometry_owner_.push_back(id | kCurvesBit);
    dirty_ = true;
  }
  curve_sets_.push_back(std::move(set));
  return id;
}

size_t Scene::num_curve_segments() const {
  size_t n = 0;
  for (const auto& s : curve_sets_) n += s->segment_key.size();
  return n;
}

void Scene::curve_hit(uint32_t set_index, uint32_t prim, float u, const Vec3& origin, const Vec3& dir, float t,
                      SurfaceHit& hit) const {
  const CurveSet& set = *curve_sets_[set_index];
  const glm::vec4* c = &set.keys[set.segment_key[prim]];
  const float embree_v = hit.uv.y;  // surface_hit passes Embree's v in
  hit = SurfaceHit{};
  hit.t = t;
  hit.on_curve = true;
  hit.object_settings = set.settings;
  hit.material = set.segment_material[prim];
  hit.position = origin + t * dir;
  const glm::vec4 centre = curve_basis::eval(c, u);
  Vec3 tangent(curve_basis::derivative(c, u));
  if (!(glm::length(tangent) > 0.0f)) tangent = Vec3(c[2] - c[1]);  // a zero-length segment
  const Vec3 view = glm::length(dir) > 0.0f ? -glm::normalize(dir) : Vec3(0.0f, 0.0f, 1.0f);
  // A tangent along the view (or none): any direction across it.
  if (!(glm::length(glm::cross(tangent, view)) > 1e-12f * glm::dot(tangent, tangent)))
    tangent = std::abs(view.x) < 0.9f ? glm::cross(view, Vec3(1, 0, 0)) : glm::cross(view, Vec3(0, 1, 0));
  tangent = glm::normalize(tangent);
  hit.tangent = tangent;
  hit.uv = Vec2(u, 0.0f);
  hit.prim = prim;
  hit.curve_set = set_index;
  // Curves Info, as Cycles reads its curve attributes: key values interpolated linearly over the
  // segment (c[1] -> c[2]); Thickness the radii's, doubled (kernel curve_thickness).
  const float* intercept = &set.key_intercept[set.segment_key[prim]];
  hit.primitive_info = glm::vec4(intercept[1] + u * (intercept[2] - intercept[1]), set.segment_length[prim],
                             2.0f * (c[1].w + u * (c[2].w - c[1].w)), set.segment_random[prim]);
  if (!set.key_normal.empty()) {
    const Vec3* n = &set.key_normal[set.segment_key[prim]];
    hit.curve_normal = n[1] + u * (n[2] - n[1]);
  }
  if (set.shape == CurveShape::Round) {
    // Cycles' thick curves: the normal from the centre line at u out through the hit (the view
    // when they coincide).
    const Vec3 out = hit.position - Vec3(centre);
    const float len = glm::length(out);
    const Vec3 n = len > 0.0f && std::isfinite(len) ? out / len : view;
    hit.geometric_normal = n;
    hit.shading_normal = n;
  } else {
    // Cycles' rounded ribbons: Embree's v in [-1, 1] across the strand, as Cycles takes it
    // (kernel_embree_convert_hit), the shading normal turned that far around the strand from the
    // view along the bitangent (a Diffuse BSDF on grass strands: block mean 0.0060 against
    // Cycles' own 0.0063; v measured from the centre line along the bitangent instead: 0.022).
    const Vec3 bitangent = glm::normalize(glm::cross(tangent, view));
    const float v = std::isfinite(embree_v) ? std::clamp(embree_v, -1.0f, 1.0f) : 0.0f;
    const float cosine = std::sqrt(std::max(1.0f - v * v, 0.0f));
    const Vec3 n = v * bitangent - cosine * glm::normalize(glm::cross(tangent, bitangent));
    hit.uv.y = v;
    hit.geometric_normal = glm::normalize(n);  // (the hair BSDF's h = -v needs N unchanged by the
    hit.shading_normal = hit.geometric_normal;  // integrator's check against the geometric one)
  }
}

}  // namespace torrance
