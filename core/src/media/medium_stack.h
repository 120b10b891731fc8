// The media a path is inside of (Cycles' volume stack): the world's medium outermost, then the
// volumes of the closed meshes the path has entered, their coefficients summed (MediumMix). A path
// enters a mesh's medium when it crosses its surface against the geometric normal (refracting
// into it or passing a volume-only boundary) and leaves it when it crosses it the other way.
#pragma once

#include "torrance/media/homogeneous_medium.h"
#include "torrance/media/scene_media.h"

#include <array>
#include <cstdint>

namespace torrance {

class Scene;

class MediumStack {
 public:
  static constexpr int kMaxDepth = 8;  // Cycles' volume stack holds as many (a deeper nest: the innermost left out)

  // Crossing a surface of `material` into the mesh (entering) or out of it.
  void cross(const SceneMedia& media, uint32_t material, bool entering);
  void enter(const SceneMedia& media, int32_t id);
  void leave(const SceneMedia& media, int32_t id);
  const MediumMix& mix() const { return mix_; }
  bool empty() const { return count_ == 0; }

 private:
  void update(const SceneMedia& media);
  std::array<int32_t, kMaxDepth> ids_{};
  int count_ = 0;
  MediumMix mix_;
};

// The stack at point p (the camera): the world's medium and the volume meshes p is inside of,
// told along one ray as Cycles' volume_stack_init does: a volume mesh whose first hit is a
// back face encloses p.
MediumStack media_at(const Scene& scene, const Vec3& p);

}  // namespace torrance
