#include "torrance/scene/scene.h"

#include "scene/embree_rays.h"
#include "scene/ray_queries.h"
#include "scene/scene_internal.h"

#include "torrance/util/first_failure.h"
#include "torrance/util/limits.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace torrance {

using namespace scene_detail;

void embree_error_callback(void* user, int code, const char* message) {
  auto* scene = static_cast<Scene*>(user);
  scene->embree_error_ = "Embree error " + std::to_string(code) + ": " + (message ? message : "");
}

namespace {
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
  local_scenes_.reset();
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

void Scene::set_world_program(uint32_t program, int radiance_register, int resolution, const SunGuide& sun) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("change the world");
  if (program >= programs_.size())
    throw std::invalid_argument("the world uses shader program " + std::to_string(program) + " but the scene has " +
                                std::to_string(programs_.size()));
  lights_.set_world_shader(std::make_shared<EmissionShader>(programs_[program], radiance_register, textures_),
                           resolution, sun);
}

void Scene::set_light_program(uint32_t program, int radiance_register) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("change a light");
  if (program >= programs_.size())
    throw std::invalid_argument("the light uses shader program " + std::to_string(program) + " but the scene has " +
                                std::to_string(programs_.size()));
  lights_.set_last_light_shader(std::make_shared<EmissionShader>(programs_[program], radiance_register, textures_));
}

uint32_t Scene::add_shader_program(ShaderProgram program) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("add a shader program");
  programs_.push_back(std::move(program));
  return uint32_t(programs_.size() - 1);
}

void Scene::apply_textures(uint32_t id, const ShaderGlobals& g, Material& m, glm::vec4* regs) const {
  const Vec2& uv = g.uv;
  const float footprint = g.footprint;
  const MaterialTextures& t = material_textures_[id];
  if (t.base_color >= 0) m.base_color = glm::clamp(Vec3(textures_[t.base_color]->lookup(uv, footprint)), Vec3(0.0f), Vec3(1.0f));
  if (t.metallic >= 0) m.metallic = clamp01(blender_luminance(Vec3(textures_[t.metallic]->lookup(uv, footprint))));
  if (t.roughness >= 0) m.roughness = clamp01(blender_luminance(Vec3(textures_[t.roughness]->lookup(uv, footprint))));
  // Emission as Cycles' closure weight: Color x Strength, signed (negative emission takes light away).
  if (t.emission >= 0) m.emission = Vec3(textures_[t.emission]->lookup(uv, footprint)) * t.emission_strength;
  if (t.program.any()) apply_program(t, g, m, regs);
}

void Scene::apply_program(const MaterialTextures& t, const ShaderGlobals& g, Material& m, glm::vec4* out) const {
  const ShaderOutputs& o = t.program;
  std::array<glm::vec4, ShaderProgram::kMaxRegisters> local;
  glm::vec4* regs = out ? out : local.data();
  run_shader_program(uint32_t(o.program), g, regs);
  if (o.base_color >= 0) m.base_color = glm::clamp(Vec3(regs[size_t(o.base_color)]), Vec3(0.0f), Vec3(1.0f));
  if (o.metallic >= 0) m.metallic = clamp01(regs[size_t(o.metallic)].x);
  if (o.roughness >= 0) m.roughness = clamp01(regs[size_t(o.roughness)].x);
  if (o.emission >= 0) m.emission = Vec3(regs[size_t(o.emission)]) * t.emission_strength;  // signed, as Cycles
  if (o.transmission >= 0) m.transmission = clamp01(regs[size_t(o.transmission)].x);
  if (o.coat_weight >= 0) m.coat_weight = std::max(regs[size_t(o.coat_weight)].x, 0.0f);
  if (o.coat_roughness >= 0) m.coat_roughness = clamp01(regs[size_t(o.coat_roughness)].x);
  if (o.coat_ior >= 0) m.coat_ior = std::max(regs[size_t(o.coat_ior)].x, 1.0f);
  if (o.coat_tint >= 0) m.coat_tint = glm::max(Vec3(regs[size_t(o.coat_tint)]), Vec3(0.0f));
  if (o.sheen_weight >= 0) m.sheen_weight = std::max(regs[size_t(o.sheen_weight)].x, 0.0f);
  if (o.sheen_roughness >= 0) m.sheen_roughness = clamp01(regs[size_t(o.sheen_roughness)].x);
  if (o.sheen_tint >= 0) {
    m.sheen_tint = clamp01(regs[size_t(o.sheen_tint)].x);
    m.sheen_tint_color = glm::max(Vec3(regs[size_t(o.sheen_tint)]), Vec3(0.0f));
  }
  if (o.anisotropy >= 0) m.anisotropy = std::clamp(regs[size_t(o.anisotropy)].x, -1.0f, 1.0f);
  if (o.anisotropic_rotation >= 0) m.anisotropic_rotation = regs[size_t(o.anisotropic_rotation)].x;
  if (o.tangent >= 0) m.tangent = Vec3(regs[size_t(o.tangent)]);
  if (o.subsurface >= 0) m.subsurface = clamp01(regs[size_t(o.subsurface)].x);
  if (o.subsurface_radius >= 0) m.subsurface_radius = glm::max(Vec3(regs[size_t(o.subsurface_radius)]), Vec3(0.0f));
  if (o.subsurface_color >= 0)
    m.subsurface_color = glm::clamp(Vec3(regs[size_t(o.subsurface_color)]), Vec3(0.0f), Vec3(1.0f));
  // Cycles: max(thickness, 1e-5) and max(IOR, 1e-5); a NaN is no film.
  if (o.thin_film_thickness >= 0) {
    const float d = regs[size_t(o.thin_film_thickness)].x;
    m.thin_film_thickness = std::isfinite(d) ? d : 0.0f;
  }
  if (o.thin_film_ior >= 0) {
    const float n = regs[size_t(o.thin_film_ior)].x;
    m.thin_film_ior = std::isfinite(n) ? std::max(n, 1e-5f) : 1.33f;
  }
  if (o.dispersion >= 0) {  // a NaN or a negative quotient: none
    const float v = regs[size_t(o.dispersion)].x;
    m.dispersion = std::isfinite(v) ? std::max(v, 0.0f) : 0.0f;
  }
  if (o.specular >= 0) m.specular = std::max(regs[size_t(o.specular)].x, 0.0f);
  if (o.ior >= 0) m.ior = std::clamp(regs[size_t(o.ior)].x, 1e-5f, 1000.0f);
  if (o.diffuse_roughness >= 0) m.diffuse_roughness = clamp01(regs[size_t(o.diffuse_roughness)].x);
  if (o.transmission_roughness >= 0)
    m.transmission_roughness = clamp01(regs[size_t(o.transmission_roughness)].x);
  if (o.specular_tint_color >= 0)
    m.specular_tint_color = glm::max(Vec3(regs[size_t(o.specular_tint_color)]), Vec3(0.0f));
  if (o.specular_tint >= 0) m.specular_tint = clamp01(regs[size_t(o.specular_tint)].x);
  if (o.portal_position >= 0) {
    m.portal_position = Vec3(regs[size_t(o.portal_position)]);
    m.portal_at_hit = false;
  }
  if (o.portal_direction >= 0) m.portal_direction = Vec3(regs[size_t(o.portal_direction)]);
}

Vec3 Scene::normal_mapped(uint32_t id, const SurfaceHit& hit, const Vec3& ns, const ShaderGlobals& g,
                          Vec3* surface_normal, const glm::vec4* program_regs) const {
  const MaterialTextures& t = material_textures_[id];
  // Cycles maps normals facing the viewer; the result goes back to the mesh's winding.
  const float side = g.backfacing ? -1.0f : 1.0f;
  const Vec3 n = side * ns;
  Vec3 out = n;
  if (t.program.normal >= 0) {
    std::array<glm::vec4, ShaderProgram::kMaxRegisters> local;
    const glm::vec4* regs = program_regs;
    if (!regs) {
      ShaderGlobals at = g;
      at.normal = n;
      run_shader_program(uint32_t(t.program.program), at, local.data());
      regs = local.data();
    }
    auto unit = [&](int16_t r) {
      const Vec3 v = Vec3(regs[size_t(r)]);
      const float len = glm::length(v);
      return len > 1e-6f && std::isfinite(len) ? v / len : n;
    };
    out = unit(t.program.normal);
    if (surface_normal && t.program.surface_normal >= 0) *surface_normal = side * unit(t.program.surface_normal);
  } else if (t.normal >= 0) {
    const Vec3 c = Vec3(textures_[t.normal]->lookup(hit.uv, g.footprint));
    out = side * shader::tangent_normal_map(c, ns, hit.tangent, hit.bitangent_sign, t.normal_strength);
  } else if (t.bump >= 0) {
    out = bump_mapped(t, hit, n, g);
  }
  return side * out;
}

bool Scene::coated(uint32_t i) const {
  auto own = [&](uint32_t m) { return materials_[m].coat_weight > 0.0f || material_textures_[m].program.coat_weight >= 0; };
  if (const Mixture* m = mixture(i)) {
    for (const MixtureComponent& c : m->components)
      if (own(c.material)) return true;
    return false;
  }
  return own(i);
}

bool Scene::coat_normal(uint32_t i, const ShaderGlobals& g, const glm::vec4* program_regs, Vec3& n) const {
  const ShaderOutputs& o = material_textures_[i].program;
  if (o.coat_normal < 0) return false;
  std::array<glm::vec4, ShaderProgram::kMaxRegisters> local;
  const glm::vec4* regs = program_regs;
  if (!regs) {
    run_shader_program(uint32_t(o.program), g, local.data());
    regs = local.data();
  }
  const Vec3 v = Vec3(regs[size_t(o.coat_normal)]);
  const float len = glm::length(v);
  if (!(len > 1e-6f) || !std::isfinite(len)) return false;  // Cycles: the surface's normal then
  n = v / len;
  return true;
}

uint8_t Scene::globals_read(uint32_t i) const {
  auto own = [&](uint32_t m) {
    const MaterialTextures& t = material_textures_[m];
    return uint8_t((t.bump >= 0 ? kReadsDifferentials : 0) |
                   (t.program.any() ? programs_[size_t(t.program.program)].globals_read() : 0));
  };
  uint8_t reads = own(i);
  if (const Mixture* m = mixture(i)) {
    if (m->program >= 0) reads |= programs_[size_t(m->program)].globals_read();
    for (const MixtureComponent& c : m->components) {
      reads |= own(c.material);
      if (c.type == ClosureType::PrincipledHair || c.type == ClosureType::PrincipledHairHuang)
        reads |= kReadsTangent;  // the strand's direction
      if (c.type == ClosureType::HairReflection || c.type == ClosureType::HairTransmission)
        reads |= kReadsTangent | kReadsCorners;  // the strand's, or the triangle's edge
    }
  }
  return reads;
}

void check_material(const Material& m) {
  if (!is_finite(m.base_color) || !is_finite(m.emission) || !std::isfinite(m.metallic) ||
      !std::isfinite(m.roughness) || !std::isfinite(m.specular) || !std::isfinite(m.specular_tint) ||
      !std::isfinite(m.ior) || !is_finite(m.specular_tint_color) || !std::isfinite(m.hair_offset) ||
      !std::isfinite(m.hair_aspect_ratio) || !is_finite(m.hair_lobe_weights) ||
      !std::isfinite(m.hair_random_roughness) || !std::isfinite(m.hair_random_color) || !std::isfinite(m.hair_random) ||
      !std::isfinite(m.hair_melanin) || !std::isfinite(m.hair_melanin_redness) || !is_finite(m.hair_color))
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
  if (!std::isfinite(m.coat_weight) || !std::isfinite(m.coat_roughness) || !std::isfinite(m.coat_ior) ||
      !is_finite(m.coat_tint))
    throw std::invalid_argument("material coat values must be finite");
  if (m.coat_weight < 0.0f || m.coat_roughness < 0.0f || m.coat_roughness > 1.0f || m.coat_ior < 1.0f ||
      glm::any(glm::lessThan(m.coat_tint, Vec3(0.0f))))
    throw std::invalid_argument("material coat_weight must be >= 0, coat_roughness in [0, 1], coat_ior >= 1 and "
                                "coat_tint >= 0");
  if (!std::isfinite(m.sheen_weight) || !std::isfinite(m.sheen_roughness) || !std::isfinite(m.sheen_tint) ||
      !is_finite(m.sheen_tint_color))
    throw std::invalid_argument("material sheen values must be finite");
  if (m.sheen_weight < 0.0f || m.sheen_roughness < 0.0f || m.sheen_roughness > 1.0f || m.sheen_tint < 0.0f ||
      m.sheen_tint > 1.0f || glm::any(glm::lessThan(m.sheen_tint_color, Vec3(0.0f))))
    throw std::invalid_argument("material sheen_weight must be >= 0, sheen_roughness and sheen_tint in [0, 1] and "
                                "sheen_tint_color >= 0");
  if (!std::isfinite(m.anisotropy) || !std::isfinite(m.anisotropic_rotation) || !is_finite(m.tangent))
    throw std::invalid_argument("material anisotropy, anisotropic_rotation and tangent must be finite");
  if (m.anisotropy < -1.0f || m.anisotropy > 1.0f)
    throw std::invalid_argument("material anisotropy must be in [-1, 1]");
  if (!std::isfinite(m.subsurface) || !is_finite(m.subsurface_radius) || !is_finite(m.subsurface_color) ||
      !std::isfinite(m.subsurface_ior) || !std::isfinite(m.subsurface_anisotropy) ||
      !std::isfinite(m.subsurface_entry_alpha))
    throw std::invalid_argument("material subsurface values must be finite");
  if (m.subsurface < 0.0f || m.subsurface > 1.0f || glm::any(glm::lessThan(m.subsurface_radius, Vec3(0.0f))) ||
      glm::any(glm::lessThan(m.subsurface_color, Vec3(0.0f))) || !(m.subsurface_ior > 0.0f))
    throw std::invalid_argument("material subsurface must be in [0, 1], subsurface_radius and subsurface_color >= 0 "
                                "and subsurface_ior > 0");
  if (!std::isfinite(m.thin_film_thickness) || !std::isfinite(m.thin_film_ior) || !(m.thin_film_ior > 0.0f))
    throw std::invalid_argument("material thin_film_thickness must be finite and thin_film_ior finite and > 0");
  if (!(m.dispersion >= 0.0f) || !std::isfinite(m.dispersion))
    throw std::invalid_argument("material dispersion (the inverse Abbe number) must be finite and >= 0");
  if (!is_finite(m.portal_direction)) throw std::invalid_argument("material portal_direction must be finite");
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
  check_program_outputs(textures.program);
  check_material(m);
  Material clean = m;
  clean.base_color = glm::clamp(m.base_color, Vec3(0.0f), Vec3(1.0f));
  clean.transparent_color = glm::clamp(m.transparent_color, Vec3(0.0f), Vec3(1.0f));
  materials_.push_back(clean);
  material_textures_.push_back(textures);
  mixture_index_.push_back(-1);
  emitters_dirty_ = true;
  return uint32_t(materials_.size() - 1);
}

void Scene::check_program_outputs(const ShaderOutputs& o) const {
  const auto registers = o.registers();
  if (o.program < 0) {
    if (std::any_of(registers.begin(), registers.end(), [](int16_t r) { return r >= 0; }))
      throw std::invalid_argument("material reads shader program registers but names no program");
    return;
  }
  if (size_t(o.program) >= programs_.size())
    throw std::invalid_argument("material uses shader program " + std::to_string(o.program) + " but the scene has " +
                                std::to_string(programs_.size()) + " programs");
  const ShaderProgram& program = programs_[size_t(o.program)];
  for (int r : registers)
    if (r != -1 && !program.written(r))
      throw std::invalid_argument("material reads register " + std::to_string(r) + " of a shader program with " +
                                  std::to_string(program.registers()) + " registers, which the program does not write");
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

void Scene::set_instance_constants(const int64_t* ids, size_t count, const int32_t* layer_ids, size_t num_layers,
                                   const float* values) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set instance constants");
  for (size_t i = 0; i < count; ++i)
    if (ids[i] < 0 || size_t(ids[i]) >= instances_.size())
      throw std::invalid_argument("instance " + std::to_string(ids[i]) + " does not exist");
  // The layout: every layer id any call gave, in order of arrival; a new one widens every
  // instance's row (rows already set keep their values, the new layer 0).
  std::vector<int32_t> layout = instance_constant_ids_;
  std::vector<size_t> slot(num_layers);
  for (size_t a = 0; a < num_layers; ++a) {
    const auto found = std::find(layout.begin(), layout.end(), layer_ids[a]);
    slot[a] = size_t(found - layout.begin());
    if (found == layout.end()) layout.push_back(layer_ids[a]);
  }
  if (layout.size() > 64) throw std::invalid_argument("instances have at most 64 constant attributes");
  const size_t width = layout.size(), old_width = instance_constant_ids_.size();
  if (width == 0) return;
  size_t rows = old_width > 0 ? instance_constants_.size() / old_width : 0;
  for (size_t i = 0; i < count; ++i) rows = std::max(rows, size_t(ids[i]) + 1);
  require_memory(double(rows) * double(width) * sizeof(Vec3), "instance constants");
  if (width != old_width) {
    std::vector<Vec3> wider(rows * width, Vec3(0.0f));
    for (size_t r = 0; old_width > 0 && r < instance_constants_.size() / old_width; ++r)
      std::copy_n(&instance_constants_[r * old_width], old_width, &wider[r * width]);
    instance_constants_ = std::move(wider);
    instance_constant_ids_ = std::move(layout);
  } else {
    instance_constants_.resize(rows * width, Vec3(0.0f));
  }
  for (size_t i = 0; i < count; ++i)
    for (size_t a = 0; a < num_layers; ++a) {
      const float* v = values + 3 * (i * num_layers + a);
      const Vec3 x(v[0], v[1], v[2]);
      instance_constants_[size_t(ids[i]) * width + slot[a]] = is_finite(x) ? x : Vec3(0.0f);
    }
}

void Scene::set_mesh_attributes(uint32_t id, bool prototype, const float* values, size_t num_corners,
                                const int32_t* ids, size_t num_attributes) {
  std::lock_guard<std::mutex> lock(mutex_);
  check_idle("set mesh attributes");
  if (prototype ? id >= prototypes_.size() : id >= meshes_.size())
    throw std::invalid_argument(std::string(prototype ? "prototype " : "mesh ") + std::to_string(id) +
                                " does not exist");
  Mesh& mesh = prototype ? *prototypes_[id]->mesh : *meshes_[id];
  const size_t corners = 3 * mesh.triangles.size();
  if (num_attributes > 0 && num_corners != corners)
    throw std::invalid_argument("mesh attributes have " + std::to_string(num_corners) + " corners; the mesh has " +
                                std::to_string(corners));
  if (num_attributes > 64) throw std::invalid_argument("a mesh has at most 64 attributes");
  require_memory(double(corners) * double(num_attributes) * sizeof(Vec3), "mesh attributes");
  std::vector<Vec3> stored(corners * num_attributes);
  for (size_t a = 0; a < num_attributes; ++a)
    for (size_t i = 0; i < corners; ++i) {
      const float* v = values + 3 * (a * corners + i);
      const Vec3 x(v[0], v[1], v[2]);
      stored[i * num_attributes + a] = is_finite(x) ? x : Vec3(0.0f);
    }
  mesh.corner_attributes = std::move(stored);
  mesh.attribute_ids.assign(ids, ids + num_attributes);
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

size_t Scene::num_triangles() const {
  size_t n = 0;
  for (const auto& m : meshes_) n += m->triangles.size();
  for (const Instance& inst : instances_)
    if (inst.binding != kRemoved && !inst.hidden)
      n += prototypes_[bindings_[inst.binding].prototype]->mesh->triangles.size();
  return n;
}

void Scene::commit() {
  if (catcher_masks_dirty_ || (dirty_ && shadow_catchers_)) apply_catcher_masks();
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
    local_scenes_.reset();
  }
  if (!local_scenes_ && std::any_of(programs_.begin(), programs_.end(),
                                    [](const ShaderProgram& p) { return p.local_queries(); }))
    build_local_scenes();
  if (emitters_dirty_) {
    build_mesh_light();
    emitters_dirty_ = false;
  }
}

void Scene::bounds(Vec3& lo, Vec3& hi) const {
  if (dirty_) {  // not committed since the last change: Embree knows no bounds yet (and would complain)
    lo = Vec3(std::numeric_limits<float>::infinity());
    hi = -lo;
    return;
  }
  RTCBounds b;
  rtcGetSceneBounds(scene_of(scene_), &b);
  lo = Vec3(b.lower_x, b.lower_y, b.lower_z);
  hi = Vec3(b.upper_x, b.upper_y, b.upper_z);
}

bool Scene::intersect(const Ray& ray, SurfaceHit& hit) const {
  RTCRayHit rh = embree_ray_hit(ray.origin, ray.dir, ray.tmin, ray.tmax);
  ray_queries::intersect(scene_of(scene_), rh);
  return surface_hit(&rh, ray.dir, hit);
}

bool Scene::intersect_object(Ray ray, uint32_t object, SurfaceHit& hit) const {
  constexpr int kMaxPassed = 64;  // other objects' surfaces passed on the way
  for (int passed = 0; passed <= kMaxPassed; ++passed) {
    if (!intersect(ray, hit)) return false;
    if (hit.object == object) return true;
    ray.tmin = std::nextafter(hit.t, std::numeric_limits<float>::infinity());
    if (!(ray.tmin < ray.tmax)) return false;
  }
  return false;
}

bool Scene::occluded(const Vec3& origin, const Vec3& dir, float tmin, float tmax) const {
  RTCRay ray = embree_ray(origin, dir, tmin, tmax);
  return ray_queries::occluded(scene_of(scene_), ray);
}

}  // namespace torrance
