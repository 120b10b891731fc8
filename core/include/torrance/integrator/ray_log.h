// Counting and logging the rays a render traces. Every query the Scene makes (Scene::intersect,
// Scene::occluded) passes through one place (src/scene/ray_queries.cpp), which counts it per thread
// and, while a RayLog of that scene is alive, appends it with its answer to the log. The log
// is replayed through raw Embree by ray_replay.h: the integrator's rays per second against
// Embree's on the very same rays.
#pragma once

#include "torrance/util/math.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace torrance {

class Scene;

// Camera: a closest-hit query with tmin > 0 (camera rays start at clip_start; every later ray
// of a path starts at 0). Occlusion: a shadow ray.
enum class RayKind : uint8_t { Camera, Closest, Occlusion };

struct LoggedRay {
  Vec3 origin{0.0f};
  float tmin = 0.0f;
  Vec3 dir{0.0f};
  float tmax = 0.0f;
  RayKind kind = RayKind::Closest;
  // The answer: closest hit -> hit_t (tfar) and Embree's ids (geom_id RTC_INVALID_GEOMETRY_ID
  // when it missed); occlusion -> occluded.
  bool occluded = false;
  uint32_t geom_id = 0xFFFFFFFFu, inst_id = 0xFFFFFFFFu, prim_id = 0xFFFFFFFFu;
  float hit_t = 0.0f;

  // Same query and same answer (ids, occlusion, bit-equal t).
  bool same_answer(const LoggedRay& other) const;
};

struct RayCounts {
  uint64_t closest = 0, occlusion = 0;
  uint64_t packets = 0;  // of the closest-hit queries, the 8-wide packets they went in
  uint64_t total() const { return closest + occlusion; }
  RayCounts operator-(const RayCounts& o) const {
    return {closest - o.closest, occlusion - o.occlusion, packets - o.packets};
  }
};

// The queries made by the calling thread since it started (never reset: take differences).
RayCounts thread_ray_counts();

// While alive, logs every query made on `scene` by any thread (one RayLog at a time: a second
// throws std::runtime_error). Logging costs a copy per ray; renders are counted either way.
class RayLog {
 public:
  explicit RayLog(const Scene& scene);
  ~RayLog();
  RayLog(const RayLog&) = delete;
  RayLog& operator=(const RayLog&) = delete;
  // The logged rays, thread by thread, each thread's in the order it traced them.
  std::vector<LoggedRay> rays() const;

  struct Storage;

 private:
  std::unique_ptr<Storage> storage_;
};

}  // namespace torrance
