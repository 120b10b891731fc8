// The local ray queries (ShaderTracer::local_occluded, local_hits: Cycles' scene_intersect_local,
// for the Bevel node and Ambient Occlusion's Only Local): rays against one object's own
// triangles, traced in a BVH of that object alone (Scene::LocalScenes), an instance's ray taken
// into its prototype's space. local_hits collects every hit along the ray through Embree's
// context filter, keeping a uniformly chosen few (reservoir sampling) as Cycles does.
#include "scene/embree_rays.h"
#include "scene/scene_internal.h"

#include <algorithm>

namespace torrance {

using namespace scene_detail;

namespace {

RTCScene new_local_scene(RTCDevice device, RTCGeometry geom) {
  RTCScene scene = rtcNewScene(device);
  rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_MEDIUM);
  rtcAttachGeometryByID(scene, geom, 0);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  return scene;
}

struct RecordedHit {
  uint32_t prim;
  float u, v, t;
};

// An intersection context that records every hit (the context filter rejects each, so Embree
// goes on to the next), up to max of them chosen uniformly among all.
struct CollectingContext {
  RTCIntersectContext context;  // first: Embree hands the filter a pointer to it
  RecordedHit* kept;
  int max_kept;
  int found = 0;
  uint32_t state;
  uint32_t next_random() {  // xorshift32
    state ^= state << 13;
    state ^= state >> 17;
    state ^= state << 5;
    return state;
  }
};

void collect_hit(const RTCFilterFunctionNArguments* args) {
  if (args->N != 1 || !args->valid[0]) return;
  args->valid[0] = 0;  // go on: every hit along the ray is wanted
  auto* c = reinterpret_cast<CollectingContext*>(args->context);
  const RecordedHit hit{RTCHitN_primID(args->hit, 1, 0), RTCHitN_u(args->hit, 1, 0), RTCHitN_v(args->hit, 1, 0),
                        RTCRayN_tfar(args->ray, 1, 0)};
  // A ray through an edge meets both triangles at the same distance: one hit (as Cycles).
  for (int i = std::min(c->found, c->max_kept) - 1; i >= 0; --i)
    if (c->kept[i].t == hit.t) return;
  ++c->found;
  int slot = c->found - 1;
  if (slot >= c->max_kept) {
    slot = int(c->next_random() % uint32_t(c->found));
    if (slot >= c->max_kept) return;
  }
  c->kept[slot] = hit;
}

}  // namespace

void Scene::build_local_scenes() {
  auto local = std::make_unique<LocalScenes>();
  const RTCDevice device = device_of(device_);
  local->meshes.resize(meshes_.size(), nullptr);
  for (size_t m = 0; m < meshes_.size(); ++m)
    if (!meshes_[m]->triangles.empty())
      local->meshes[m] = new_local_scene(device, static_cast<RTCGeometry>(new_triangle_geometry(*meshes_[m])));
  local->prototypes.resize(prototypes_.size(), nullptr);
  for (size_t p = 0; p < prototypes_.size(); ++p)
    if (prototypes_[p]->scene)
      local->prototypes[p] =
          new_local_scene(device, static_cast<RTCGeometry>(new_triangle_geometry(*prototypes_[p]->mesh)));
  check_device("building the objects' own BVHs");
  local_scenes_ = std::move(local);
}

void* Scene::local_scene(uint32_t object, Vec3& origin, Vec3& dir) const {
  if (!local_scenes_ || object == ShaderGlobals::kNoObject || (object & kCurvesBit)) return nullptr;
  if (!(object & kInstanceBit))
    return object < local_scenes_->meshes.size() ? local_scenes_->meshes[object] : nullptr;
  const size_t index = object & ~kInstanceBit;
  if (index >= instances_.size()) return nullptr;
  const Instance& inst = instances_[index];
  if (inst.binding == kRemoved || inst.hidden) return nullptr;
  const uint32_t prototype = bindings_[inst.binding].prototype;
  if (prototype >= local_scenes_->prototypes.size()) return nullptr;
  // World to object space: the inverse of the 3x3 part is the transpose of normal_matrix's.
  const std::array<float, 12> m = instance_transform(inst);
  const std::array<double, 9> n = normal_matrix(m);
  auto to_object = [&](const Vec3& v) {
    return Vec3(float(n[0] * v.x + n[3] * v.y + n[6] * v.z), float(n[1] * v.x + n[4] * v.y + n[7] * v.z),
                float(n[2] * v.x + n[5] * v.y + n[8] * v.z));
  };
  origin = to_object(origin - Vec3(m[3], m[7], m[11]));
  dir = to_object(dir);
  return local_scenes_->prototypes[prototype];
}

bool Scene::local_occluded(uint32_t object, const Vec3& origin, const Vec3& dir, float tmin, float tmax) const {
  Vec3 o = origin, d = dir;
  const RTCScene scene = static_cast<RTCScene>(local_scene(object, o, d));
  if (!scene) return false;
  RTCRay ray = embree_ray(o, d, tmin, tmax);
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar < 0.0f;
}

int Scene::local_hits(uint32_t object, const Vec3& origin, const Vec3& dir, float tmax, uint32_t seed,
                      LocalHit* hits, int max_hits) const {
  Vec3 o = origin, d = dir;
  const RTCScene scene = static_cast<RTCScene>(local_scene(object, o, d));
  if (!scene || max_hits < 1) return 0;
  constexpr int kMaxKept = 16;
  RecordedHit kept[kMaxKept];
  CollectingContext c;
  rtcInitIntersectContext(&c.context);
  c.context.filter = collect_hit;
  c.kept = kept;
  c.max_kept = std::min(max_hits, kMaxKept);
  c.state = seed | 1u;
  RTCRayHit rh = embree_ray_hit(o, d, 0.0f, tmax);
  rtcIntersect1(scene, &c.context, &rh);
  const int n = std::min(c.found, c.max_kept);
  for (int i = 0; i < n; ++i) {
    SurfaceHit sh;
    triangle_hit(object, kept[i].prim, kept[i].u, kept[i].v, dir, sh);
    hits[i] = LocalHit{sh.position, sh.geometric_normal, sh.shading_normal};
  }
  return c.found;
}

}  // namespace torrance
