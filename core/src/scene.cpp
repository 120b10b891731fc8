#include "torrance/scene.h"

#include "torrance/first_failure.h"
#include "torrance/limits.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
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

namespace {
constexpr uint32_t kInstanceBit = 0x80000000u;
constexpr uint32_t kNoOwner = 0xFFFFFFFFu;     // a detached geometry id
constexpr uint32_t kRemoved = 0xFFFFFFFFu;     // Instance::binding once removed
constexpr uint32_t kNoGeometry = 0xFFFFFFFFu;  // Instance::geometry of an empty prototype's instance
}  // namespace

// An object-space mesh (material_ids hold material slots) in its own BVH, built once.
struct Scene::Prototype {
  std::unique_ptr<Mesh> mesh;
  RTCScene scene = nullptr;  // nullptr when the mesh has no triangles
  bool built = false;        // its BVH, built by the first commit() after add_prototype
  Vec3 lo{0.0f}, hi{0.0f};   // bounds of its vertices (both 0 without vertices), for transforms
  Prototype() = default;
  Prototype(const Prototype&) = delete;
  Prototype& operator=(const Prototype&) = delete;
  ~Prototype() {
    if (scene) rtcReleaseScene(scene);
  }
};

// A prototype with one slot -> material table; instances share it (16 bytes per instance).
struct Scene::Binding {
  uint32_t prototype = 0;
  std::vector<uint32_t> materials;    // never empty
  std::vector<int32_t> emitter_rank;  // per prototype triangle: rank among the emissive ones, or -1
  uint32_t num_emissive = 0;          // (both set by build_mesh_light)
  uint32_t material(uint32_t slot) const { return materials[std::min<size_t>(slot, materials.size() - 1)]; }
};

struct Scene::Instance {
  std::array<float, 12> transform;  // row-major 3x4, object to world
  uint32_t binding = kRemoved;
  uint32_t geometry = kNoGeometry;  // Embree geometry id in the top-level scene
  int32_t emitter_base = -1;        // mesh-light index of its first emissive triangle, or -1
  bool hidden = false;              // singular transform: disabled in Embree
};

namespace {
// The corners of a hit triangle in world space; a mirroring instance's corners 1 and 2 are
// swapped (and the barycentrics with them) exactly as the flattening export does, so that the
// geometric normal keeps its side and everything derived from it matches a world-space copy.
struct Corners {
  Vec3 p[3];
  Vec3 n[3];
  Vec2 uv[3];
  bool has_n = false, has_uv = false;
};

double determinant3(const std::array<float, 12>& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], i = m[10];
  return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g);
}

Vec3 transform_point(const std::array<float, 12>& m, const Vec3& p) {
  const double x = p.x, y = p.y, z = p.z;
  return Vec3(float(m[0] * x + m[1] * y + m[2] * z + m[3]), float(m[4] * x + m[5] * y + m[6] * z + m[7]),
              float(m[8] * x + m[9] * y + m[10] * z + m[11]));
}

// Rows of the inverse transpose of the 3x3 part, for normals.
std::array<double, 9> normal_matrix(const std::array<float, 12>& m) {
  const double a = m[0], b = m[1], c = m[2], d = m[4], e = m[5], f = m[6], g = m[8], h = m[9], i = m[10];
  const double inv_det = 1.0 / determinant3(m);
  // inverse(M)^T = cofactor(M) / det(M)
  return {(e * i - f * h) * inv_det, (f * g - d * i) * inv_det, (d * h - e * g) * inv_det,
          (c * h - b * i) * inv_det, (a * i - c * g) * inv_det, (b * g - a * h) * inv_det,
          (b * f - c * e) * inv_det, (c * d - a * f) * inv_det, (a * e - b * d) * inv_det};
}

Vec3 transform_normal(const std::array<double, 9>& n, const Vec3& v) {
  const double x = v.x, y = v.y, z = v.z;
  const double rx = n[0] * x + n[1] * y + n[2] * z, ry = n[3] * x + n[4] * y + n[5] * z,
               rz = n[6] * x + n[7] * y + n[8] * z;
  const Vec3 r{float(rx), float(ry), float(rz)};
  const float len = glm::length(r);
  if (len > 1e-12f && std::isfinite(len)) return r / len;
  // M^-T of a large scale (entries up to the 1e12 check_transform allows) shrinks normals below
  // float's reach before they are normalized: normalize in double instead.
  const double dlen = std::sqrt(rx * rx + ry * ry + rz * rz);
  return dlen > 0.0 && std::isfinite(dlen) ? Vec3(float(rx / dlen), float(ry / dlen), float(rz / dlen)) : Vec3(0.0f);
}
}  // namespace

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
  prototypes_.clear();
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
    mixture_index_.push_back(-1);
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

Vec3 Scene::normal_mapped(uint32_t id, const SurfaceHit& hit, const Vec3& ns, float footprint, float cone_width) const {
  const MaterialTextures& t = material_textures_[id];
  if (t.normal < 0 && t.bump >= 0) return bump_mapped(t, hit, ns, cone_width);
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
      !std::isfinite(m.roughness) || !std::isfinite(m.specular) || !std::isfinite(m.specular_tint) ||
      !std::isfinite(m.ior) || !is_finite(m.specular_tint_color))
    throw std::invalid_argument("material values must be finite (no NaN or Inf)");
  if (m.metallic < 0.0f || m.metallic > 1.0f || m.roughness < 0.0f || m.roughness > 1.0f)
    throw std::invalid_argument("material metallic and roughness must lie in [0, 1]");
  if (m.specular < 0.0f) throw std::invalid_argument("material specular must be >= 0");
  if (!std::isfinite(m.transmission) || !std::isfinite(m.transmission_roughness) || !std::isfinite(m.ior))
    throw std::invalid_argument("material transmission, transmission_roughness and ior must be finite");
  if (m.transmission < 0.0f || m.transmission > 1.0f || m.transmission_roughness < 0.0f ||
      m.transmission_roughness > 1.0f)
    throw std::invalid_argument("material transmission and transmission_roughness must lie in [0, 1]");
  if (!(m.ior > 0.0f) || m.ior > 1000.0f) throw std::invalid_argument("material ior must lie in (0, 1000]");
  if (!std::isfinite(m.alpha) || !is_finite(m.transparent_color))
    throw std::invalid_argument("material alpha and transparent_color must be finite");
  if (m.alpha < 0.0f || m.alpha > 1.0f) throw std::invalid_argument("material alpha must lie in [0, 1]");
  if (glm::any(glm::lessThan(m.specular_tint_color, Vec3(0.0f))))
    throw std::invalid_argument("material specular_tint_color must be >= 0");
}

uint32_t Scene::add_material(const Material& m, const MaterialTextures& textures) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a material");
  for (int id : {textures.base_color, textures.metallic, textures.roughness, textures.emission, textures.normal,
                 textures.bump, textures.alpha})
    if (id < -1 || id >= int(textures_.size()))
      throw std::invalid_argument("material uses texture " + std::to_string(id) + " but the scene has " +
                                  std::to_string(textures_.size()) + " textures");
  if (!std::isfinite(textures.emission_strength) || !std::isfinite(textures.normal_strength) ||
      !std::isfinite(textures.bump_strength) || !std::isfinite(textures.bump_distance))
    throw std::invalid_argument("texture strengths must be finite");
  check_material(m);
  Material clean = m;
  clean.base_color = glm::clamp(m.base_color, Vec3(0.0f), Vec3(1.0f));
  clean.emission = glm::max(m.emission, Vec3(0.0f));
  clean.transparent_color = glm::clamp(m.transparent_color, Vec3(0.0f), Vec3(1.0f));
  materials_.push_back(clean);
  material_textures_.push_back(textures);
  mixture_index_.push_back(-1);
  emitters_dirty_ = true;
  return uint32_t(materials_.size() - 1);
}

namespace {
// Runs body(i) for i in [0, n) on all cores; body throws std::invalid_argument for a bad
// element. The error thrown is the first bad element's, as a serial loop would throw it.
template <typename Body>
void check_each(size_t n, const Body& body) {
  const size_t bad = first_failure(n, [&](size_t i) {
    try {
      body(i);
      return false;
    } catch (const std::invalid_argument&) {
      return true;
    }
  });
  if (bad < n) body(bad);
}
}  // namespace

std::unique_ptr<Scene::Mesh> Scene::make_mesh(const float* positions, size_t num_vertices, const int64_t* triangles,
                                              size_t num_triangles, const float* corner_normals,
                                              const int64_t* material_ids, const float* corner_uvs, bool slots) const {
  auto mesh = std::make_unique<Mesh>();
  if (num_triangles > 0 && num_vertices == 0) throw std::invalid_argument("mesh has triangles but no vertices");
  if (num_vertices > UINT32_MAX || num_triangles > UINT32_MAX)
    throw std::invalid_argument("mesh is too large (more than 2^32 vertices or triangles)");
  // Copies here and in Embree, corner data, and about 64 bytes of BVH per triangle.
  require_memory(double(num_vertices) * 24.0 +
                     double(num_triangles) * (24.0 + (corner_normals ? 36 : 0) + (corner_uvs ? 24 : 0) + 64.0),
                 std::string(slots ? "a prototype of " : "a mesh of ") + std::to_string(num_vertices) +
                     " vertices and " + std::to_string(num_triangles) + " triangles");
  // One extra vertex of capacity: Embree shares the buffer and reads its last vertex with a
  // 16-byte load (rtcSetSharedGeometryBuffer).
  mesh->positions.reserve(num_vertices + 1);
  mesh->positions.resize(num_vertices);
  const char* vertex_kind = slots ? "prototype vertex " : "mesh vertex ";
  check_each(num_vertices, [&](size_t i) {
    const Vec3 p(positions[3 * i], positions[3 * i + 1], positions[3 * i + 2]);
    if (!is_finite(p))
      throw std::invalid_argument(vertex_kind + std::to_string(i) + " has a NaN or Inf coordinate");
    if (std::abs(p.x) > kMaxCoordinate || std::abs(p.y) > kMaxCoordinate || std::abs(p.z) > kMaxCoordinate)
      require_position(p, vertex_kind + std::to_string(i));  // throws its message
    mesh->positions[i] = p;
  });
  mesh->triangles.resize(num_triangles);
  check_each(num_triangles, [&](size_t i) {
    for (int k = 0; k < 3; ++k) {
      const int64_t v = triangles[3 * i + k];
      if (v < 0 || uint64_t(v) >= num_vertices)
        throw std::invalid_argument("triangle " + std::to_string(i) + " uses vertex index " + std::to_string(v) +
                                    ", outside [0, " + std::to_string(num_vertices) + ")");
      mesh->triangles[i][k] = uint32_t(v);
    }
  });
  if (corner_normals) {
    mesh->corner_normals.resize(3 * num_triangles);
    check_each(3 * num_triangles, [&](size_t i) {
      const Vec3 n(corner_normals[3 * i], corner_normals[3 * i + 1], corner_normals[3 * i + 2]);
      if (!is_finite(n))
        throw std::invalid_argument("normal of triangle corner " + std::to_string(i) + " has NaN or Inf");
      const float len = glm::length(n);
      mesh->corner_normals[i] = len > 1e-12f ? n / len : Vec3(0.0f);  // zero => flat at that point
    });
  }
  if (corner_uvs) {
    mesh->corner_uvs.resize(3 * num_triangles);
    check_each(3 * num_triangles, [&](size_t i) {
      const Vec2 uv(corner_uvs[2 * i], corner_uvs[2 * i + 1]);
      mesh->corner_uvs[i] = std::isfinite(uv.x) && std::isfinite(uv.y) ? uv : Vec2(0.0f);
    });
  }
  mesh->material_ids.assign(num_triangles, 0);
  if (material_ids) {
    check_each(num_triangles, [&](size_t i) {
      const int64_t m = material_ids[i];
      if (slots ? (m < 0 || m > INT32_MAX) : (m < 0 || uint64_t(m) >= materials_.size()))
        throw std::invalid_argument(slots ? "triangle " + std::to_string(i) + " uses material slot " +
                                                std::to_string(m) + "; slots must be >= 0"
                                          : "triangle " + std::to_string(i) + " uses material " + std::to_string(m) +
                                                " but the scene has " + std::to_string(materials_.size()) +
                                                " materials");
      mesh->material_ids[i] = uint32_t(m);
    });
  } else if (!slots && num_triangles > 0 && materials_.empty()) {
    throw std::invalid_argument("add a material before adding a mesh");
  }
  return mesh;
}

static_assert(sizeof(Vec3) == 3 * sizeof(float) && sizeof(glm::uvec3) == 3 * sizeof(uint32_t),
              "Embree shares the mesh arrays as FLOAT3 and UINT3");

void* Scene::new_triangle_geometry(const Mesh& mesh) const {
  // Embree reads the mesh's own arrays (no copy: 180 MB and 0.1 s on 10 M triangles); they
  // live as long as the scene and never change. positions has one vertex of spare capacity
  // for Embree's 16-byte loads (make_mesh).
  RTCGeometry geom = rtcNewGeometry(device_of(device_), RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, mesh.positions.data(), 0,
                             sizeof(Vec3), mesh.positions.size());
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, mesh.triangles.data(), 0,
                             sizeof(glm::uvec3), mesh.triangles.size());
  rtcCommitGeometry(geom);
  if (!embree_error_.empty()) {
    rtcReleaseGeometry(geom);
    check_device("sharing mesh buffers");
  }
  return geom;
}

uint32_t Scene::add_mesh(const float* positions, size_t num_vertices, const int64_t* triangles,
                         size_t num_triangles, const float* corner_normals, const int64_t* material_ids,
                         const float* corner_uvs) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a mesh");
  auto mesh = make_mesh(positions, num_vertices, triangles, num_triangles, corner_normals, material_ids, corner_uvs,
                        false);
  const uint32_t id = uint32_t(meshes_.size());
  if (num_triangles > 0) {
    RTCGeometry geom = static_cast<RTCGeometry>(new_triangle_geometry(*mesh));
    const uint32_t geom_id = uint32_t(geometry_owner_.size());
    rtcAttachGeometryByID(scene_of(scene_), geom, geom_id);
    rtcReleaseGeometry(geom);
    check_device("committing a mesh");
    geometry_owner_.push_back(id);
    dirty_ = true;
    emitters_dirty_ = true;
  }
  meshes_.push_back(std::move(mesh));
  return id;
}

uint32_t Scene::add_prototype(const float* positions, size_t num_vertices, const int64_t* triangles,
                              size_t num_triangles, const float* corner_normals, const int64_t* slots,
                              const float* corner_uvs) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a prototype");
  auto prototype = std::make_unique<Prototype>();
  prototype->mesh = make_mesh(positions, num_vertices, triangles, num_triangles, corner_normals, slots, corner_uvs,
                              true);
  if (num_vertices > 0) {
    prototype->lo = prototype->hi = prototype->mesh->positions[0];
    for (const Vec3& p : prototype->mesh->positions) {
      prototype->lo = glm::min(prototype->lo, p);
      prototype->hi = glm::max(prototype->hi, p);
    }
  }
  if (num_triangles > 0) {
    prototype->scene = rtcNewScene(device_of(device_));
    rtcSetSceneFlags(prototype->scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(prototype->scene, RTC_BUILD_QUALITY_MEDIUM);
    RTCGeometry geom = static_cast<RTCGeometry>(new_triangle_geometry(*prototype->mesh));
    rtcAttachGeometryByID(prototype->scene, geom, 0);
    rtcReleaseGeometry(geom);
    check_device("adding a prototype's mesh");
    // Its BVH is built by commit(), on the thread that renders, not on the caller's (Blender's
    // main thread for the viewport); once, whatever happens to its instances later.
    dirty_ = true;
  }
  prototypes_.push_back(std::move(prototype));
  return uint32_t(prototypes_.size() - 1);
}

namespace {
std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}
}  // namespace

// What an instance's matrix may do (issue 15's bounds, for instancing): every entry finite and
// within kMaxCoordinate (1e12) -- the translation is the object's origin, a column of the 3x3
// part the world image of a unit object axis -- and the prototype's vertex bounds, transformed,
// within 1e12 of the origin too, as add_mesh requires of world-space vertices. So hit points and
// their offsets stay valid rays for Embree, whatever the matrix.
void Scene::check_transform(const float* m, uint32_t prototype, const std::string& which) const {
  for (int k = 0; k < 12; ++k)
    if (!std::isfinite(m[k])) throw std::invalid_argument(which + " has a NaN or Inf entry");
  for (int k = 0; k < 12; ++k)
    if (std::abs(m[k]) > kMaxCoordinate)
      throw std::invalid_argument(which + " has an entry of " + number(m[k]) + " (row " + std::to_string(k / 4) +
                                  ", column " + std::to_string(k % 4) + "); entries must lie within 1e12");
  const Prototype& proto = *prototypes_[prototype];
  if (proto.mesh->positions.empty()) return;
  for (int r = 0; r < 3; ++r) {  // the exact world bounds of the object-space box, row by row
    double lo = m[4 * r + 3], hi = lo;
    for (int c = 0; c < 3; ++c) {
      const double a = double(m[4 * r + c]) * proto.lo[c], b = double(m[4 * r + c]) * proto.hi[c];
      lo += std::min(a, b);
      hi += std::max(a, b);
    }
    if (std::max(std::abs(lo), std::abs(hi)) > double(kMaxCoordinate))
      throw std::invalid_argument(which + " places prototype " + std::to_string(prototype) + " beyond 1e12 from " +
                                  "the origin (world " + "xyz"[r] + " from " + number(lo) + " to " + number(hi) + ")");
  }
}

namespace {

bool singular(const std::array<float, 12>& m) {
  // Zero scale in some direction (a common way of hiding instances): nothing to trace.
  const double det = determinant3(m);
  return !(std::abs(det) > 1e-30) || !std::isfinite(1.0 / det);
}
}  // namespace

// Sets the instance's matrix, in Embree too, and hides it while the matrix is singular.
void Scene::place_instance(Instance& instance, const float* transform) {
  std::copy_n(transform, 12, instance.transform.begin());
  const bool was_hidden = instance.hidden;
  instance.hidden = singular(instance.transform);
  if (instance.hidden != was_hidden) hidden_instances_ += instance.hidden ? 1 : size_t(-1);
  if (instance.geometry == kNoGeometry) return;
  RTCGeometry geom = rtcGetGeometry(scene_of(scene_), instance.geometry);
  if (!instance.hidden) {
    rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, instance.transform.data());
    rtcCommitGeometry(geom);
  }
  if (instance.hidden != was_hidden) {
    if (instance.hidden)
      rtcDisableGeometry(geom);
    else
      rtcEnableGeometry(geom);
  }
  if (bindings_[instance.binding].num_emissive > 0) emitters_dirty_ = true;
  dirty_ = true;
}

uint32_t Scene::add_instances(uint32_t prototype, const float* transforms, size_t count, const int64_t* materials,
                              size_t table_size, bool per_instance_tables) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add instances");
  if (prototype >= prototypes_.size())
    throw std::invalid_argument("prototype " + std::to_string(prototype) + " does not exist (the scene has " +
                                std::to_string(prototypes_.size()) + " prototypes)");
  if (table_size == 0) throw std::invalid_argument("the material table of instances must not be empty");
  const size_t num_tables = per_instance_tables ? count : (count > 0 ? 1 : 0);
  // Per instance its record, an Embree instance geometry and its share of the top-level BVH
  // (~512 bytes); per table entry the binding's copy and its key (8 bytes).
  require_memory(double(count) * 512.0 + double(num_tables) * double(table_size) * 8.0,
                 std::to_string(count) + " instances" +
                     (per_instance_tables ? " with material tables of " + std::to_string(table_size) + " entries"
                                          : std::string()));
  for (size_t i = 0; i < num_tables * table_size; ++i)
    if (materials[i] < 0 || uint64_t(materials[i]) >= materials_.size())
      throw std::invalid_argument("material table entry " + std::to_string(i) + " is material " +
                                  std::to_string(materials[i]) + " but the scene has " +
                                  std::to_string(materials_.size()) + " materials");
  for (size_t i = 0; i < count; ++i) check_transform(transforms + 12 * i, prototype, "transform " + std::to_string(i));
  if (instances_.size() + count >= kInstanceBit || geometry_owner_.size() + count >= kInstanceBit)
    throw std::invalid_argument("too many instances (2^31 at most)");

  // The distinct tables, each a binding shared by all instances using it.
  std::vector<uint32_t> binding_of(num_tables);
  std::vector<uint32_t> key(1 + table_size);
  key[0] = prototype;
  for (size_t t = 0; t < num_tables; ++t) {
    for (size_t k = 0; k < table_size; ++k) key[1 + k] = uint32_t(materials[t * table_size + k]);
    auto [it, inserted] = binding_ids_.try_emplace(key, uint32_t(bindings_.size()));
    if (inserted) {
      Binding b;
      b.prototype = prototype;
      b.materials.assign(key.begin() + 1, key.end());
      bindings_.push_back(std::move(b));
    }
    binding_of[t] = it->second;
  }

  const Prototype& proto = *prototypes_[prototype];
  const uint32_t first = uint32_t(instances_.size());
  instances_.reserve(instances_.size() + count);
  if (proto.scene) geometry_owner_.reserve(geometry_owner_.size() + count);
  for (size_t i = 0; i < count; ++i) {
    Instance inst;
    inst.binding = binding_of[per_instance_tables ? i : 0];
    std::copy_n(transforms + 12 * i, 12, inst.transform.begin());
    inst.hidden = singular(inst.transform);
    if (proto.scene) {
      RTCGeometry geom = rtcNewGeometry(device_of(device_), RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(geom, proto.scene);
      rtcSetGeometryTimeStepCount(geom, 1);
      if (!inst.hidden) rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, inst.transform.data());
      rtcCommitGeometry(geom);
      inst.geometry = uint32_t(geometry_owner_.size());
      rtcAttachGeometryByID(scene_of(scene_), geom, inst.geometry);
      if (inst.hidden) rtcDisableGeometry(geom);
      rtcReleaseGeometry(geom);
      geometry_owner_.push_back(uint32_t(instances_.size()) | kInstanceBit);
    }
    hidden_instances_ += inst.hidden;
    instances_.push_back(inst);
  }
  check_device("adding instances");
  live_instances_ += count;
  dirty_ = true;
  emitters_dirty_ = true;
  return first;
}

const Scene::Instance& Scene::live_instance(int64_t id, const char* during) const {
  if (id < 0 || uint64_t(id) >= instances_.size() || instances_[size_t(id)].binding == kRemoved)
    throw std::invalid_argument(std::string(during) + ": instance " + std::to_string(id) +
                                (id >= 0 && uint64_t(id) < instances_.size() ? " was removed"
                                                                              : " does not exist"));
  return instances_[size_t(id)];
}

void Scene::set_instance_transforms(const int64_t* ids, const float* transforms, size_t count) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("move instances");
  for (size_t i = 0; i < count; ++i) {
    const Instance& inst = live_instance(ids[i], "set_instance_transforms");
    check_transform(transforms + 12 * i, bindings_[inst.binding].prototype,
                    "transform " + std::to_string(i) + " (instance " + std::to_string(ids[i]) + ")");
  }
  for (size_t i = 0; i < count; ++i) place_instance(instances_[size_t(ids[i])], transforms + 12 * i);
  check_device("moving instances");
}

void Scene::remove_instances(const int64_t* ids, size_t count) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("remove instances");
  for (size_t i = 0; i < count; ++i) live_instance(ids[i], "remove_instances");
  for (size_t i = 0; i < count; ++i) {
    Instance& inst = instances_[size_t(ids[i])];
    if (inst.binding == kRemoved) continue;  // listed twice
    if (inst.geometry != kNoGeometry) {
      rtcDetachGeometry(scene_of(scene_), inst.geometry);
      geometry_owner_[inst.geometry] = kNoOwner;
    }
    if (bindings_[inst.binding].num_emissive > 0) emitters_dirty_ = true;
    hidden_instances_ -= inst.hidden;
    inst.binding = kRemoved;
    inst.emitter_base = -1;
    --live_instances_;
  }
  check_device("removing instances");
  dirty_ = true;
}

size_t Scene::num_material_tables() const { return bindings_.size(); }

size_t Scene::num_triangles() const {
  size_t n = 0;
  for (const auto& m : meshes_) n += m->triangles.size();
  for (const Instance& inst : instances_)
    if (inst.binding != kRemoved && !inst.hidden)
      n += prototypes_[bindings_[inst.binding].prototype]->mesh->triangles.size();
  return n;
}

void Scene::commit() {
  if (dirty_) {
    for (const auto& prototype : prototypes_)
      if (prototype->scene && !prototype->built) {
        rtcCommitScene(prototype->scene);  // before the instances' scene: Embree needs it built
        check_device("building a prototype's BVH");
        prototype->built = true;
      }
    rtcCommitScene(scene_of(scene_));
    check_device("building the BVH");
    dirty_ = false;
  }
  if (emitters_dirty_) {
    build_mesh_light();
    emitters_dirty_ = false;
  }
}

// A triangle of a world-space mesh as Corners.
static Corners mesh_corners(const std::vector<Vec3>& positions, const glm::uvec3& tri, const Vec3* normals,
                            const Vec2* uvs) {
  Corners c;
  for (int k = 0; k < 3; ++k) {
    c.p[k] = positions[tri[k]];
    if (normals) c.n[k] = normals[k];
    if (uvs) c.uv[k] = uvs[k];
  }
  c.has_n = normals != nullptr;
  c.has_uv = uvs != nullptr;
  return c;
}

// A prototype triangle placed by an instance's matrix: what the flattening export would have
// added as a world-space mesh (positions by M, normals by M^-T, corners 1 and 2 swapped when M
// mirrors). Returns whether they were swapped.
static bool instance_corners(const std::vector<Vec3>& positions, const glm::uvec3& tri, const Vec3* normals,
                             const Vec2* uvs, const std::array<float, 12>& m, Corners& c) {
  c = mesh_corners(positions, tri, normals, uvs);
  for (int k = 0; k < 3; ++k) c.p[k] = transform_point(m, c.p[k]);
  if (normals) {
    const std::array<double, 9> nm = normal_matrix(m);
    for (int k = 0; k < 3; ++k) c.n[k] = transform_normal(nm, c.n[k]);
  }
  const bool mirrored = determinant3(m) < 0.0;
  if (mirrored) {
    std::swap(c.p[1], c.p[2]);
    std::swap(c.n[1], c.n[2]);
    std::swap(c.uv[1], c.uv[2]);
  }
  return mirrored;
}

void Scene::build_mesh_light() {
  std::vector<EmissiveTriangle> triangles;
  std::vector<float> power;
  // Power estimate for choosing among emitters: a textured emission counts as its strength.
  // Once per material: the scans below look it up per triangle (10 M triangles: 0.2 s before).
  std::vector<float> material_radiance(materials_.size());
  bool any_emissive = false;
  for (size_t m = 0; m < materials_.size(); ++m) {
    const MaterialTextures& tex = material_textures_[m];
    material_radiance[m] = tex.emission >= 0 ? tex.emission_strength : luminance(materials_[m].emission);
    any_emissive |= material_radiance[m] > 0.0f;
  }
  auto radiance_of = [&material_radiance](uint32_t m) { return material_radiance[m]; };
  auto add = [&](const Corners& c, uint32_t material, float radiance) {
    EmissiveTriangle e;
    e.p0 = c.p[0];
    e.edge1 = c.p[1] - e.p0;
    e.edge2 = c.p[2] - e.p0;
    const Vec3 cross = glm::cross(e.edge1, e.edge2);
    e.area = 0.5f * glm::length(cross);
    if (!(e.area > 0.0f) || !std::isfinite(e.area)) return false;
    e.normal = cross / (2.0f * e.area);
    e.uv0 = c.uv[0];
    e.uv1 = c.uv[1];
    e.uv2 = c.uv[2];
    e.material = material;
    triangles.push_back(e);
    const float p = e.area * radiance;  // huge but finite inputs may overflow: keep the CDF finite
    power.push_back(std::isfinite(p) ? p : std::numeric_limits<float>::max());
    return true;
  };
  for (auto& mesh : meshes_) {
    mesh->emitter_index.clear();  // none emits (intersect reads an empty table as -1)
    if (!any_emissive) continue;
    mesh->emitter_index.assign(mesh->triangles.size(), -1);
    const bool has_uv = !mesh->corner_uvs.empty();
    for (size_t i = 0; i < mesh->triangles.size(); ++i) {
      const uint32_t m = mesh->material_ids[i];
      const float radiance = radiance_of(m);
      if (!(radiance > 0.0f)) continue;
      const Corners c = mesh_corners(mesh->positions, mesh->triangles[i], nullptr,
                                     has_uv ? &mesh->corner_uvs[3 * i] : nullptr);
      if (add(c, m, radiance)) mesh->emitter_index[i] = int32_t(triangles.size() - 1);
    }
  }
  // Instances: a prototype triangle emits under a table if its material does and it has an area
  // in object space; each visible instance of an emissive binding adds those triangles in world
  // space, consecutively from its emitter_base, in the order of the prototype.
  for (Binding& b : bindings_) {
    const Mesh& mesh = *prototypes_[b.prototype]->mesh;
    b.emitter_rank.clear();
    b.num_emissive = 0;
    if (!any_emissive) continue;
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      const glm::uvec3 t = mesh.triangles[i];
      const float area = glm::length(glm::cross(mesh.positions[t.y] - mesh.positions[t.x],
                                                mesh.positions[t.z] - mesh.positions[t.x]));
      if (radiance_of(b.material(mesh.material_ids[i])) > 0.0f && area > 0.0f && std::isfinite(area)) {
        if (b.emitter_rank.empty()) b.emitter_rank.assign(mesh.triangles.size(), -1);
        b.emitter_rank[i] = int32_t(b.num_emissive++);
      }
    }
  }
  // Every visible instance repeats its binding's emissive triangles in world space: check what
  // that takes (here, in the light and its CDF) before allocating it.
  double num_emissive = double(triangles.size());
  for (const Instance& inst : instances_)
    if (inst.binding != kRemoved && !inst.hidden) num_emissive += bindings_[inst.binding].num_emissive;
  require_memory(num_emissive * 2.0 * double(sizeof(EmissiveTriangle) + 2 * sizeof(float)),
                 "the mesh light of " + std::to_string(size_t(num_emissive)) +
                     " emissive triangles (instances included)");
  for (Instance& inst : instances_) {
    inst.emitter_base = -1;
    if (inst.binding == kRemoved || inst.hidden || bindings_[inst.binding].num_emissive == 0) continue;
    const Binding& b = bindings_[inst.binding];
    const Mesh& mesh = *prototypes_[b.prototype]->mesh;
    const bool has_uv = !mesh.corner_uvs.empty();
    inst.emitter_base = int32_t(triangles.size());
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      if (b.emitter_rank[i] < 0) continue;
      const uint32_t m = b.material(mesh.material_ids[i]);
      Corners c;
      instance_corners(mesh.positions, mesh.triangles[i], nullptr, has_uv ? &mesh.corner_uvs[3 * i] : nullptr,
                       inst.transform, c);
      if (!add(c, m, radiance_of(m))) {
        // Only a scale near float underflow gets here: keep the numbering, never choose it.
        EmissiveTriangle e{};
        e.p0 = c.p[0];
        e.normal = Vec3(0, 0, 1);
        e.area = 1.0f;
        e.material = m;
        triangles.push_back(e);
        power.push_back(0.0f);
      }
    }
  }
  double total = 0.0;
  for (float w : power) total += w;
  if (triangles.empty() || !(total > 0.0)) {
    lights_.set_mesh_light(std::nullopt);
    for (auto& mesh : meshes_) mesh->emitter_index.clear();  // no emitter: read as -1
    for (Instance& inst : instances_) inst.emitter_base = -1;
    return;
  }
  lights_.set_mesh_light(MeshLight(std::move(triangles), power, [this](uint32_t material, const Vec2& uv) {
    return emission_at(material, uv);
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

  const uint32_t prim = rh.hit.primID;
  float u = rh.hit.u, v = rh.hit.v;
  Corners c;
  if (rh.hit.instID[0] == RTC_INVALID_GEOMETRY_ID) {
    const Mesh& mesh = *meshes_[geometry_owner_[rh.hit.geomID]];
    c = mesh_corners(mesh.positions, mesh.triangles[prim],
                     mesh.corner_normals.empty() ? nullptr : &mesh.corner_normals[3 * prim],
                     mesh.corner_uvs.empty() ? nullptr : &mesh.corner_uvs[3 * prim]);
    hit.material = mesh.material_ids[prim];
    hit.emitter = mesh.emitter_index.empty() ? -1 : mesh.emitter_index[prim];
  } else {
    const Instance& inst = instances_[geometry_owner_[rh.hit.instID[0]] & ~kInstanceBit];
    const Binding& b = bindings_[inst.binding];
    const Mesh& mesh = *prototypes_[b.prototype]->mesh;
    if (instance_corners(mesh.positions, mesh.triangles[prim],
                         mesh.corner_normals.empty() ? nullptr : &mesh.corner_normals[3 * prim],
                         mesh.corner_uvs.empty() ? nullptr : &mesh.corner_uvs[3 * prim], inst.transform, c))
      std::swap(u, v);
    hit.material = b.material(mesh.material_ids[prim]);
    hit.emitter = inst.emitter_base >= 0 && b.emitter_rank[prim] >= 0 ? inst.emitter_base + b.emitter_rank[prim] : -1;
  }

  const Vec3 &p0 = c.p[0], &p1 = c.p[1], &p2 = c.p[2];
  const float w = 1.0f - u - v;
  hit.t = rh.ray.tfar;
  hit.position = w * p0 + u * p1 + v * p2;  // interpolated, more accurate than origin + t * dir
  Vec3 ng = glm::cross(p1 - p0, p2 - p0);
  const float ng_len = glm::length(ng);
  ng = ng_len > 0.0f ? ng / ng_len : -ray.dir;
  hit.geometric_normal = ng;
  hit.shading_normal = ng;
  if (c.has_n) {
    const Vec3 n = w * c.n[0] + u * c.n[1] + v * c.n[2];
    const float len = glm::length(n);
    if (len > 1e-6f && std::isfinite(len)) hit.shading_normal = n / len;
  }
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
