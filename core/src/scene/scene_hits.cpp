// Hits from Embree's answers (Scene::intersect, Scene::intersect_packet): the hit triangle's
// corners (instances placed as the flattening export would), position, normals and UV frame.
#include "scene/ray_queries.h"

#include "scene/embree_rays.h"
#include "scene/scene_internal.h"
#include "scene/scene_motion.h"

#include <stdexcept>

namespace torrance {

using namespace scene_detail;

bool Scene::surface_hit(const void* rayhit, const Vec3& dir, SurfaceHit& hit) const {
  const RTCRayHit& rh = *static_cast<const RTCRayHit*>(rayhit);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  const uint32_t owner = rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID ? geometry_owner_[rh.hit.geomID]
                                                                      : geometry_owner_[rh.hit.instID[0]];
  hit.t = rh.ray.tfar;
  // Strands and points (never instanced) in one test, so that triangles pay for one branch.
  if (owner != kNoOwner && (owner & (kCurvesBit | kPointsBit)) && !(owner & kInstanceBit)) {
    const Vec3 origin(rh.ray.org_x, rh.ray.org_y, rh.ray.org_z);
    if (owner & kPointsBit) {
      point_hit(owner & ~kPointsBit, rh.hit.primID, origin, dir, hit.t, hit);
      return true;
    }
    hit.uv.y = rh.hit.v;  // Embree's v across the strand, which a ribbon's normal is rounded by
    hit.object = ShaderGlobals::kNoObject;
    curve_hit(owner & ~kCurvesBit, rh.hit.primID, rh.hit.u, origin, dir, hit.t, hit);
    return true;
  }
  triangle_hit(owner, rh.hit.primID, rh.hit.u, rh.hit.v, dir, hit);
  return true;
}

// Every field of the hit is written (those the triangle does not give, as a new SurfaceHit has
// them): a ray that passes a surface (alpha, volume boundaries) is intersected again into the
// same hit, and the surface behind must not keep the instance constants or the UV frame of the
// one in front.
void Scene::triangle_hit(uint32_t owner, uint32_t prim, float u, float v, const Vec3& dir, SurfaceHit& hit) const {
  Corners c;
  hit.on_curve = false;
  hit.on_point = false;
  hit.instance_constants = nullptr;
  hit.instance_constant_ids = nullptr;
  hit.num_instance_constants = 0;
  const Mesh* hit_mesh = nullptr;
  bool mirrored = false;
  if (!(owner & kInstanceBit)) {
    const Mesh& mesh = *meshes_[owner];
    hit_mesh = &mesh;
    c = mesh_corners(mesh.positions, mesh.triangles[prim],
                     mesh.corner_normals.empty() ? nullptr : &mesh.corner_normals[3 * prim],
                     mesh.corner_uvs.empty() ? nullptr : &mesh.corner_uvs[3 * prim]);
    if (mesh.motion_steps > 1)
      motion_corners({mesh.motion_steps, mesh.motion_positions.data(), mesh.positions.size(),
                      mesh.motion_normals.empty() ? nullptr : mesh.motion_normals.data(), 3 * mesh.triangles.size()},
                     mesh.triangles[prim], prim, c);
    hit.material = mesh.material_ids[prim];
    hit.emitter = mesh.emitter_index.empty() ? -1 : mesh.emitter_index[prim];
    hit.object_settings = mesh.settings;
  } else {
    const Instance& inst = instances_[owner & ~kInstanceBit];
    const Binding& b = bindings_[inst.binding];
    const Mesh& mesh = *prototypes_[b.prototype]->mesh;
    hit_mesh = &mesh;
    c = mesh_corners(mesh.positions, mesh.triangles[prim],
                     mesh.corner_normals.empty() ? nullptr : &mesh.corner_normals[3 * prim],
                     mesh.corner_uvs.empty() ? nullptr : &mesh.corner_uvs[3 * prim]);
    if (mesh.motion_steps > 1)  // a deforming prototype: its object-space corners at the ray's time
      motion_corners({mesh.motion_steps, mesh.motion_positions.data(), mesh.positions.size(),
                      mesh.motion_normals.empty() ? nullptr : mesh.motion_normals.data(), 3 * mesh.triangles.size()},
                     mesh.triangles[prim], prim, c);
    mirrored = place_corners(instance_transform(inst), c);
    if (mirrored) std::swap(u, v);
    hit.material = b.material(mesh.material_ids[prim]);
    hit.emitter = inst.emitter_base >= 0 && b.emitter_rank[prim] >= 0 ? inst.emitter_base + b.emitter_rank[prim] : -1;
    hit.object_settings = inst.settings;
    const size_t layers = instance_constant_ids_.size(), first = size_t(owner & ~kInstanceBit) * layers;
    if (layers > 0 && first + layers <= instance_constants_.size()) {
      hit.instance_constants = &instance_constants_[first];
      hit.instance_constant_ids = instance_constant_ids_.data();
      hit.num_instance_constants = int(layers);
    }
  }

  hit.object = owner;
  hit.prim = prim;
  hit.has_uv = !hit_mesh->corner_uvs.empty();
  const Vec3 &p0 = c.p[0], &p1 = c.p[1], &p2 = c.p[2];
  const float w = 1.0f - u - v;
  hit.num_attributes = int(hit_mesh->attribute_ids.size());
  if (hit.num_attributes > 0) {
    hit.corner_attributes = &hit_mesh->corner_attributes[3 * size_t(prim) * hit_mesh->attribute_ids.size()];
    // Fetched now, beside the corners' positions: a program's Attribute op (Object and Generated
    // coordinates, colours) reads them soon after, and waited for them there (2 % of a
    // procedural material's time).
    const char* first = reinterpret_cast<const char*>(hit.corner_attributes);
    __builtin_prefetch(first);
    __builtin_prefetch(first + 3 * sizeof(Vec3) * size_t(hit.num_attributes) - 1);
    hit.attribute_ids = hit_mesh->attribute_ids.data();
    hit.corner_weights = mirrored ? Vec3(w, v, u) : Vec3(w, u, v);  // the stored corners' order
  } else {
    hit.corner_attributes = nullptr;
    hit.attribute_ids = nullptr;
    hit.corner_weights = Vec3(0.0f);
  }
  hit.position = w * p0 + u * p1 + v * p2;  // interpolated, more accurate than origin + t * dir
  hit.corners[0] = p0;
  hit.corners[1] = p1;
  hit.corners[2] = p2;
  Vec3 ng = glm::cross(p1 - p0, p2 - p0);
  const float ng_len = glm::length(ng);
  ng = ng_len > 0.0f ? ng / ng_len : -dir;
  hit.geometric_normal = ng;
  hit.shading_normal = ng;
  if (hit.num_attributes > 0 && ng_len > 0.0f) {
    // The barycentric u's and v's gradients in the triangle's plane (attributes at moved points).
    const Vec3 n = glm::cross(p1 - p0, p2 - p0) / (ng_len * ng_len);
    const Vec3 grad_u = glm::cross(p2 - p0, n), grad_v = glm::cross(n, p1 - p0);
    hit.weight_gradients[0] = mirrored ? grad_v : grad_u;
    hit.weight_gradients[1] = mirrored ? grad_u : grad_v;
  } else {
    hit.weight_gradients[0] = hit.weight_gradients[1] = Vec3(0.0f);
  }
  if (c.has_n) {
    const Vec3 n = w * c.n[0] + u * c.n[1] + v * c.n[2];
    const float len = glm::length(n);
    if (len > 1e-6f && std::isfinite(len)) hit.shading_normal = n / len;
  }
  bool uv_frame = false;  // the tangent frame below was set
  if (c.has_uv) {
    const Vec2 &t0 = c.uv[0], &t1 = c.uv[1], &t2 = c.uv[2];
    hit.uv = w * t0 + u * t1 + v * t2;
    // dP/du from the triangle's UV parametrisation, for tangent-space normal maps.
    const Vec2 d1 = t1 - t0, d2 = t2 - t0;
    const float det = d1.x * d2.y - d1.y * d2.x;
    const float area2 = ng_len;
    hit.uv_per_metre = area2 > 0.0f ? std::sqrt(std::abs(det) / area2) : 0.0f;
    if (std::abs(det) > 1e-12f) {
      const Vec3 dpdu = ((p1 - p0) * d2.y - (p2 - p0) * d1.y) / det;
      const float len = glm::length(dpdu);
      if (len > 0.0f && std::isfinite(len)) {
        hit.tangent = dpdu / len;
        hit.bitangent_sign = det > 0.0f ? 1.0f : -1.0f;
        hit.dpdu = dpdu;
        hit.dpdv = ((p2 - p0) * d1.x - (p1 - p0) * d2.x) / det;
        uv_frame = true;
      }
    }
  } else {
    hit.uv = Vec2(0.0f);
    hit.uv_per_metre = 0.0f;
  }
  if (!uv_frame) {  // as a new SurfaceHit has it
    hit.tangent = Vec3(0.0f);
    hit.bitangent_sign = 1.0f;
    hit.dpdu = hit.dpdv = Vec3(0.0f);
  }
}

void Scene::intersect_packet(const Ray* rays, int n, SurfaceHit* hits, bool* found) const {
  if (n < 1 || n > kPacketSize) throw std::invalid_argument("intersect_packet takes 1 to 8 rays");
  alignas(32) int valid[kPacketSize];
  alignas(32) RTCRayHit8 packet;
  for (int i = 0; i < kPacketSize; ++i) {
    const Ray& r = rays[i < n ? i : 0];
    valid[i] = i < n ? -1 : 0;
    set_embree_lane(packet, i, r.origin, r.dir, r.tmin, r.tmax);
  }
  ray_queries::intersect_coherent(scene_of(scene_), valid, packet);
  for (int i = 0; i < n; ++i) {
    RTCRayHit rh;  // lane i as a single ray's answer
    rh.ray.org_x = packet.ray.org_x[i];
    rh.ray.org_y = packet.ray.org_y[i];
    rh.ray.org_z = packet.ray.org_z[i];
    rh.ray.tfar = packet.ray.tfar[i];
    rh.hit.u = packet.hit.u[i];
    rh.hit.v = packet.hit.v[i];
    rh.hit.primID = packet.hit.primID[i];
    rh.hit.geomID = packet.hit.geomID[i];
    rh.hit.instID[0] = packet.hit.instID[0][i];
    found[i] = surface_hit(&rh, rays[i].dir, hits[i]);
  }
}

}  // namespace torrance
