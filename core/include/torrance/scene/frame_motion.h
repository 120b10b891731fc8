// The Vector pass's view of the scene (Cycles' motion pass): where the camera, the world-space
// meshes' vertices, the instances, the deforming prototypes' vertices and the hair strands' keys
// were one frame before the rendered frame and will be one frame after it, as
// Scene::set_frame_motion_* gave them. What was not given did not move.
#pragma once

#include "torrance/util/math.h"

#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace torrance {

struct FrameMotion {
  bool has_camera = false;  // the Vector pass is made only when the camera's frames are known
  std::array<std::array<float, 16>, 2> camera{};  // camera_to_world (row-major) before, after
  struct MeshFrames {
    std::vector<Vec3> before, after;  // every vertex (world space but for prototypes')
  };
  std::unordered_map<uint32_t, MeshFrames> meshes;  // by mesh id
  // By instance id: its object-to-world 3x4 row-major transform before and after.
  std::unordered_map<uint32_t, std::array<std::array<float, 12>, 2>> instances;
  // By prototype id: a deforming instanced mesh's vertices before and after, object space.
  std::unordered_map<uint32_t, MeshFrames> prototypes;
  // By curve set id: its keys before and after, in the set's layout (its stored keys).
  std::unordered_map<uint32_t, MeshFrames> curves;
};

}  // namespace torrance
