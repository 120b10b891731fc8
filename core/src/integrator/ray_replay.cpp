#include "torrance/integrator/ray_replay.h"

#include "scene/embree_rays.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace torrance {

std::vector<LoggedRay> record_render_rays(Scene& scene, const RenderSettings& settings) {
  RayLog log(scene);
  render(scene, settings);
  return log.rays();
}

std::vector<LoggedRay> select_rays(const std::vector<LoggedRay>& rays, RayKind kind, bool unbounded_only) {
  std::vector<LoggedRay> selected;
  for (const LoggedRay& r : rays)
    if (r.kind == kind && (!unbounded_only || std::isinf(r.tmax))) selected.push_back(r);
  return selected;
}

namespace {

constexpr uint32_t kInvalid = RTC_INVALID_GEOMETRY_ID;

void trace_one(RTCScene scene, LoggedRay& r) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh = embree_ray_hit(r.origin, r.dir, r.tmin, r.tmax);
  if (r.kind == RayKind::Occlusion) {
    rtcOccluded1(scene, &context, &rh.ray);
    r.occluded = rh.ray.tfar < 0.0f;
    return;
  }
  rtcIntersect1(scene, &context, &rh);
  r.geom_id = rh.hit.geomID;
  r.inst_id = rh.hit.instID[0];
  r.prim_id = rh.hit.geomID == kInvalid ? kInvalid : rh.hit.primID;
  r.hit_t = rh.hit.geomID == kInvalid ? 0.0f : rh.ray.tfar;
}

template <int W>
struct Packet;
template <>
struct Packet<8> {
  using RayHit = RTCRayHit8;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* p) { rtcIntersect8(valid, s, c, p); }
  static void occluded(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* p) { rtcOccluded8(valid, s, c, &p->ray); }
};
// Up to W consecutive rays of one kind as one packet.
template <int W>
void trace_packet(RTCScene scene, LoggedRay* rays, int n) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) int valid[W];
  alignas(64) typename Packet<W>::RayHit p;
  for (int i = 0; i < W; ++i) {
    const LoggedRay& r = rays[i < n ? i : 0];
    valid[i] = i < n ? -1 : 0;
    set_embree_lane(p, i, r.origin, r.dir, r.tmin, r.tmax);
  }
  if (rays[0].kind == RayKind::Occlusion) {
    Packet<W>::occluded(valid, scene, &context, &p);
    for (int i = 0; i < n; ++i) rays[i].occluded = p.ray.tfar[i] < 0.0f;
    return;
  }
  Packet<W>::intersect(valid, scene, &context, &p);
  for (int i = 0; i < n; ++i) {
    const bool hit = p.hit.geomID[i] != kInvalid;
    rays[i].geom_id = p.hit.geomID[i];
    rays[i].inst_id = p.hit.instID[0][i];
    rays[i].prim_id = hit ? p.hit.primID[i] : kInvalid;
    rays[i].hit_t = hit ? p.ray.tfar[i] : 0.0f;
  }
}

template <int W>
void trace_packets(RTCScene scene, LoggedRay* rays, size_t n) {
  for (size_t i = 0; i < n;) {
    size_t run = 1;
    while (run < W && i + run < n && rays[i + run].kind == rays[i].kind) ++run;
    trace_packet<W>(scene, rays + i, int(run));
    i += run;
  }
}

}  // namespace

double replay_rays(const Scene& scene, std::vector<LoggedRay>& rays, int packet_width, int threads) {
  // (16-wide packets are left out: Embree 3.13's rtcOccluded16 did not return on instanced
  // scenes here, an emulation of 16 lanes on AVX2 anyway.)
  if (packet_width != 1 && packet_width != 8) throw std::invalid_argument("packet_width must be 1 or 8");
  RTCScene rtc_scene = static_cast<RTCScene>(scene.embree_scene());
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  constexpr size_t kRun = 1024;  // rays per task, a multiple of every packet width
  const auto start = std::chrono::steady_clock::now();
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, rays.size(), kRun), [&](const tbb::blocked_range<size_t>& r) {
      LoggedRay* first = rays.data() + r.begin();
      const size_t n = r.size();
      if (packet_width == 8) trace_packets<8>(rtc_scene, first, n);
      else
        for (size_t i = 0; i < n; ++i) trace_one(rtc_scene, first[i]);
    });
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace torrance
