// Scene: the emissive triangles of meshes and instances as one light (the mesh light).
#include "scene/scene_internal.h"
#include "scene/scene_motion.h"

#include "torrance/util/limits.h"

#include <stdexcept>
#include <string>

namespace torrance {

using namespace scene_detail;

void Scene::build_mesh_light() {
  std::vector<EmissiveTriangle> triangles;
  std::vector<float> power;
  // Power estimate for choosing among emitters: a textured emission counts as its strength; a
  // negative emission (light taken away, as Cycles) is sampled by its magnitude.
  // Once per material: the scans below look it up per triangle (10 M triangles: 0.2 s before).
  std::vector<float> material_radiance(materials_.size());
  bool any_emissive = false;
  for (size_t m = 0; m < materials_.size(); ++m) {
    const MaterialTextures& tex = material_textures_[m];
    material_radiance[m] =
        tex.textured_emission() ? std::abs(tex.emission_strength) : luminance(glm::abs(materials_[m].emission));
    any_emissive |= material_radiance[m] > 0.0f;
  }
  auto radiance_of = [&material_radiance](uint32_t m) { return material_radiance[m]; };
  auto add = [&](const Corners& c, uint32_t material, float radiance, uint32_t owner, uint32_t prim, bool mirrored) {
    EmissiveTriangle e;
    e.owner = owner;
    e.prim = prim;
    e.light_group = owner & kInstanceBit ? instances_[owner & ~kInstanceBit].settings.light_group : meshes_[owner]->settings.light_group;
    e.emitter_links =
        owner & kInstanceBit ? instances_[owner & ~kInstanceBit].settings.emitter_links : meshes_[owner]->settings.emitter_links;
    e.mirrored = mirrored;
    if (owner & kInstanceBit) {  // moving: its transform, or its prototype deforms
      const Instance& inst = instances_[owner & ~kInstanceBit];
      e.moving = inst.motion.size() > 1 || prototypes_[bindings_[inst.binding].prototype]->mesh->motion_steps > 1;
    } else {
      e.moving = meshes_[owner]->motion_steps > 1;
    }
    if (!place_emissive_triangle(e, c.p[0], c.p[1], c.p[2])) return false;
    e.material = material;
    triangles.push_back(e);
    const float p = e.area * radiance;  // huge but finite inputs may overflow: keep the CDF finite
    power.push_back(std::isfinite(p) ? p : std::numeric_limits<float>::max());
    return true;
  };
  for (size_t mesh_index = 0; mesh_index < meshes_.size(); ++mesh_index) {
    Mesh* mesh = meshes_[mesh_index].get();
    mesh->emitter_index.clear();  // none emits (intersect reads an empty table as -1)
    if (!any_emissive) continue;
    mesh->emitter_index.assign(mesh->triangles.size(), -1);
    for (size_t i = 0; i < mesh->triangles.size(); ++i) {
      const uint32_t m = mesh->material_ids[i];
      const float radiance = radiance_of(m);
      if (!(radiance > 0.0f)) continue;
      const Corners c = mesh_corners(mesh->positions, mesh->triangles[i], nullptr, nullptr);
      if (add(c, m, radiance, uint32_t(mesh_index), uint32_t(i), false))
        mesh->emitter_index[i] = int32_t(triangles.size() - 1);
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
  for (size_t inst_index = 0; inst_index < instances_.size(); ++inst_index) {
    Instance& inst = instances_[inst_index];
    inst.emitter_base = -1;
    if (inst.binding == kRemoved || inst.hidden || bindings_[inst.binding].num_emissive == 0) continue;
    const Binding& b = bindings_[inst.binding];
    const Mesh& mesh = *prototypes_[b.prototype]->mesh;
    inst.emitter_base = int32_t(triangles.size());
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
      if (b.emitter_rank[i] < 0) continue;
      const uint32_t m = b.material(mesh.material_ids[i]);
      Corners c;
      const bool mirrored = instance_corners(mesh.positions, mesh.triangles[i], nullptr, nullptr, inst.transform, c);
      if (!add(c, m, radiance_of(m), uint32_t(inst_index) | kInstanceBit, uint32_t(i), mirrored)) {
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
  // Motion blur: a moving mesh's triangle at the ray's time (scene_motion.h), as its hits are; a
  // moving instance's triangle (a deforming prototype's at that time) under its transform then.
  auto at_ray_time = [this](const EmissiveTriangle& t) {
    Corners c;
    if (t.owner & kInstanceBit) {
      const Instance& inst = instances_[t.owner & ~kInstanceBit];
      const Mesh& mesh = *prototypes_[bindings_[inst.binding].prototype]->mesh;
      c = mesh_corners(mesh.positions, mesh.triangles[t.prim], nullptr, nullptr);
      if (mesh.motion_steps > 1)  // a deforming prototype
        motion_corners({mesh.motion_steps, mesh.motion_positions.data(), mesh.positions.size(), nullptr, 0},
                       mesh.triangles[t.prim], t.prim, c);
      place_corners(instance_transform(inst), c);
    } else {
      const Mesh& mesh = *meshes_[t.owner];
      const glm::uvec3& tri = mesh.triangles[t.prim];
      c = mesh_corners(mesh.positions, tri, nullptr, nullptr);
      motion_corners({mesh.motion_steps, mesh.motion_positions.data(), mesh.positions.size(), nullptr, 0}, tri,
                     t.prim, c);
    }
    EmissiveTriangle moved = t;
    if (!place_emissive_triangle(moved, c.p[0], c.p[1], c.p[2])) moved.area = 0.0f;
    return moved;
  };
  lights_.set_mesh_light(MeshLight(
      std::move(triangles), power,
      [this](const EmissiveTriangle& t, const Vec2& b, const Vec3& wi, const PathState& seen_by) {
        return sampled_emission(t, b, wi, seen_by);
      },
      has_motion_ ? MeshLight::MovingTriangle(at_ray_time) : nullptr));
}

}  // namespace torrance
