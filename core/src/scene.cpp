#include "torrance/scene.h"

#include "torrance/limits.h"

#include <embree3/rtcore.h>

#include <limits>
#include <stdexcept>

namespace torrance {

struct Scene::Mesh {
  std::vector<Vec3> positions;
  std::vector<glm::uvec3> triangles;
  std::vector<Vec3> corner_normals;  // empty => flat
  std::vector<uint32_t> material_ids;
  std::vector<Vec2> corner_uvs;  // empty => no UVs
  std::vector<int32_t> emitter_index;  // per triangle: index in the mesh light, or -1
};

void embree_error_callback(void* user, int code, const char* message) {
  auto* scene = static_cast<Scene*>(user);
  scene->embree_error_ = "Embree error " + std::to_string(code) + ": " + (message ? message : "");
}

namespace {
RTCDevice device_of(void* d) { return static_cast<RTCDevice>(d); }
RTCScene scene_of(void* s) { return static_cast<RTCScene>(s); }
void error_trampoline(void* user, RTCError code, const char* message) {
  embree_error_callback(user, int(code), message);
}
}  // namespace

Scene::Scene() {
  device_ = rtcNewDevice("verbose=0");
  if (!device_) throw std::runtime_error("Embree: could not create a device (rtcNewDevice failed)");
  rtcSetDeviceErrorFunction(device_of(device_), error_trampoline, this);
  scene_ = rtcNewScene(device_of(device_));
  rtcSetSceneFlags(scene_of(scene_), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(scene_of(scene_), RTC_BUILD_QUALITY_MEDIUM);
  check_device("creating the scene");
}

Scene::~Scene() {
  if (scene_) rtcReleaseScene(scene_of(scene_));
  if (device_) rtcReleaseDevice(device_of(device_));
}

void Scene::check_device(const char* during) const {
  if (!embree_error_.empty()) {
    std::string message = embree_error_ + " (while " + during + ")";
    embree_error_.clear();
    throw std::runtime_error(message);
  }
}

void Scene::check_idle(const char* change) const {
  if (renders_ > 0)
    throw std::runtime_error(std::string("cannot ") + change +
                             " while a render uses the scene; stop the render (RenderSession.stop()) first");
}

void Scene::begin_render(LightSelection selection) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (materials_.empty()) {
    materials_.push_back(Material{});
    material_textures_.push_back({});
    emitters_dirty_ = true;
  }
  commit();
  lights_.set_selection(selection);
  ++renders_;
}

void Scene::edit_lights(const std::function<void(Lights&)>& edit) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("change the lights");
  edit(lights_);
}

uint32_t Scene::add_texture(Texture texture) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a texture");
  textures_.push_back(std::make_shared<const Texture>(std::move(texture)));
  return uint32_t(textures_.size() - 1);
}

void Scene::set_world_texture(uint32_t id, float strength) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("change the world");
  if (id >= textures_.size())
    throw std::invalid_argument("world uses texture " + std::to_string(id) + " but the scene has " +
                                std::to_string(textures_.size()) + " textures");
  lights_.set_world_map(textures_[id], strength);
}

Material Scene::textured_material(uint32_t id, const Vec2& uv, float footprint) const {
  Material m = materials_[id];
  const MaterialTextures& t = material_textures_[id];
  if (t.base_color >= 0) m.base_color = glm::clamp(Vec3(textures_[t.base_color]->lookup(uv, footprint)), Vec3(0.0f), Vec3(1.0f));
  if (t.metallic >= 0) m.metallic = clamp01(blender_luminance(Vec3(textures_[t.metallic]->lookup(uv, footprint))));
  if (t.roughness >= 0) m.roughness = clamp01(blender_luminance(Vec3(textures_[t.roughness]->lookup(uv, footprint))));
  if (t.emission >= 0) m.emission = glm::max(Vec3(textures_[t.emission]->lookup(uv, footprint)), Vec3(0.0f)) * t.emission_strength;
  return m;
}

Vec3 Scene::normal_mapped(uint32_t id, const SurfaceHit& hit, const Vec3& ns, float footprint) const {
  const MaterialTextures& t = material_textures_[id];
  if (t.normal < 0 || glm::dot(hit.tangent, hit.tangent) == 0.0f) return ns;
  const Vec3 tangent = glm::normalize(hit.tangent - glm::dot(hit.tangent, ns) * ns);
  const Vec3 bitangent = hit.bitangent_sign * glm::cross(ns, tangent);
  const Vec3 c = 2.0f * Vec3(textures_[t.normal]->lookup(hit.uv, footprint)) - Vec3(1.0f);
  const Vec3 mapped = c.x * tangent + c.y * bitangent + c.z * ns;
  const Vec3 n = ns + (mapped - ns) * t.normal_strength;
  const float len = glm::length(n);
  return len > 1e-6f && std::isfinite(len) ? n / len : ns;
}

void check_material(const Material& m) {
  if (!is_finite(m.base_color) || !is_finite(m.emission) || !std::isfinite(m.metallic) ||
      !std::isfinite(m.roughness) || !std::isfinite(m.specular) || !std::isfinite(m.specular_tint))
    throw std::invalid_argument("material values must be finite (no NaN or Inf)");
  if (m.metallic < 0.0f || m.metallic > 1.0f || m.roughness < 0.0f || m.roughness > 1.0f)
    throw std::invalid_argument("material metallic and roughness must lie in [0, 1]");
  if (m.specular < 0.0f) throw std::invalid_argument("material specular must be >= 0");
}

uint32_t Scene::add_material(const Material& m, const MaterialTextures& textures) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a material");
  for (int id : {textures.base_color, textures.metallic, textures.roughness, textures.emission, textures.normal})
    if (id < -1 || id >= int(textures_.size()))
      throw std::invalid_argument("material uses texture " + std::to_string(id) + " but the scene has " +
                                  std::to_string(textures_.size()) + " textures");
  if (!std::isfinite(textures.emission_strength) || !std::isfinite(textures.normal_strength))
    throw std::invalid_argument("texture strengths must be finite");
  check_material(m);
  Material clean = m;
  clean.base_color = glm::clamp(m.base_color, Vec3(0.0f), Vec3(1.0f));
  clean.emission = glm::max(m.emission, Vec3(0.0f));
  materials_.push_back(clean);
  material_textures_.push_back(textures);
  emitters_dirty_ = true;
  return uint32_t(materials_.size() - 1);
}

uint32_t Scene::add_mesh(const float* positions, size_t num_vertices, const int64_t* triangles,
                         size_t num_triangles, const float* corner_normals, const int64_t* material_ids,
                         const float* corner_uvs) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a mesh");
  auto mesh = std::make_unique<Mesh>();
  if (num_triangles > 0 && num_vertices == 0) throw std::invalid_argument("mesh has triangles but no vertices");
  if (num_vertices > UINT32_MAX || num_triangles > UINT32_MAX)
    throw std::invalid_argument("mesh is too large (more than 2^32 vertices or triangles)");
  // Copies here and in Embree, corner data, and about 64 bytes of BVH per triangle.
  require_memory(double(num_vertices) * 24.0 +
                     double(num_triangles) * (24.0 + (corner_normals ? 36 : 0) + (corner_uvs ? 24 : 0) + 64.0),
                 "a mesh of " + std::to_string(num_vertices) + " vertices and " + std::to_string(num_triangles) +
                     " triangles");
  mesh->positions.resize(num_vertices);
  for (size_t i = 0; i < num_vertices; ++i) {
    const Vec3 p(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    if (!is_finite(p))
      throw std::invalid_argument("mesh vertex " + std::to_string(i) + " has a NaN or Inf coordinate");
    require_position(p, "mesh vertex " + std::to_string(i));
    mesh->positions[i] = p;
  }
  mesh->triangles.resize(num_triangles);
  for (size_t i = 0; i < num_triangles; ++i) {
    for (int k = 0; k < 3; ++k) {
      const int64_t v = triangles[3 * i + k];
      if (v < 0 || uint64_t(v) >= num_vertices)
        throw std::invalid_argument("triangle " + std::to_string(i) + " uses vertex index " + std::to_string(v) +
                                    ", outside [0, " + std::to_string(num_vertices) + ")");
      mesh->triangles[i][k] = uint32_t(v);
    }
  }
  if (corner_normals) {
    mesh->corner_normals.resize(3 * num_triangles);
    for (size_t i = 0; i < 3 * num_triangles; ++i) {
      const Vec3 n(corner_normals[3 * i], corner_normals[3 * i + 1], corner_normals[3 * i + 2]);
      if (!is_finite(n))
        throw std::invalid_argument("normal of triangle corner " + std::to_string(i) + " has NaN or Inf");
      const float len = glm::length(n);
      mesh->corner_normals[i] = len > 1e-12f ? n / len : Vec3(0.0f);  // zero => flat at that point
    }
  }
  if (corner_uvs) {
    mesh->corner_uvs.resize(3 * num_triangles);
    for (size_t i = 0; i < 3 * num_triangles; ++i) {
      const Vec2 uv(corner_uvs[2 * i], corner_uvs[2 * i + 1]);
      mesh->corner_uvs[i] = std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : Vec2(0.0f);
    }
  }
  mesh->material_ids.assign(num_triangles, 0);
  if (material_ids) {
    for (size_t i = 0; i < num_triangles; ++i) {
      const int64_t m = material_ids[i];
      if (m < 0 || uint64_t(m) >= materials_.size())
        throw std::invalid_argument("triangle " + std::to_string(i) + " uses material " + std::to_string(m) +
                                    " but the scene has " + std::to_string(materials_.size()) + " materials");
      mesh->material_ids[i] = uint32_t(m);
    }
  } else if (num_triangles > 0 && materials_.empty()) {
    throw std::invalid_argument("add a material before adding a mesh");
  }

  const uint32_t id = uint32_t(meshes_.size());
  if (num_triangles > 0) {
    RTCGeometry geom = rtcNewGeometry(device_of(device_), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                           3 * sizeof(float), num_vertices));
    auto* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                              3 * sizeof(uint32_t), num_triangles));
    if (!vb || !ib) {
      rtcReleaseGeometry(geom);
      check_device("allocating mesh buffers");
      throw std::runtime_error("Embree could not allocate mesh buffers");
    }
    std::copy_n(&mesh->positions[0].x, 3 * num_vertices, vb);
    std::copy_n(&mesh->triangles[0].x, 3 * num_triangles, ib);
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(scene_of(scene_), geom, id);
    rtcReleaseGeometry(geom);
    check_device("committing a mesh");
    dirty_ = true;
    emitters_dirty_ = true;
  }
  meshes_.push_back(std::move(mesh));
  return id;
}

size_t Scene::num_triangles() const {
  size_t n = 0;
  for (const auto& m : meshes_) n += m->triangles.size();
  return n;
}

void Scene::commit() {
  if (dirty_) {
    rtcCommitScene(scene_of(scene_));
    check_device("building the BVH");
    dirty_ = false;
  }
  if (emitters_dirty_) {
    build_mesh_light();
    emitters_dirty_ = false;
  }
}

void Scene::build_mesh_light() {
  std::vector<EmissiveTriangle> triangles;
  std::vector<float> power;
  for (auto& mesh : meshes_) {
    mesh->emitter_index.assign(mesh->triangles.size(), -1);
    for (size_t i = 0; i < mesh->triangles.size(); ++i) {
      const uint32_t m = mesh->material_ids[i];
      const MaterialTextures& tex = material_textures_[m];
      // Power estimate for choosing among emitters: a textured emission counts as its strength.
      const float radiance = tex.emission >= 0 ? tex.emission_strength : luminance(materials_[m].emission);
      if (!(radiance > 0.0f)) continue;
      const glm::uvec3 t = mesh->triangles[i];
      EmissiveTriangle e;
      e.p0 = mesh->positions[t.x];
      e.edge1 = mesh->positions[t.y] - e.p0;
      e.edge2 = mesh->positions[t.z] - e.p0;
      const Vec3 cross = glm::cross(e.edge1, e.edge2);
      e.area = 0.5f * glm::length(cross);
      if (!(e.area > 0.0f) || !std::isfinite(e.area)) continue;
      e.normal = cross / (2.0f * e.area);
      const bool has_uv = !mesh->corner_uvs.empty();
      e.uv0 = has_uv ? mesh->corner_uvs[3 * i] : Vec2(0.0f);
      e.uv1 = has_uv ? mesh->corner_uvs[3 * i + 1] : Vec2(0.0f);
      e.uv2 = has_uv ? mesh->corner_uvs[3 * i + 2] : Vec2(0.0f);
      e.material = m;
      mesh->emitter_index[i] = int32_t(triangles.size());
      triangles.push_back(e);
      const float p = e.area * radiance;  // huge but finite inputs may overflow: keep the CDF finite
      power.push_back(std::isfinite(p) ? p : std::numeric_limits<float>::max());
    }
  }
  if (triangles.empty()) {
    lights_.set_mesh_light(std::nullopt);
    return;
  }
  lights_.set_mesh_light(MeshLight(std::move(triangles), power, [this](uint32_t material, const Vec2& uv) {
    return material_textures_[material].emission >= 0 ? textured_material(material, uv).emission
                                                      : materials_[material].emission;
  }));
}

bool Scene::intersect(const Ray& ray, SurfaceHit& hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = ray.origin.x;
  rh.ray.org_y = ray.origin.y;
  rh.ray.org_z = ray.origin.z;
  rh.ray.dir_x = ray.dir.x;
  rh.ray.dir_y = ray.dir.y;
  rh.ray.dir_z = ray.dir.z;
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_of(scene_), &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;

  const Mesh& mesh = *meshes_[rh.hit.geomID];
  const uint32_t prim = rh.hit.primID;
  const glm::uvec3 tri = mesh.triangles[prim];
  const Vec3 &p0 = mesh.positions[tri.x], &p1 = mesh.positions[tri.y], &p2 = mesh.positions[tri.z];
  const float u = rh.hit.u, v = rh.hit.v, w = 1.0f - u - v;
  hit.t = rh.ray.tfar;
  hit.position = w * p0 + u * p1 + v * p2;  // interpolated, more accurate than origin + t * dir
  Vec3 ng = glm::cross(p1 - p0, p2 - p0);
  const float ng_len = glm::length(ng);
  ng = ng_len > 0.0f ? ng / ng_len : -ray.dir;
  hit.geometric_normal = ng;
  hit.shading_normal = ng;
  if (!mesh.corner_normals.empty()) {
    const Vec3 n = w * mesh.corner_normals[3 * prim] + u * mesh.corner_normals[3 * prim + 1] +
                   v * mesh.corner_normals[3 * prim + 2];
    const float len = glm::length(n);
    if (len > 1e-6f && std::isfinite(len)) hit.shading_normal = n / len;
  }
  hit.material = mesh.material_ids[prim];
  hit.emitter = mesh.emitter_index.empty() ? -1 : mesh.emitter_index[prim];
  if (!mesh.corner_uvs.empty()) {
    const Vec2 &t0 = mesh.corner_uvs[3 * prim], &t1 = mesh.corner_uvs[3 * prim + 1], &t2 = mesh.corner_uvs[3 * prim + 2];
    hit.uv = w * t0 + u * t1 + v * t2;
    // dP/du from the triangle's UV parametrisation, for tangent-space normal maps.
    const Vec2 d1 = t1 - t0, d2 = t2 - t0;
    const float det = d1.x * d2.y - d1.y * d2.x;
    const float area2 = glm::length(glm::cross(p1 - p0, p2 - p0));
    hit.uv_per_metre = area2 > 0.0f ? std::sqrt(std::abs(det) / area2) : 0.0f;
    if (std::abs(det) > 1e-12f) {
      const Vec3 dpdu = ((p1 - p0) * d2.y - (p2 - p0) * d1.y) / det;
      const float len = glm::length(dpdu);
      if (len > 0.0f && std::isfinite(len)) {
        hit.tangent = dpdu / len;
        hit.bitangent_sign = det > 0.0f ? 1.0f : -1.0f;
      }
    }
  } else {
    hit.uv = Vec2(0.0f);
    hit.tangent = Vec3(0.0f);
    hit.uv_per_metre = 0.0f;
  }
  return true;
}

bool Scene::occluded(const Vec3& origin, const Vec3& dir, float tmin, float tmax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = dir.x;
  ray.dir_y = dir.y;
  ray.dir_z = dir.z;
  ray.tnear = tmin;
  ray.tfar = tmax;
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(scene_of(scene_), &context, &ray);
  return ray.tfar < 0.0f;
}

}  // namespace torrance
