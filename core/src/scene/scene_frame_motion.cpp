// The Vector pass's scene data (Scene::set_frame_motion_*, frame_motion.h) and where a hit's point
// was one frame before and will be one frame after (Scene::frame_motion_points), as Cycles'
// primitive_motion_vector finds it: a deforming mesh's vertices then at the hit's barycentric
// weights, an instance's transforms then applied to the point in the instance (a deforming
// prototype's point then: its vertices then at the same weights), a strand's keys then along its
// segment.
#include "hair/curve_set.h"
#include "scene/scene_internal.h"
#include "torrance/util/limits.h"

#include <stdexcept>
#include <string>

namespace torrance {

using namespace scene_detail;

namespace {

std::vector<Vec3> checked_positions(const float* xyz, size_t n, const std::string& which) {
  std::vector<Vec3> out(n);
  for (size_t i = 0; i < n; ++i) {
    out[i] = Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    require_position(out[i], which + ", vertex " + std::to_string(i));
  }
  return out;
}

void check_matrix(const float* m, int entries, const std::string& which) {
  for (int k = 0; k < entries; ++k) {
    if (!std::isfinite(m[k])) throw std::invalid_argument(which + " has a NaN or Inf entry");
    if (std::abs(m[k]) > kMaxCoordinate) throw std::invalid_argument(which + " has an entry beyond 1e12");
  }
}

// The barycentric weights of p (on the triangle's plane) at corners c.
Vec3 barycentric(const Vec3& p, const Vec3 (&c)[3]) {
  const Vec3 e1 = c[1] - c[0], e2 = c[2] - c[0], d = p - c[0];
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double dp1 = glm::dot(d, e1), dp2 = glm::dot(d, e2);
  const double det = d11 * d22 - d12 * d12;
  if (!(det > 0.0)) return Vec3(1.0f, 0.0f, 0.0f);  // a degenerate triangle: its first corner
  const double u = (d22 * dp1 - d12 * dp2) / det, v = (d11 * dp2 - d12 * dp1) / det;
  return Vec3(float(1.0 - u - v), float(u), float(v));
}

}  // namespace

void Scene::set_frame_motion_camera(const std::array<float, 16>& before, const std::array<float, 16>& after) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set the camera's neighbouring frames");
  check_matrix(before.data(), 16, "the camera's previous frame");
  check_matrix(after.data(), 16, "the camera's next frame");
  frame_motion_.camera = {before, after};
  frame_motion_.has_camera = true;
}

void Scene::set_frame_motion_mesh(uint32_t mesh, const float* before, const float* after) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a mesh's neighbouring frames");
  if (mesh >= meshes_.size()) throw std::invalid_argument("set_frame_motion_mesh: no mesh " + std::to_string(mesh));
  const size_t n = meshes_[mesh]->positions.size();
  FrameMotion::MeshFrames frames{checked_positions(before, n, "previous frame"),
                                 checked_positions(after, n, "next frame")};
  frame_motion_.meshes[mesh] = std::move(frames);
}

void Scene::set_frame_motion_instances(const int64_t* ids, size_t count, const float* before, const float* after) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set instances' neighbouring frames");
  for (size_t i = 0; i < count; ++i) {
    live_instance(ids[i], "set_frame_motion_instances");
    check_matrix(before + 12 * i, 12, "the previous frame's transform of instance " + std::to_string(ids[i]));
    check_matrix(after + 12 * i, 12, "the next frame's transform of instance " + std::to_string(ids[i]));
  }
  for (size_t i = 0; i < count; ++i) {
    auto& frames = frame_motion_.instances[uint32_t(ids[i])];
    std::copy_n(before + 12 * i, 12, frames[0].begin());
    std::copy_n(after + 12 * i, 12, frames[1].begin());
  }
}

void Scene::set_frame_motion_prototype(uint32_t prototype, const float* before, const float* after) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set a prototype's neighbouring frames");
  if (prototype >= prototypes_.size())
    throw std::invalid_argument("set_frame_motion_prototype: no prototype " + std::to_string(prototype));
  const size_t n = prototypes_[prototype]->mesh->positions.size();
  FrameMotion::MeshFrames frames{checked_positions(before, n, "previous frame"),
                                 checked_positions(after, n, "next frame")};
  frame_motion_.prototypes[prototype] = std::move(frames);
}

void Scene::set_frame_motion_curves(uint32_t set_id, const int64_t* curve_first, size_t num_curves,
                                    const float* before, const float* after, size_t num_keys) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set curves' neighbouring frames");
  if (set_id >= curve_sets_.size())
    throw std::invalid_argument("set_frame_motion_curves: no curve set " + std::to_string(set_id));
  if (curve_first[0] != 0 || curve_first[num_curves] != int64_t(num_keys))
    throw std::invalid_argument("curve offsets must run from 0 to the number of keys");
  const std::vector<Vec3> b = checked_positions(before, num_keys, "previous frame's keys");
  const std::vector<Vec3> a = checked_positions(after, num_keys, "next frame's keys");
  // The set's layout (add_curves): each curve of 2 keys or more, its end keys doubled.
  FrameMotion::MeshFrames frames;
  for (size_t c = 0; c < num_curves; ++c) {
    const int64_t first = curve_first[c], end = curve_first[c + 1];
    if (end < first) throw std::invalid_argument("curve offsets must ascend");
    if (end - first < 2) continue;
    for (const auto& [from, to] : {std::pair(&b, &frames.before), std::pair(&a, &frames.after)}) {
      to->push_back((*from)[size_t(first)]);
      to->insert(to->end(), from->begin() + first, from->begin() + end);
      to->push_back((*from)[size_t(end - 1)]);
    }
  }
  if (frames.before.size() != curve_sets_[set_id]->keys.size())
    throw std::invalid_argument("the curves' offsets are not those curve set " + std::to_string(set_id) +
                                " was added with");
  frame_motion_.curves[set_id] = std::move(frames);
}

std::array<Vec3, 3> Scene::frame_motion_points(const SurfaceHit& hit) const {
  const Vec3& p = hit.position;
  if (hit.on_curve) {
    const auto it = frame_motion_.curves.find(hit.curve_set);
    const CurveSet& set = *curve_sets_[hit.curve_set];
    const uint32_t k = set.segment_key[hit.prim] + 1;  // the segment runs from key k to k + 1
    const float u = hit.uv.x;
    const auto along = [&](const Vec3& a, const Vec3& b) { return (1.0f - u) * a + u * b; };
    const Vec3 centre = along(Vec3(set.keys[k]), Vec3(set.keys[k + 1]));
    if (it == frame_motion_.curves.end()) return {centre, centre, centre};
    const FrameMotion::MeshFrames& f = it->second;
    return {centre, along(f.before[k], f.before[k + 1]), along(f.after[k], f.after[k + 1])};
  }
  if (hit.object == ShaderGlobals::kNoObject) return {p, p, p};
  if (!(hit.object & kInstanceBit)) {
    const auto it = frame_motion_.meshes.find(hit.object);
    if (it == frame_motion_.meshes.end()) return {p, p, p};
    const glm::uvec3& tri = meshes_[hit.object]->triangles[hit.prim];
    const Vec3 w = barycentric(p, hit.corners);
    const auto at = [&](const std::vector<Vec3>& v) { return w.x * v[tri.x] + w.y * v[tri.y] + w.z * v[tri.z]; };
    return {p, at(it->second.before), at(it->second.after)};
  }
  const uint32_t index = hit.object & ~kInstanceBit;
  const auto it = frame_motion_.instances.find(index);
  const uint32_t prototype = bindings_[instances_[index].binding].prototype;
  const auto deformed = frame_motion_.prototypes.find(prototype);
  const bool moved = it != frame_motion_.instances.end(), deforms = deformed != frame_motion_.prototypes.end();
  if (!moved && !deforms) return {p, p, p};
  // The point in the instance: M^-1 (p - t), M^-1 the transpose of normal_matrix's rows.
  const std::array<float, 12> m = instance_transform(instances_[index]);
  const std::array<double, 9> n = normal_matrix(m);
  const double x = double(p.x) - m[3], y = double(p.y) - m[7], z = double(p.z) - m[11];
  const Vec3 local(float(n[0] * x + n[3] * y + n[6] * z), float(n[1] * x + n[4] * y + n[7] * z),
                   float(n[2] * x + n[5] * y + n[8] * z));
  Vec3 local_before = local, local_after = local;
  if (deforms) {  // the point of the deforming mesh at the same barycentric weights then
    const Mesh& mesh = *prototypes_[prototype]->mesh;
    const glm::uvec3& tri = mesh.triangles[hit.prim];
    const Vec3 corners[3] = {mesh.positions[tri.x], mesh.positions[tri.y], mesh.positions[tri.z]};
    const Vec3 w = barycentric(local, corners);
    const auto at = [&](const std::vector<Vec3>& v) { return w.x * v[tri.x] + w.y * v[tri.y] + w.z * v[tri.z]; };
    local_before = at(deformed->second.before);
    local_after = at(deformed->second.after);
  }
  return {p, transform_point(moved ? it->second[0] : m, local_before),
          transform_point(moved ? it->second[1] : m, local_after)};
}

}  // namespace torrance
