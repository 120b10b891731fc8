// The scene: triangle meshes traced by Embree 3, their materials, the lights and the camera.
//
// Embree is driven in the order of its minimal tutorial: device -> error callback -> buffers ->
// commit geometry -> commit scene -> trace. Every input is validated on the way in and rejected
// with std::invalid_argument naming the problem, so nothing malformed ever reaches the tracer.
#pragma once

#include "torrance/bsdf.h"
#include "torrance/camera.h"
#include "torrance/lights.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace torrance {

struct SurfaceHit {
  float t = 0.0f;
  Vec3 position{0.0f};
  Vec3 geometric_normal{0.0f};  // unit, as wound (counter-clockwise), not yet facing the ray
  Vec3 shading_normal{0.0f};    // unit, interpolated corner normal (= geometric for flat meshes)
  uint32_t material = 0;
};

class Scene {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  uint32_t add_material(const Material& material);

  // positions: num_vertices xyz; triangles: num_triangles vertex-index triples;
  // corner_normals: nullptr or num_triangles * 3 xyz normals; material_ids: nullptr or num_triangles.
  // Degenerate triangles and zero-length normals are tolerated (the latter fall back to flat).
  // Returns the mesh id; a mesh without triangles is accepted and ignored.
  uint32_t add_mesh(const float* positions, size_t num_vertices, const int64_t* triangles, size_t num_triangles,
                    const float* corner_normals, const int64_t* material_ids);

  Lights& lights() { return lights_; }
  const Lights& lights() const { return lights_; }
  void set_camera(const CameraParams& camera) { camera_ = camera; }
  const CameraParams& camera() const { return camera_; }

  size_t num_triangles() const;
  size_t num_materials() const { return materials_.size(); }
  const Material& material(uint32_t i) const { return materials_[i]; }

  // Builds the BVH if geometry changed since the last commit. Must precede intersect/occluded.
  void commit();
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  bool occluded(const Vec3& origin, const Vec3& dir, float tmin, float tmax) const;

 private:
  struct Mesh;
  void check_device(const char* during) const;

  std::vector<Material> materials_;
  std::vector<std::unique_ptr<Mesh>> meshes_;  // indexed by Embree geometry id
  Lights lights_;
  CameraParams camera_;
  void* device_ = nullptr;  // RTCDevice
  void* scene_ = nullptr;   // RTCScene
  bool dirty_ = true;
  mutable std::string embree_error_;
  friend void embree_error_callback(void*, int, const char*);
};

}  // namespace torrance
