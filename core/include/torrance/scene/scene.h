// The scene: triangle meshes traced by Embree 3, their materials, the lights and the camera.
//
// Embree is driven in the order of its minimal tutorial: device -> error callback -> buffers ->
// commit geometry -> commit scene -> trace. Every input is validated on the way in and rejected
// with std::invalid_argument naming the problem, so nothing malformed ever reaches the tracer.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/camera/camera.h"
#include "torrance/film/cryptomatte.h"
#include "torrance/film/extra_passes.h"
#include "torrance/scene/frame_motion.h"
#include "torrance/scene/object_settings.h"
#include "torrance/lights/lights.h"
#include "torrance/bsdfs/mixture.h"
#include "torrance/media/scene_media.h"
#include "torrance/media/volume_grid.h"
#include "torrance/shader/shader_bump.h"
#include "torrance/shader/shader_program.h"
#include "torrance/shader/texture.h"

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace torrance {

// Image textures driving a material's inputs (indices from Scene::add_texture; -1 = none), like
// Image Texture nodes linked to Principled BSDF sockets. Float inputs read the colour's luminance.
struct MaterialTextures {
  int base_color = -1, metallic = -1, roughness = -1, emission = -1;
  int normal = -1;                 // a tangent-space normal map (Normal Map node)
  int alpha = -1;                  // the material's alpha from the texture's ALPHA channel (Scene::opacity)
  // How the alpha texture is read: its colour's luminance instead of its alpha channel (a Mix
  // Shader's Fac fed by an Image Texture's Color), and 1 - that (the Transparent BSDF in the
  // Mix Shader's second slot, so the opaque closure's weight is 1 - Fac).
  bool alpha_from_luminance = false, alpha_inverted = false;
  float emission_strength = 1.0f;  // emission = texture colour * strength
  float normal_strength = 1.0f;
  // A height map (Bump node fed by an image texture's luminance) when there is no normal map.
  int bump = -1;
  float bump_strength = 1.0f, bump_distance = 1.0f;
  // Inputs computed by a shader program (node graphs the fields above do not express); an input
  // the program feeds replaces both the constant and the texture (emission: x emission_strength).
  ShaderOutputs program;
  bool any() const {
    return base_color >= 0 || metallic >= 0 || roughness >= 0 || emission >= 0 || normal >= 0 || bump >= 0 ||
           program.any();
  }
  bool textured_emission() const { return emission >= 0 || program.emission >= 0; }
};

struct SurfaceHit {
  float t = 0.0f;
  Vec3 position{0.0f};
  Vec3 geometric_normal{0.0f};  // unit, as wound (counter-clockwise), not yet facing the ray
  Vec3 shading_normal{0.0f};    // unit, interpolated corner normal (= geometric for flat meshes)
  uint32_t material = 0;
  int32_t emitter = -1;       // index among the emissive triangles (Lights' mesh light), or -1
  Vec2 uv{0.0f};              // interpolated corner UVs (0 without UVs)
  bool has_uv = false;        // the mesh has UVs (the UV pass: (u, v, 1), else 0)
  ObjectSettings object_settings;  // its object's (scene/object_settings.h)
  Vec3 tangent{0.0f};         // unit dP/du from the triangle's UVs (0 without usable UVs)
  float uv_per_metre = 0.0f;  // how fast UVs change across the triangle (sqrt of UV area / area)
  float bitangent_sign = 1.0f;
  Vec3 dpdu{0.0f}, dpdv{0.0f};  // dP/du and dP/dv of the triangle's UV mapping (0 without usable UVs)
  // The hit triangle's corner attributes (Scene::set_mesh_attributes) and each stored corner's
  // interpolation weight (nullptr / 0 without attributes).
  const Vec3* corner_attributes = nullptr;
  const int32_t* attribute_ids = nullptr;
  int num_attributes = 0;
  Vec3 corner_weights{0.0f};
  // The hit instance's constant attributes (Scene::set_instance_constants; nullptr / 0: none).
  const Vec3* instance_constants = nullptr;
  const int32_t* instance_constant_ids = nullptr;
  int num_instance_constants = 0;
  // The gradients (1/m, in the triangle's plane) of corner_weights.y and .z (with attributes).
  Vec3 weight_gradients[2] = {Vec3(0.0f), Vec3(0.0f)};
  Vec3 corners[3] = {Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)};  // the triangle's, world space
  // A hair strand's hit (Scene::add_curves): `tangent` is the strand's direction (Cycles' dPdu),
  // the normals are Cycles' (a round curve's: from its centre line out through the hit; a
  // ribbon's: geometric towards the viewer, shading rounded across the strand).
  bool on_curve = false;
  // On a strand of curves with a normal attribute (add_curves' normals): it, interpolated over
  // the segment as Cycles' curve attributes; else 0.
  Vec3 curve_normal{0.0f};
  // A point's hit (Scene::add_points): the normals are Cycles' (from the point's centre out
  // through the hit), no UVs, no tangent.
  bool on_point = false;
  // ShaderGlobals::primitive_info, set only on a strand (Intercept, Length, Thickness, Random)
  // or a point (its centre xyz, radius).
  glm::vec4 primitive_info{0.0f};
  // The hit's object as the local queries name it (ShaderGlobals::object: a world-space mesh's
  // index, or an instance's index with the top bit set; none on a hair strand) and its triangle
  // (on a strand: its segment, uv.x along it); what Scene::intersect_object follows.
  uint32_t object = ShaderGlobals::kNoObject, prim = 0;
  uint32_t curve_set = 0;  // on a strand: its curve set (Scene::add_curves' id)
};

// How hair strands are traced (Blender's Render > Curves > Shape, Cycles 3.4): Round is Cycles'
// "3D Curves" (a tube), Ribbon its "Rounded Ribbons" (flat, facing the ray, normals rounded).
enum class CurveShape { Round, Ribbon };

// Shader globals that know only a UV (what a mesh light's sample or a test has).
inline ShaderGlobals uv_globals(const Vec2& uv, float footprint = 0.0f) {
  ShaderGlobals g;
  g.uv = uv;
  g.footprint = footprint;
  return g;
}

// What a shader program reads at a hit seen along ray_dir (Cycles' ShaderData: normals facing
// the viewer), textures averaged over `footprint` UV units; cone_width: the ray cone's width
// at the hit in metres (Cycles' dP, the ray differentials' length).
inline ShaderGlobals shader_globals(const SurfaceHit& hit, const Vec3& ray_dir, float footprint,
                                    float cone_width = 0.0f, uint8_t reads = kReadsAll) {
  ShaderGlobals g = uv_globals(hit.uv, footprint);
  g.position = hit.position;
  g.incoming = -ray_dir;
  g.backfacing = glm::dot(hit.geometric_normal, g.incoming) < 0.0f;
  const float side = g.backfacing ? -1.0f : 1.0f;
  g.normal = side * hit.shading_normal;
  g.true_normal = side * hit.geometric_normal;
  g.object = hit.object;
  g.prim = hit.prim;
  if (hit.on_curve || hit.on_point) {
    g.on_curve = hit.on_curve;
    g.on_point = hit.on_point;
    g.primitive_info = hit.primitive_info;
    g.curve_normal = hit.curve_normal;
  }
  // Of the rest, only what `reads` (GlobalsRead flags) names.
  if (reads & kReadsAttributes) {
    g.corner_attributes = hit.corner_attributes;
    g.attribute_ids = hit.attribute_ids;
    g.num_attributes = hit.num_attributes;
    g.corner_weights = hit.corner_weights;
    g.instance_constants = hit.instance_constants;
    g.instance_constant_ids = hit.instance_constant_ids;
    g.num_instance_constants = hit.num_instance_constants;
  }
  if (reads & kReadsTangent) {
    g.tangent = hit.tangent;
    g.bitangent_sign = hit.bitangent_sign;
  }
  if (reads & kReadsCorners)
    for (int k = 0; k < 3; ++k) g.corners[k] = hit.corners[k];
  // Cycles' ray differentials: the cone's width along its tangent pair around the true normal,
  // and the UVs (through dP/du, dP/dv) and corner weights they move by.
  if ((reads & kReadsDifferentials) && cone_width > 0.0f && std::isfinite(cone_width)) {
    Vec3 a, b;
    shader::differential_axes(g.true_normal, a, b);
    g.dpdx = cone_width * a;
    g.dpdy = cone_width * b;
    const Vec3 n = hit.geometric_normal;
    const float det_uv = glm::dot(n, glm::cross(hit.dpdu, hit.dpdv));
    if (std::abs(det_uv) > 0.0f && std::isfinite(det_uv)) {
      const Vec3 grad_u = glm::cross(hit.dpdv, n) / det_uv, grad_v = glm::cross(n, hit.dpdu) / det_uv;
      g.duvdx = Vec2(glm::dot(grad_u, g.dpdx), glm::dot(grad_v, g.dpdx));
      g.duvdy = Vec2(glm::dot(grad_u, g.dpdy), glm::dot(grad_v, g.dpdy));
      if (!std::isfinite(g.duvdx.x + g.duvdx.y + g.duvdy.x + g.duvdy.y)) g.duvdx = g.duvdy = Vec2(0.0f);
    }
    if (hit.num_attributes > 0) {
      auto weights = [&](const Vec3& d) {
        const float y = glm::dot(hit.weight_gradients[0], d), z = glm::dot(hit.weight_gradients[1], d);
        return std::isfinite(y + z) ? Vec3(-y - z, y, z) : Vec3(0.0f);
      };
      g.dweights_dx = weights(g.dpdx);
      g.dweights_dy = weights(g.dpdy);
    }
  }
  return g;
}

// Throws std::invalid_argument unless the material's values are finite and in range.
void check_material(const Material& material);

class Scene final : public ShaderTracer {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  uint32_t add_material(const Material& material, const MaterialTextures& textures = {});
  uint32_t add_texture(Texture texture);
  // Adds a shader program (its textures must already be added); returns its index for
  // MaterialTextures::program.
  uint32_t add_shader_program(ShaderProgram program);
  size_t num_shader_programs() const { return programs_.size(); }
  const ShaderProgram& shader_program(uint32_t i) const { return programs_[i]; }
  // Runs program i at a point; regs must hold its registers() entries.
  void run_shader_program(uint32_t i, const ShaderGlobals& g, glm::vec4* regs) const {
    programs_[i].run(g, textures_, regs);
  }
  size_t num_textures() const { return textures_.size(); }
  const MaterialTextures& material_textures(uint32_t i) const { return material_textures_[i]; }
  // The material at a hit with its textures applied (base colour, metallic, roughness, emission),
  // averaged over a footprint of that many UV units (0: the finest texels).
  // regs (if given, kMaxRegisters entries): where the material's shader program, if it has one,
  // leaves its registers, for normal_mapped at the same hit to reuse instead of running it again.
  Material textured_material(uint32_t material, const ShaderGlobals& globals, glm::vec4* regs = nullptr) const {
    Material m = materials_[material];
    apply_textures(material, globals, m, regs);
    return m;
  }
  // The same into `m`, which holds material(material): the path tracer's vertex keeps its
  // material in place instead of copying a returned one (Material is large).
  void apply_textures(uint32_t material, const ShaderGlobals& globals, Material& m, glm::vec4* regs = nullptr) const;
  Material textured_material(uint32_t material, const Vec2& uv, float footprint = 0.0f) const {
    return textured_material(material, uv_globals(uv, footprint));
  }
  // A material made of weighted closures (Mix/Add Shader, mixture.h); returns its material index.
  // Its normal map or bump and its alpha texture come from `textures` (only those fields are read);
  // alpha and transparent_color as Material's (a Mix Shader of a Transparent BSDF and this
  // mixture). Checked by check_mixture; its closures' materials must not be mixtures themselves.
  uint32_t add_mixture(const Mixture& mixture, const MaterialTextures& textures = {}, float alpha = 1.0f,
                       const Vec3& transparent_color = Vec3(1.0f));
  // The mixture of material i, or nullptr for an ordinary material.
  const Mixture* mixture(uint32_t i) const {
    return mixture_index_[i] >= 0 ? &mixtures_[size_t(mixture_index_[i])] : nullptr;
  }
  bool has_mixtures() const { return !mixtures_.empty(); }
  // Volumes (media/scene_media.h): material's closed meshes hold `medium`; pass_through: the
  // material has no surface shader (a boundary paths cross). The world's volume surrounds all.
  void set_material_volume(uint32_t material, const HomogeneousMedium& medium, bool pass_through);
  // A heterogeneous volume (media/varying_medium.h): its program must be added; its majorant is
  // found here from the program's values over the bounds.
  void set_material_volume(uint32_t material, VaryingMedium medium, bool pass_through);
  void set_world_volume(const HomogeneousMedium& medium);
  const SceneMedia& media() const { return media_; }
  // A sparse voxel grid (media/volume_grid.h) heterogeneous volumes' programs read (their
  // VolumeGrid ops' resource); returns its id.
  uint32_t add_volume_grid(VolumeGrid grid);
  const std::vector<std::shared_ptr<const VolumeGrid>>& volume_grids() const { return volume_grids_; }
  // The weights of mixture material i's closures at uv (image factors over footprint UV units).
  // regs: as textured_material's (the mixture's program, which its Normal reads too).
  MixtureWeights mixture_weights(uint32_t i, const ShaderGlobals& globals, glm::vec4* regs = nullptr) const;
  MixtureWeights mixture_weights(uint32_t i, const Vec2& uv, float footprint = 0.0f) const {
    return mixture_weights(i, uv_globals(uv, footprint));
  }
  // The radiance material i emits at a point seen as g says (textures and mixtures included).
  Vec3 emission_at(uint32_t i, const ShaderGlobals& g) const;
  // The alpha of the surface a ray along dir meets at hit, the path being in state seen_by (a
  // shadow ray's: kRayShadow): its program's alpha register run there, else as below.
  // tint (if given) becomes the colour that passes (Material::transparent_color, or a mixture's
  // Transparent closures' colours by their weights). portal_share (if given) becomes, of the share
  // that passes, the part through Ray Portal closures (portal_exit; 0 without them). A shadow ray
  // meeting a Ray Portal closure is stopped there (opacity 1, as Cycles' shade_shadow).
  float opacity(const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by, Vec3* tint = nullptr,
                float* portal_share = nullptr) const;
  // Where a ray along dir that passes the hit's Ray Portal closures goes on (Cycles'
  // integrate_surface_ray_portal): one of them chosen by its weight (u in [0, 1)), its Position
  // (`moved`: not the hit point, to start there as it is; else the hit's, to be offset along
  // the new direction), its Direction (unit; the ray's own where zero) and Color (`tint`).
  struct PortalExit {
    Vec3 origin{0.0f}, dir{0.0f, 0.0f, 1.0f}, tint{0.0f};
    bool moved = false;
  };
  PortalExit portal_exit(const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by, float u) const;
  // What the shaders at a hit see of a ray along dir in state seen_by (no footprint).
  ShaderGlobals globals_seen_by(const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by) const;
  // The holdout weight of the surface at hit for a camera ray (Cycles' surface_shader_apply_holdout):
  // a holdout object's `opacity` (its surface's, from opacity() above: the object's transparency
  // stays), else the weight of its mixture's Holdout closures (times the material's alpha); 0
  // without either. The path takes it, times its throughput, off the pixel's alpha.
  float holdout(const SurfaceHit& hit, const Vec3& dir, const PathState& seen_by, float opacity) const;
  // Whether some object is a holdout or some mixture has a Holdout closure.
  bool has_holdouts() const { return object_holdouts_ || mixture_holdouts_; }
  // The material's alpha at a hit: its alpha texture's alpha channel (or colour luminance, or 1 -
  // either: MaterialTextures) at uv, else Material::alpha (its program's alpha not run).
  float opacity(uint32_t material, const Vec2& uv) const {
    const MaterialTextures& t = material_textures_[material];
    if (t.alpha < 0) return materials_[material].alpha;
    const glm::vec4 c = textures_[t.alpha]->lookup(uv);
    const float a = clamp01(t.alpha_from_luminance ? blender_luminance(Vec3(c)) : c.a);
    return t.alpha_inverted ? 1.0f - a : a;
  }
  // The shading normal ns (as wound) perturbed by the material's Normal at a hit seen as g says
  // (shader_globals: the view, footprint and ray differentials), as wound; ns when none. The
  // Normal is the material's program's normal register (Bump and Normal Map nodes of any graph,
  // shader_bump.h), else its image normal map (tangent space) or image height map (a Bump node
  // fed by an Image Texture's luminance: its heights at the hit and at the hit moved by the ray
  // differentials, at least a hundredth of a texel apart), by shader_bump.h's formulas.
  // surface_normal (if given) becomes the surface's normal after the Material Output's Displacement
  // (ShaderOutputs::surface_normal, as wound) where the program computes it; else it is left as is.
  // program_regs: the registers textured_material or mixture_weights of this material left at
  // this hit (g, ns = hit.shading_normal), read instead of running the program again.
  Vec3 normal_mapped(uint32_t material, const SurfaceHit& hit, const Vec3& ns, const ShaderGlobals& g,
                     Vec3* surface_normal = nullptr, const glm::vec4* program_regs = nullptr) const;
  // Whether material i (a mixture: one of its closures) has a Principled coat (a weight above 0,
  // or one its program computes), whose normal may then differ from the closures' (bsdf.h).
  bool coated(uint32_t i) const;
  // The Coat Normal material i's program computes (ShaderOutputs::coat_normal: facing the viewer,
  // as the Normal) at the hit g describes, into n; false (n left as is) without one.
  // program_regs: as for normal_mapped.
  bool coat_normal(uint32_t i, const ShaderGlobals& g, const glm::vec4* program_regs, Vec3& n) const;
  // Whether shading material i (its programs, its mixture's closures, an image bump) reads the
  // ray differentials of ShaderGlobals (shader_globals' cone_width): else they need not be made.
  bool reads_differentials(uint32_t i) const { return globals_read(i) & kReadsDifferentials; }
  // GlobalsRead flags of what shading material i reads of ShaderGlobals (as above: its programs,
  // its mixture's closures; an image bump reads the differentials).
  uint8_t globals_read(uint32_t i) const;
  // As above, seen from the front (along -geometric_normal); cone_width: the ray cone's width in
  // metres at the hit (the ray differentials' length).
  Vec3 normal_mapped(uint32_t material, const SurfaceHit& hit, const Vec3& ns, float footprint = 0.0f,
                     float cone_width = 0.0f) const {
    ShaderGlobals g = shader_globals(hit, -hit.geometric_normal, footprint, cone_width);
    g.tracer = this;
    return normal_mapped(material, hit, ns, g);
  }

  // positions: num_vertices xyz; triangles: num_triangles vertex-index triples;
  // corner_normals: nullptr or num_triangles * 3 xyz normals; material_ids: nullptr or num_triangles;
  // corner_uvs: nullptr or num_triangles * 3 uv pairs.
  // Degenerate triangles and zero-length normals are tolerated (the latter fall back to flat).
  // Returns the mesh id; a mesh without triangles is accepted and ignored.
  uint32_t add_mesh(const float* positions, size_t num_vertices, const int64_t* triangles, size_t num_triangles,
                    const float* corner_normals, const int64_t* material_ids, const float* corner_uvs = nullptr);

  // Motion blur: mesh `mesh` (from add_mesh, before the next commit) moves through `steps` >= 2
  // world-space positions (steps x num_vertices xyz), evenly spaced over the shutter's time
  // [0, 1], with corner normals the same way (nullptr: its static ones, or flat). Embree
  // interpolates linearly between steps (multi-segment motion triangles); a hit's position and
  // normals are interpolated at the ray's time (ray_queries::set_time). Its add_mesh positions
  // stay what light sampling and the other static queries see. Throws std::invalid_argument for
  // a bad mesh id, fewer than 2 steps, a step count above 129, NaN/Inf or out-of-range values.
  void set_mesh_motion(uint32_t mesh, size_t steps, const float* positions, const float* corner_normals);
  // Motion blur of instances: instances ids[0..count) (from add_instances) move through `steps`
  // >= 2 transforms each (steps x count row-major 3x4 matrices, step-major), evenly over the
  // shutter: Embree's instance motion (linear between steps, as the hits and the emissive
  // triangles interpolate them at the ray's time). Throws std::invalid_argument for a removed or
  // unknown id, a step count outside 2..129 or a transform add_instances would refuse. An
  // instance with a step of (nearly) zero scale, which Embree could not trace, keeps its transform
  // without motion; returns how many did.
  size_t set_instance_motion(const int64_t* ids, size_t count, size_t steps, const float* transforms);
  // Motion blur of a deforming instanced mesh: prototype `prototype` (from add_prototype) moves
  // through `steps` >= 2 object-space positions (steps x num_vertices xyz) and corner normals
  // (nullptr: its static ones, or flat), as set_mesh_motion's; every instance of it deforms so,
  // under its own transform (or transform motion) at the ray's time. Throws std::invalid_argument
  // as set_mesh_motion, and when a step would take an instance of it beyond add_instances' bounds.
  void set_prototype_motion(uint32_t prototype, size_t steps, const float* positions, const float* corner_normals);
  // Whether some mesh or instance moves: the integrator then samples a time per path.
  bool has_motion() const { return has_motion_; }

  // The Vector pass (kPassVector; Cycles' motion pass, frame_motion.h): the scene one frame
  // before and one frame after the rendered frame. The camera's camera_to_world then (row-major,
  // as CameraParams'); world mesh `mesh`'s vertices then (num_vertices xyz each: its deformation
  // and its object's transform); instances ids[0..count)'s object-to-world 3x4 row-major
  // transforms then (count of them each). Later calls replace earlier ones. Throws
  // std::invalid_argument for a bad mesh or instance id and NaN/Inf or out-of-range values.
  void set_frame_motion_camera(const std::array<float, 16>& before, const std::array<float, 16>& after);
  void set_frame_motion_mesh(uint32_t mesh, const float* before, const float* after);
  void set_frame_motion_instances(const int64_t* ids, size_t count, const float* before, const float* after);
  // Prototype `prototype`'s object-space vertices then (num_vertices xyz each: a deforming
  // instanced mesh), which its instances' transforms then (or now) place.
  void set_frame_motion_prototype(uint32_t prototype, const float* before, const float* after);
  // Curve set `set`'s keys then (num_keys xyz each, in add_curves' order), whose curves start at
  // curve_first (num_curves + 1 offsets, as add_curves was given them).
  void set_frame_motion_curves(uint32_t set, const int64_t* curve_first, size_t num_curves, const float* before,
                               const float* after, size_t num_keys);
  const FrameMotion& frame_motion() const { return frame_motion_; }
  // The point `hit` found, now and where it was one frame before and will be one after (world
  // space), as Cycles' primitive_motion_vector takes them: its mesh's vertices then at its
  // barycentric weights, or its instance's transforms then applied to its position in the
  // instance (a deforming prototype's: its vertices then at the barycentric weights); on a strand the point of its segment's key polyline at the hit (Cycles' curve
  // centre), with its keys then; the point itself for what was not given.
  std::array<Vec3, 3> frame_motion_points(const SurfaceHit& hit) const;
  // Vertices and triangles of mesh `mesh` from add_mesh (std::invalid_argument for a bad id).
  size_t mesh_vertex_count(uint32_t mesh) const;
  size_t mesh_triangle_count(uint32_t mesh) const;
  // The same of prototype `prototype` from add_prototype.
  size_t prototype_vertex_count(uint32_t prototype) const;
  size_t prototype_triangle_count(uint32_t prototype) const;

  // Per-corner attributes of mesh `mesh` (from add_mesh; with prototype = true, of a prototype)
  // for shader programs: values (num_attributes, 3 * its triangles) xyz, ids naming each layer
  // (the Attribute op's resource); num_corners must be 3 * its triangles. NaN/Inf values are read
  // as 0. Replaces earlier ones.
  // Per-instance constant attributes (an instanced object's Object Info: the Attribute op reads
  // them where the prototype's corners have no layer of that id): values (count, num_layers, 3)
  // for instances ids[0..count) of the layers layer_ids (any of them, in any order; a layer an
  // instance was never given reads 0). Non-finite values are stored as 0.
  void set_instance_constants(const int64_t* ids, size_t count, const int32_t* layer_ids, size_t num_layers,
                              const float* values);
  void set_mesh_attributes(uint32_t mesh, bool prototype, const float* values, size_t num_corners,
                           const int32_t* ids, size_t num_attributes);

  // Blender's pass indices, for the Object Index and Material Index passes (0 unless set): of a
  // mesh from add_mesh, of instances (ids from add_instances), of materials 0 .. count - 1.
  void set_mesh_pass_index(uint32_t mesh, float index);
  void set_instance_pass_indices(const int64_t* ids, size_t count, const float* values);
  void set_material_pass_indices(const float* values, size_t count);
  // Holdout objects (Blender's Object > Visibility > Holdout, or a collection's in the view layer):
  // a mesh from add_mesh, instances (ids from add_instances). See holdout().
  void set_mesh_holdout(uint32_t mesh, bool holdout);
  void set_instance_holdouts(const int64_t* ids, size_t count, bool holdout);
  // Shadow catchers (Blender's Object > Visibility > Shadow Catcher): a mesh from add_mesh,
  // instances (ids from add_instances). A camera path that meets one splits there as Cycles'
  // (film/shadow_catcher.h); scenes without any pay nothing.
  void set_mesh_shadow_catcher(uint32_t mesh, bool catcher);
  void set_instance_shadow_catchers(const int64_t* ids, size_t count, bool catcher);
  // Whether some mesh or instance is a shadow catcher.
  bool has_shadow_catchers() const { return shadow_catchers_; }
  // The Embree ray mask (ray_queries::set_mask) of rays that see only the shadow catchers: in a
  // scene with some, every other geometry's mask is kOrdinaryMask (after commit).
  static constexpr uint32_t kCatcherOnlyMask = 2u, kOrdinaryMask = 1u;
  // Light groups (extra_passes.h: Scene::extra_passes().set_light_groups) of emitting objects:
  // a mesh from add_mesh, instances; group -1: none.
  void set_mesh_light_group(uint32_t mesh, int group);
  void set_instance_light_groups(const int64_t* ids, size_t count, int group);
  // Light linking (lights/light_linking.h) of a mesh from add_mesh or of instances: its receiver
  // set and blocker set (0..63) and, as an emitter, its entry of the Lights' table (0: unlinked).
  void set_mesh_light_linking(uint32_t mesh, int receiver_set, int blocker_set, int emitter_entry);
  void set_instance_light_linking(const int64_t* ids, size_t count, int receiver_set, int blocker_set,
                                  int emitter_entry);
  // The view layer's shader AOVs and light groups, and the materials' AOV Output programs
  // (extra_passes.h). Set before a render.
  ExtraPasses& extra_passes() { return extra_passes_; }
  const ExtraPasses& extra_passes() const { return extra_passes_; }
  // Cryptomatte (film/cryptomatte.h): the view layer's layers and the ids of the object entries
  // and materials; a mesh from add_mesh's or instances' entry (-1: none). Set before a render.
  Cryptomatte& cryptomatte() { return cryptomatte_; }
  const Cryptomatte& cryptomatte() const { return cryptomatte_; }
  void set_mesh_cryptomatte(uint32_t mesh, int32_t entry);
  void set_instance_cryptomatte(const int64_t* ids, size_t count, int32_t entry);
  // A curve set's (add_curves) object settings at once, as its mesh's setters above give them:
  // pass index, holdout, shadow catcher, light group, light linking sets (a strand emits no
  // light, so no emitter entry), Cryptomatte entry. std::invalid_argument for a bad set, group
  // or linking set.
  void set_curves_settings(uint32_t set, const ObjectSettings& settings);
  float material_pass_index(uint32_t material) const {
    return material < material_pass_indices_.size() ? material_pass_indices_[material] : 0.0f;
  }

  // Hair strands (hair/curve_set.h): num_curves curves through keys (num_keys xyz) of radii
  // (num_keys, >= 0), curve c having keys curve_first[c] .. curve_first[c + 1] - 1 (num_curves + 1
  // ascending offsets from 0 to num_keys), traced as Cycles 3.4's Catmull-Rom curves of `shape`;
  // materials: nullptr or one material per curve; random: nullptr (0) or the Curves Info node's
  // Random per curve (Cycles hashes the curve's index); normals: nullptr or the curves' normal
  // attribute per key (num_keys xyz, world space). A curve of fewer than 2 keys is skipped;
  // zero-length segments and zero radii are tolerated. Non-finite keys, radii or random values,
  // negative radii or bad offsets: std::invalid_argument. Returns the curve set's id.
  uint32_t add_curves(const float* keys, const float* radii, size_t num_keys, const int64_t* curve_first,
                      size_t num_curves, const int64_t* materials, CurveShape shape,
                      const float* random = nullptr, const float* normals = nullptr);
  size_t num_curve_segments() const;
  struct CurveSet;  // a curve set's storage (core/src/hair/curve_set.h), for its Embree filter
  // Point clouds (points/point_set.h), as Cycles renders them: num_points spheres, centres
  // (num_points xyz, world space) of radii (num_points), of one material. attributes: nullptr or
  // num_attributes layers of num_points xyz each (layer a, point i at 3 * (a * num_points + i);
  // non-finite values read 0), named by attribute_ids, which the Attribute op reads at a point's
  // hit (Point Info's Random is one). A point whose centre is not finite (or beyond
  // kMaxCoordinate) or whose radius is not finite and > 0 is skipped. A bad material or more
  // than 64 layers: std::invalid_argument. Returns the point set's id.
  uint32_t add_points(const float* centres, const float* radii, size_t num_points, int64_t material,
                      const float* attributes = nullptr, const int32_t* attribute_ids = nullptr,
                      size_t num_attributes = 0);
  size_t num_points() const;  // points added (those skipped not counted)
  // A point set's object settings, as set_curves_settings gives a curve set's.
  void set_points_settings(uint32_t set, const ObjectSettings& settings);
  struct PointSet;

  // Instancing (a two-level BVH): a prototype is a mesh in object space, built once into its own
  // BVH, whose per-triangle `slots` (>= 0) index a material table given per instance, like
  // Blender's material slots (a slot past the table's end uses its last entry, as Cycles).
  // Arguments as add_mesh with slots for material_ids; slots nullptr = all 0. Returns its id.
  uint32_t add_prototype(const float* positions, size_t num_vertices, const int64_t* triangles,
                         size_t num_triangles, const float* corner_normals, const int64_t* slots,
                         const float* corner_uvs = nullptr);
  // Adds `count` instances of `prototype` with ids first, first + 1, ... (the returned first).
  // transforms: count row-major 3x4 object-to-world matrices (12 floats each). materials: the
  // slot -> material table, table_size entries shared by all (per_instance_tables false) or one
  // table per instance (count * table_size). Tables are stored once per distinct content.
  // A matrix with NaN/Inf, an entry beyond 1e12, or placing the prototype's vertex bounds beyond
  // 1e12 from the origin is rejected (std::invalid_argument), as is a request beyond the memory
  // budget (limits.h); a singular one (zero scale, or below 1e-5 in some direction: too thin for
  // Embree to trace it in object space) leaves its instance hidden until
  // set_instance_transforms gives it a regular matrix (see num_hidden_instances). Like add_mesh,
  // add_prototype/add_instances/set_instance_transforms/remove_instances throw
  // std::runtime_error while a render uses the scene (begin_render .. end_render).
  uint32_t add_instances(uint32_t prototype, const float* transforms, size_t count, const int64_t* materials,
                         size_t table_size, bool per_instance_tables = false);
  // Moves instances (count ids and 12 floats each); only the top-level BVH is rebuilt at commit.
  void set_instance_transforms(const int64_t* ids, const float* transforms, size_t count);
  void remove_instances(const int64_t* ids, size_t count);
  size_t num_prototypes() const { return prototypes_.size(); }
  size_t num_instances() const { return live_instances_; }          // added and not removed
  size_t num_hidden_instances() const { return hidden_instances_; }  // of those, (near-)singular
  size_t num_material_tables() const;  // distinct (prototype, material table) pairs

  // An HDRI world: texture `id` as an equirectangular environment, times strength.
  void set_world_texture(uint32_t id, float strength);
  // The world's node graph: shader program `program` (from add_shader_program), its radiance in
  // register radiance_register (emission_shader.h), NEE sampling a map `resolution` cells
  // wide (Cycles' world Map Resolution), and the cone of `sun` where its half angle is above 0
  // (a Sky Texture's sun disc: Cycles' sun guiding). Throws std::invalid_argument naming a bad
  // argument.
  void set_world_program(uint32_t program, int radiance_register, int resolution, const SunGuide& sun = {});
  // The light added last takes shader program `program`'s radiance register as its node graph
  // (Lights::set_last_light_shader). Throws std::invalid_argument naming a bad argument.
  void set_light_program(uint32_t program, int radiance_register);
  Lights& lights() { return lights_; }  // C++ set-up; bindings use edit_lights
  const Lights& lights() const { return lights_; }
  // Runs edit on the lights unless a render is using the scene (then std::runtime_error).
  void edit_lights(const std::function<void(Lights&)>& edit);
  // The camera may change while renders run (each copies it when it starts).
  void set_camera(const CameraParams& camera) {
    std::lock_guard<std::mutex> lock(mutex_);
    camera_ = camera;
  }
  CameraParams camera() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return camera_;
  }

  // Triangles traced: those of the world-space meshes plus, per visible instance, its prototype's.
  size_t num_triangles() const;
  size_t num_materials() const { return materials_.size(); }
  const Material& material(uint32_t i) const { return materials_[i]; }

  // Builds the BVH and the emissive-triangle light if the scene changed since the last commit.
  // Must precede intersect/occluded.
  void commit();
  // A render holds the scene read-only from begin_render (default material if none, commit,
  // light selection) to end_render; meanwhile add_*, set_world_texture and edit_lights throw
  // std::runtime_error instead of racing with the render threads. Renders may overlap.
  void begin_render(LightSelection selection);
  void end_render() { --renders_; }
  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  // The nearest hit of the ray on `object` (SurfaceHit::object) alone, other objects' surfaces
  // passed (what a subsurface walk sees: Cycles' local intersection).
  bool intersect_object(Ray ray, uint32_t object, SurfaceHit& hit) const;
  // intersect of up to kPacketSize coherent rays at once (an 8-wide Embree packet: camera rays
  // of neighbouring samples): the same hits, bit for bit, as intersect of each. found[i]: hit.
  static constexpr int kPacketSize = 8;
  void intersect_packet(const Ray* rays, int n, SurfaceHit* hits, bool* found) const;
  bool occluded(const Vec3& origin, const Vec3& dir, float tmin, float tmax) const override;
  // Local queries (ShaderTracer): answered once commit() has built the objects' own BVHs, which
  // it does only when some shader program traces local rays (ShaderProgram::local_queries).
  bool local_occluded(uint32_t object, const Vec3& origin, const Vec3& dir, float tmin, float tmax) const override;
  int local_hits(uint32_t object, const Vec3& origin, const Vec3& dir, float tmax, uint32_t seed, LocalHit* hits,
                 int max_hits) const override;
  // The Raycast node's query (ShaderTracer::raycast; scene_raycast.cpp): an only_object query is
  // a local one, answered once commit() has built the objects' own BVHs.
  bool raycast(const Vec3& origin, const Vec3& dir, float tmin, float tmax, uint32_t only_object, uint32_t skip_object,
               uint32_t skip_prim, RaycastHit& hit) const override;
  void* embree_scene() const { return scene_; }  // the RTCScene, for raw-Embree measurements (ray_replay.h)
  void bounds(Vec3& lo, Vec3& hi) const;  // of everything traced, after commit (lo > hi: nothing, or not committed)
  // The flat pieces that the triangles of material `material` make (mirror_images.h): either a
  // few exact planes shaded flat (a quad, a box: every corner inside its plane to a relative 1e-5,
  // corner normals along its normal), or else one nearly flat sheet (a wavy water surface: every
  // face and corner normal within kMaxPlaneTilt of the area-weighted mean normal, facing one way).
  // Each piece: a point on its (mean) plane, its unit normal (as its largest triangle winds), how
  // far its normals tilt from it and its points lie off it, and a sphere bounding its triangles. Empty when no world-space
  // triangle has the material, they make neither, or a prototype uses it (instances are not
  // examined).
  static constexpr size_t kMaxPlanes = 8;
  static constexpr float kMaxPlaneTilt = 0.35f;  // radians (20 degrees)
  struct Plane {
    Vec3 point{0.0f}, normal{0.0f, 0.0f, 1.0f};
    float tilt = 0.0f;   // 0: exact
    float depth = 0.0f;  // how far its points lie from its plane (0: exact)
    Vec3 center{0.0f};  // the bounding sphere
    float radius = 0.0f;
  };
  std::vector<Plane> material_planes(uint32_t material) const;
  // The sphere all triangles of material `material` make (every vertex within 0.5 % of the radius
  // from the centre of their bounds, the bounds a cube): its centre and radius; nullopt otherwise,
  // or when a prototype uses the material.
  struct Sphere {
    Vec3 center{0.0f};
    float radius = 0.0f;
  };
  std::optional<Sphere> material_sphere(uint32_t material) const;
  // A sphere bounding every triangle of material `material` (about the centre of their bounds);
  // nullopt when none has it or a prototype uses it (its instances are not examined).
  std::optional<Sphere> material_bounds(uint32_t material) const;

 private:
  struct Mesh;
  struct Prototype;
  struct Binding;
  struct Instance;
  struct LocalScenes;  // scene_local.cpp: a BVH per object for the local queries
  void check_device(const char* during) const;
  void build_local_scenes();
  // The BVH object's local queries trace (an RTCScene), the ray taken into its space; nullptr
  // when there is none (no object, a hidden instance, no local BVHs built).
  void* local_scene(uint32_t object, Vec3& origin, Vec3& dir) const;
  // The hit on segment prim of curve set `set` at Embree's u, t along the ray (origin, dir).
  void curve_hit(uint32_t set, uint32_t prim, float u, const Vec3& origin, const Vec3& dir, float t,
                 SurfaceHit& hit) const;
  // The hit on point prim of point set `set`, t along the ray (origin, dir).
  void point_hit(uint32_t set, uint32_t prim, const Vec3& origin, const Vec3& dir, float t, SurfaceHit& hit) const;
  ObjectSettings adopt_settings(const ObjectSettings& settings);  // (scene_pass_indices.cpp)
  // The hit described by Embree's answer `rayhit` (an RTCRayHit) to a ray along dir; false: a miss.
  bool surface_hit(const void* rayhit, const Vec3& dir, SurfaceHit& hit) const;
  // The hit at Embree's barycentrics (u, v) of triangle prim of owner (a mesh index, or an instance
  // index | kInstanceBit: geometry_owner_'s values) seen along dir; all but its t.
  void triangle_hit(uint32_t owner, uint32_t prim, float u, float v, const Vec3& dir, SurfaceHit& hit) const;
  // The radiance a mesh light's sample emits (MeshLight::EmissionLookup): its material's emission
  // with the shader globals Cycles' next-event estimation gives it (no ray differentials).
  Vec3 sampled_emission(const EmissiveTriangle& triangle, const Vec2& b, const Vec3& wi, const PathState& seen_by) const;
  std::unique_ptr<Mesh> make_mesh(const float* positions, size_t num_vertices, const int64_t* triangles,
                                  size_t num_triangles, const float* corner_normals, const int64_t* materials,
                                  const float* corner_uvs, bool slots) const;
  void* new_triangle_geometry(const Mesh& mesh) const;  // RTCGeometry, committed
  const Instance& live_instance(int64_t id, const char* during) const;
  // An instance's object-to-world transform at the thread's ray time (its frame's without motion).
  std::array<float, 12> instance_transform(const Instance& instance) const;
  void place_instance(Instance& instance, const float* transform);
  // Throws std::invalid_argument("<which> ...") unless the 3x4 matrix m keeps prototype within
  // kMaxCoordinate (limits.h): finite entries within 1e12, the transformed vertex bounds too.
  void check_transform(const float* m, uint32_t prototype, const std::string& which) const;
  void check_idle(const char* change) const;  // with mutex_ held
  Vec3 bump_mapped(const MaterialTextures& t, const SurfaceHit& hit, const Vec3& n, const ShaderGlobals& g) const;
  // Runs the material's shader program at uv and writes the inputs it feeds into m.
  // regs: where it runs (kMaxRegisters entries), or nullptr for a local array.
  void apply_program(const MaterialTextures& t, const ShaderGlobals& g, Material& m, glm::vec4* regs = nullptr) const;
  // A Ray Portal closure's material at a hit (its Color, Position and Direction).
  Material portal_material(uint32_t id, const ShaderGlobals& g) const;
  void check_program_outputs(const ShaderOutputs& outputs) const;  // throws std::invalid_argument

  mutable std::mutex mutex_;  // changes vs. begin_render, and the camera
  std::atomic<int> renders_{0};

  std::vector<Material> materials_;
  std::vector<MaterialTextures> material_textures_;
  std::vector<int32_t> mixture_index_;  // per material: index in mixtures_, or -1
  std::vector<Mixture> mixtures_;
  SceneMedia media_;
  std::vector<std::shared_ptr<const Texture>> textures_;
  std::vector<ShaderProgram> programs_;
  std::vector<std::shared_ptr<const VolumeGrid>> volume_grids_;
  std::vector<std::unique_ptr<Mesh>> meshes_;  // world-space meshes, in the order added
  std::vector<std::unique_ptr<CurveSet>> curve_sets_;  // hair strands, in the order added
  std::vector<std::unique_ptr<PointSet>> point_sets_;  // point clouds, in the order added
  // Instances' constant attributes: instance i's layer a at i * ids.size() + a (the vector may
  // end before the last instances: those have none).
  std::vector<Vec3> instance_constants_;
  std::vector<float> material_pass_indices_;
  bool object_holdouts_ = false;   // some mesh or instance is a holdout
  bool shadow_catchers_ = false;   // some mesh or instance is a shadow catcher
  bool catcher_masks_dirty_ = false;  // the geometries' masks are to be set again at commit
  void apply_catcher_masks();      // every geometry's mask from its object's shadow catcher flag
  ExtraPasses extra_passes_;
  Cryptomatte cryptomatte_;
  bool mixture_holdouts_ = false;  // some mixture has a Holdout closure
  std::vector<int32_t> instance_constant_ids_;
  std::vector<std::unique_ptr<Prototype>> prototypes_;
  std::vector<Binding> bindings_;  // distinct (prototype, material table) pairs
  std::map<std::vector<uint32_t>, uint32_t> binding_ids_;  // {prototype, table...} -> binding
  std::vector<Instance> instances_;
  // Embree geometry id in the top-level scene -> mesh index, or instance index | kInstanceBit.
  std::vector<uint32_t> geometry_owner_;
  size_t live_instances_ = 0, hidden_instances_ = 0;
  Lights lights_;
  CameraParams camera_;
  void* device_ = nullptr;  // RTCDevice
  void* scene_ = nullptr;   // RTCScene
  std::unique_ptr<LocalScenes> local_scenes_;  // built by commit() when programs need them
  void build_mesh_light();
  bool dirty_ = true;
  bool emitters_dirty_ = true;
  bool has_motion_ = false;
  FrameMotion frame_motion_;
  // Mesh `mesh`'s Embree geometry id in the top-level scene (meshes are attached in order).
  uint32_t mesh_geometry_id(uint32_t mesh) const;
  mutable std::string embree_error_;
  friend void embree_error_callback(void*, int, const char*);
};

}  // namespace torrance
