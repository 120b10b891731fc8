#include "scene/ray_queries.h"

#include "torrance/integrator/ray_log.h"
#include "torrance/scene/scene.h"

#include <tbb/enumerable_thread_specific.h>

#include <atomic>
#include <cstring>
#include <stdexcept>

namespace torrance {

struct RayLog::Storage {
  RTCScene scene = nullptr;
  tbb::enumerable_thread_specific<std::vector<LoggedRay>> per_thread;
};

namespace {

// A thread's query state in one thread-local object: the module is position-independent, so each
// distinct thread-local costs a __tls_get_addr call per query (three of them cost the water
// scene ~6 M instructions at 16 spp).
struct ThreadQueries {
  RayCounts counts;
  float time = 0.0f;
  uint32_t mask = 0xFFFFFFFFu;
};
thread_local ThreadQueries this_thread;
std::atomic<RayLog::Storage*> recording{nullptr};

LoggedRay logged_query(const RTCRay& ray, RayKind kind) {
  LoggedRay r;
  r.origin = Vec3(ray.org_x, ray.org_y, ray.org_z);
  r.dir = Vec3(ray.dir_x, ray.dir_y, ray.dir_z);
  r.tmin = ray.tnear;
  r.tmax = ray.tfar;
  r.kind = kind;
  return r;
}

RayLog::Storage* recording_of(RTCScene scene) {
  RayLog::Storage* log = recording.load(std::memory_order_acquire);
  return log && log->scene == scene ? log : nullptr;
}

}  // namespace

RayCounts thread_ray_counts() { return this_thread.counts; }

bool LoggedRay::same_answer(const LoggedRay& o) const {
  const bool same_query = origin == o.origin && dir == o.dir && tmin == o.tmin && tmax == o.tmax && kind == o.kind;
  if (!same_query) return false;
  if (kind == RayKind::Occlusion) return occluded == o.occluded;
  return geom_id == o.geom_id && inst_id == o.inst_id && prim_id == o.prim_id &&
         std::memcmp(&hit_t, &o.hit_t, sizeof(float)) == 0;
}

RayLog::RayLog(const Scene& scene) : storage_(std::make_unique<Storage>()) {
  storage_->scene = static_cast<RTCScene>(scene.embree_scene());
  Storage* expected = nullptr;
  if (!recording.compare_exchange_strong(expected, storage_.get()))
    throw std::runtime_error("another RayLog is already recording");
}

RayLog::~RayLog() { recording.store(nullptr, std::memory_order_release); }

std::vector<LoggedRay> RayLog::rays() const {
  std::vector<LoggedRay> all;
  for (const auto& thread_rays : storage_->per_thread) all.insert(all.end(), thread_rays.begin(), thread_rays.end());
  return all;
}

namespace ray_queries {

void set_time(float time) { this_thread.time = time; }
float time() { return this_thread.time; }
void set_mask(uint32_t mask) { this_thread.mask = mask; }

void intersect(RTCScene scene, RTCRayHit& rh) {
  RayLog::Storage* log = recording_of(scene);
  LoggedRay logged;
  if (log) logged = logged_query(rh.ray, rh.ray.tnear > 0.0f ? RayKind::Camera : RayKind::Closest);
  ThreadQueries& thread = this_thread;
  rh.ray.time = thread.time;
  rh.ray.mask = thread.mask;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcIntersect1(scene, &context, &rh);
  ++thread.counts.closest;
  if (log) {
    logged.geom_id = rh.hit.geomID;
    logged.inst_id = rh.hit.instID[0];
    logged.prim_id = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? RTC_INVALID_GEOMETRY_ID : rh.hit.primID;
    logged.hit_t = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? 0.0f : rh.ray.tfar;
    log->per_thread.local().push_back(logged);
  }
}

void intersect_coherent(RTCScene scene, const int* valid, RTCRayHit8& packet) {
  RayLog::Storage* log = recording_of(scene);
  LoggedRay logged[8];
  int active = 0;
  for (int i = 0; i < 8; ++i)
    if (valid[i]) {
      ++active;
      if (log) {
        logged[i].origin = Vec3(packet.ray.org_x[i], packet.ray.org_y[i], packet.ray.org_z[i]);
        logged[i].dir = Vec3(packet.ray.dir_x[i], packet.ray.dir_y[i], packet.ray.dir_z[i]);
        logged[i].tmin = packet.ray.tnear[i];
        logged[i].tmax = packet.ray.tfar[i];
        logged[i].kind = packet.ray.tnear[i] > 0.0f ? RayKind::Camera : RayKind::Closest;
      }
    }
  ThreadQueries& thread = this_thread;
  for (int i = 0; i < 8; ++i) {
    packet.ray.time[i] = thread.time;
    packet.ray.mask[i] = thread.mask;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  rtcIntersect8(valid, scene, &context, &packet);
  thread.counts.closest += uint64_t(active);
  ++thread.counts.packets;
  if (!log) return;
  for (int i = 0; i < 8; ++i)
    if (valid[i]) {
      const bool hit = packet.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
      logged[i].geom_id = packet.hit.geomID[i];
      logged[i].inst_id = packet.hit.instID[0][i];
      logged[i].prim_id = hit ? packet.hit.primID[i] : RTC_INVALID_GEOMETRY_ID;
      logged[i].hit_t = hit ? packet.ray.tfar[i] : 0.0f;
      log->per_thread.local().push_back(logged[i]);
    }
}

bool occluded(RTCScene scene, RTCRay& ray) {
  RayLog::Storage* log = recording_of(scene);
  LoggedRay logged;
  if (log) logged = logged_query(ray, RayKind::Occlusion);
  ThreadQueries& thread = this_thread;
  ray.time = thread.time;
  ray.mask = thread.mask;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  rtcOccluded1(scene, &context, &ray);
  ++thread.counts.occlusion;
  const bool blocked = ray.tfar < 0.0f;
  if (log) {
    logged.occluded = blocked;
    log->per_thread.local().push_back(logged);
  }
  return blocked;
}

}  // namespace ray_queries
}  // namespace torrance
