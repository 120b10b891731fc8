// Lights in Blender's units, so a scene is equally bright in Torrance and in Cycles.
//
//  * Sun: strength S in W/m^2 is the irradiance on a surface facing it. Its disk of angular diameter
//    `angle` is a cone of uniform radiance S / (solid angle); angle 0 makes it a delta light.
//  * Point: power P in W, I = P / (4 pi) W/sr. With radius r > 0 it is, as in Cycles 3.4, a disk of
//    radius r facing the shaded point, of radiance I / (pi r^2) (so soft shadows; near the light it
//    gives less than a sphere would: E = pi L r^2 / (d^2 + r^2) on axis); r = 0: a delta light.
//  * Spot: a point light times Blender 3.4's spot attenuation: 0 outside the cone, c inside it and
//    c * smoothstep in the blend band (c = cosine to the axis; the extra factor c is Cycles 3.4's).
//    Power is not renormalised to the cone.
//  * Area: rectangle (square) or ellipse (disk) of power P, one-sided along its normal, with
//    radiance P / (4 A): Cycles' convention. Rectangles are sampled by solid angle (spherical
//    rectangles, Urena et al. 2013), ellipses by area.
//  * World: uniform radiance colour * strength from every direction.
// Lights are invisible to camera rays (Blender's default), but BSDF-sampled rays see them, weighted
// by multiple importance sampling against next-event estimation.
#pragma once

#include "torrance/lights/environment.h"
#include "torrance/lights/light_linking.h"
#include "torrance/lights/lights_common.h"
#include "torrance/lights/mesh_light.h"

#include <optional>

#include <limits>
#include <variant>
#include <vector>

namespace torrance {

class LightChoice;

class SunLight {
 public:
  SunLight(const Vec3& direction, float strength, const Vec3& color, float angle);
  LightSample sample(const Vec3& p, const Vec3& n, const Vec2& u) const;
  float importance(const Vec3& p, const Vec3& n) const;
  bool hit(const Vec3& p, const Vec3& n, const Vec3& dir, float t_max, LightHit& out) const;
  // Light tracing (light_emission.cpp, lights_common.h's EmissionTargets): a ray of the sun's
  // beam through a target, and the power the beam brings into the targets.
  EmittedRay emit(const glm::vec4& u, float u_target, const EmissionTargets& targets) const;
  float emitted_power(const EmissionTargets& targets) const;
  bool is_delta() const { return one_minus_cos_ <= 0.0f; }
  Vec3 to_light() const { return to_light_; }
  float one_minus_cos() const { return one_minus_cos_; }  // of its cone's half-angle

 private:
  Vec3 to_light_, irradiance_;
  float one_minus_cos_;  // of the cone's half-angle; 0 for a delta sun
  float sin_half_;       // sin of the cone's half-angle, for importance()
  float luminance_;      // of irradiance_
};

struct SpotShape {
  Vec3 axis{0.0f, 0.0f, -1.0f};  // unit, the direction the spot points
  float cos_half_angle = -1.0f;  // cos(spot_size / 2); -1 = not a spot
  float blend_width = 0.0f;      // (1 - cos_half_angle) * spot_blend
  // Cycles 3.x also multiplies by the cosine to the axis (its attenuation starts from it);
  // Cycles 4.x does not (light/spot.h: the blend's smoothstep alone).
  bool cosine = true;
};

class PointLight {
 public:
  PointLight(const Vec3& position, float power, const Vec3& color, float radius, const SpotShape& spot = {});
  LightSample sample(const Vec3& p, const Vec3& n, const Vec2& u) const;
  float importance(const Vec3& p, const Vec3& n) const;
  bool hit(const Vec3& p, const Vec3& n, const Vec3& dir, float t_max, LightHit& out) const;
  // Light tracing: a direction from the centre towards a target, leaving the disk of the radius
  // that faces it, weighed by the intensity (a spot's cone and blend) that way; the power the
  // light sends towards the targets.
  EmittedRay emit(const glm::vec4& u, float u_target, const EmissionTargets& targets) const;
  float emitted_power(const EmissionTargets& targets) const;
  bool is_delta() const { return radius_ <= 0.0f; }
  const Vec3& position() const { return position_; }
  float radius() const { return radius_; }
  bool is_spot() const { return spot_.cos_half_angle > -1.0f; }
  const SpotShape& spot() const { return spot_; }
  float intensity_luminance() const { return luminance_; }  // |luminance| of its radiant intensity

 private:
  float spot_attenuation(const Vec3& p) const;
  Vec3 position_, intensity_;
  float luminance_;  // of intensity_, for importance()
  float radius_;
  SpotShape spot_;
};

class AreaLight {
 public:
  // centre; full-size edge vectors (object X * size, object Y * size_y, scale included), which
  // must be perpendicular; the light's normal is theirs, on the side of `normal` (Blender: the
  // light's -Z). std::invalid_argument for sheared edges or a `normal` in the light's plane.
  AreaLight(const Vec3& center, const Vec3& edge_u, const Vec3& edge_v, const Vec3& normal, bool ellipse,
            float power, const Vec3& color, float spread);
  LightSample sample(const Vec3& p, const Vec3& n, const Vec2& u) const;
  float importance(const Vec3& p, const Vec3& n) const;
  bool hit(const Vec3& p, const Vec3& n, const Vec3& dir, float t_max, LightHit& out) const;
  // Light tracing: a point of the light by area, a direction from it towards a target (the
  // cosine and the spread's attenuation in the weight); the power it sends out.
  EmittedRay emit(const glm::vec4& u, float u_target, const EmissionTargets& targets) const;
  float emitted_power(const EmissionTargets& targets) const;
  float area() const { return area_; }
  const Vec3& center() const { return center_; }
  const Vec3& normal() const { return normal_; }
  // |luminance| of its radiant intensity along its normal (radiance x area).
  float intensity_luminance() const { return std::abs(luminance(radiance_)) * area_; }
  // The radius of a sphere about the centre that holds the light.
  float extent() const { return 0.5f * std::sqrt(glm::dot(edge_u_, edge_u_) + glm::dot(edge_v_, edge_v_)); }

 private:
  float spread_attenuation(float cos_emit) const;
  Vec3 center_, edge_u_, edge_v_, normal_, radiance_;
  float area_;
  bool ellipse_;
  float tan_half_spread_ = 0.0f, spread_norm_ = 1.0f;  // unused at the default 180 degrees
  bool has_spread_ = false;
};

// The world: a uniform colour (NEE samples the cosine around the shading normal) or a map (an
// HDRI or the world's node graph; NEE samples the map's own distribution). state: the ray's (a
// world's node graph reads it; NEE reads it with kRayEmission).
class WorldLight {
 public:
  explicit WorldLight(const Vec3& radiance)
      : radiance_(radiance),
        luminance_(std::abs(luminance(radiance))),
        black_(!(max_component(glm::abs(radiance)) > 0.0f)) {}
  explicit WorldLight(std::shared_ptr<const EnvironmentMap> map) : map_(std::move(map)) {}
  LightSample sample(const Vec3& p, const Vec3& n, const Vec2& u, const PathState& receiver = {}) const;
  float importance(const Vec3&, const Vec3&) const { return (map_ ? map_->average_luminance() : luminance_) * kPi; }
  bool hit(const Vec3& p, const Vec3& n, const Vec3& dir, float t_max, LightHit& out,
           const PathState& state = {}) const;
  Vec3 radiance(const Vec3& dir, const PathState& state = {}) const {
    return map_ ? map_->radiance(dir, state) : radiance_;
  }
  // A map whose samples all came out black may still shine on some rays (a node graph reading
  // the Light Path): only a uniform black world is no world.
  bool black() const { return black_; }
  bool is_map() const { return map_ != nullptr; }
  bool in_nee() const { return map_ && map_->average_luminance() > 0.0f; }
  bool reads_path() const { return map_ && map_->reads_path(); }

 private:
  Vec3 radiance_{0.0f};
  std::shared_ptr<const EnvironmentMap> map_;
  // Of a uniform colour, made with it (every ray that leaves the scene asks black()): |luminance|
  // of radiance_, and whether it is black (a negative world is not).
  float luminance_ = 0.0f;
  bool black_ = false;
};

// How next-event estimation chooses a light at a shading point.
enum class LightSelection {
  Uniform,       // every light equally often (Cycles 3.4)
  Irradiance,    // in proportion to an unshadowed estimate of the irradiance each light brings
  Contribution,  // Irradiance mixed with irradiance x the BSDF's response (light_choice.h)
};

class Lights {
 public:
  void add_sun(const Vec3& direction, float strength, const Vec3& color, float angle);
  void add_point(const Vec3& position, float power, const Vec3& color, float radius);
  // cosine_falloff: SpotShape::cosine (Cycles 3.x true, 4.x false).
  void add_spot(const Vec3& position, const Vec3& direction, float power, const Vec3& color, float radius,
                float spot_size, float spot_blend, bool cosine_falloff = true);
  void add_area(const Vec3& center, const Vec3& edge_u, const Vec3& edge_v, const Vec3& direction, bool ellipse,
                float power, const Vec3& color, float spread);
  void set_world(const Vec3& color, float strength);
  void set_world_map(std::shared_ptr<const Texture> image, float strength);
  // The world's node graph (emission_shader.h), its NEE map `resolution` cells wide.
  // sun: a sun disc in it to sample as Cycles' sun guiding does (half_angle 0: none).
  void set_world_shader(std::shared_ptr<const EmissionShader> shader, int resolution, const SunGuide& sun = {});
  // The node graph of the light added last (emission_shader.h): its radiance at each point of
  // the light, seen from the receiver, multiplies the light's colour x power (Cycles' light
  // shader: a Light Falloff, a texture).
  void set_last_light_shader(std::shared_ptr<const EmissionShader> shader);
  // Light groups (extra_passes.h): of the light added last, of the world; -1: none.
  void set_last_light_group(int group);
  void set_world_group(int group) { world_group_ = int8_t(group); }
  int world_group() const { return world_group_; }
  // The light group of NEE strategy `index`'s sample ls (an emissive triangle's its own).
  int light_group(size_t index, const LightSample& ls) const {
    if (index < lights_.size()) return index < groups_.size() ? groups_[index] : -1;
    return mesh_ && index == lights_.size() ? ls.light_group : world_group_;
  }
  // Light linking (light_linking.h): the emitter table's entries 1.. (empty: no linking), the
  // entry of the light added last (0: unlinked), and the entry of NEE strategy `index`'s sample
  // ls (an emissive triangle's object's; the world's is 0).
  void set_link_table(const std::vector<EmitterLinks>& table) { links_.set(table); }
  void set_last_light_links(int entry);
  const LightLinks& links() const { return links_; }
  uint8_t link_entry(size_t index, const LightSample& ls) const {
    if (index < lights_.size()) return index < link_entries_.size() ? link_entries_[index] : 0;
    return mesh_ && index == lights_.size() ? ls.emitter_links : 0;
  }
  // Emissive triangles (replaces any previous set); nullopt removes them.
  void set_mesh_light(std::optional<MeshLight> emitters) { mesh_ = std::move(emitters); }
  // MIS density of NEE producing point q on emissive triangle `triangle` from (p, n).
  float mesh_light_pdf(size_t triangle, const Vec3& p, const Vec3& n, const Vec3& q, bool two_sided = false,
                       const LightChoice* choice = nullptr) const;
  size_t num_emissive_triangles() const { return mesh_ ? mesh_->size() : 0; }

  // The NEE strategies: each light in the order added, the emissive triangles (as one), then the
  // world if it is an HDRI. A uniform world is left to BSDF sampling, which already draws
  // directions in proportion to f cos: NEE could only match it, at the cost of a shadow ray.
  size_t count() const { return lights_.size() + (mesh_ ? 1 : 0) + (world_in_nee() ? 1 : 0); }
  void set_selection(LightSelection s) { selection_ = s; }
  LightSelection selection() const { return selection_; }

  struct Choice {
    size_t index = 0;
    float probability = 0.0f;  // 0: no light can contribute here
  };
  // Chooses the light for NEE at point p with shading normal n. two_sided: the surface also
  // transmits (glass), so lights behind it count too (the same flag for all four calls).
  Choice select(const Vec3& p, const Vec3& n, float u, bool two_sided = false) const;
  float selection_probability(size_t index, const Vec3& p, const Vec3& n, bool two_sided = false) const;
  // Unnormalised selection weight of strategy `index` at (p, n): its unshadowed irradiance there,
  // bounded above so that lights partly above the horizon keep a chance (1 in Uniform mode).
  float selection_weight(size_t index, const Vec3& p, const Vec3& n, bool two_sided = false) const {
    return importance(index, p, n, two_sided);
  }
  // The unit direction from p to strategy `index`'s centre (a sun: towards it); false for the
  // emissive triangles and the world, which have none.
  bool direction_hint(size_t index, const Vec3& p, const Vec3& n, Vec3& out) const;

  // receiver: the path's state at p (an emitting mesh's shader reads it, as Cycles' next-event
  // estimation does: PathState's kRayEmission).
  LightSample sample(size_t index, const Vec3& p, const Vec3& shading_normal, const Vec2& u,
                     bool two_sided = false, const PathState& receiver = {}) const;

  // Radiance, MIS-weighted against NEE, that a BSDF-sampled ray leaving p_prev (where NEE used
  // shading normal n_prev) receives from lights it passes before distance t_max (infinite if
  // the ray escaped): spheres, area lights and, if escaped, the world and visible suns.
  // prev_choice: the LightChoice NEE used at p_prev (its probabilities), if any.
  // share: each light's light is multiplied by share->of(its index) (the caller shares it with
  // another strategy: mirror_images.h); nullptr: by 1. escaped: the ray's path state, which the
  // world's node graph reads if the ray escaped. by_group (if given): each light's part is also
  // added to by_group[its light group] (light_group; none for lights of no group).
  // Lights nearer than t_min are left out (those the ray met before it passed a thin wall).
  // receiver_set: p_prev's object's (light_linking.h): only lights lighting it count, and
  // shadow-linked ones only after a delta lobe.
  Vec3 emission_along_ray(const Vec3& p_prev, const Vec3& n_prev, const Vec3& dir, float t_min, float t_max, float bsdf_pdf,
                          bool bsdf_delta, bool two_sided = false, const LightChoice* prev_choice = nullptr,
                          const LightShare* share = nullptr, const PathState& escaped = {},
                          Vec3* by_group = nullptr, uint8_t receiver_set = 0) const;
  // Shadow linking after a delta lobe (light_linking.h): the radiance of the shadow-linked lights
  // (not the world) that a ray from p_prev along dir meets between t_min and t_max (infinite:
  // suns too), that light receiver_set and whose shadow sets leave out every blocker set in
  // `passed` (bit s: set s; the surfaces the ray went through before t_min). by_group as above;
  // `attenuation` (in media): what each lamp's light keeps on its way.
  struct LinkedAttenuation {
    // The share of an emitter's light (its blocker sets shadow_sets) that reaches p_prev from
    // `distance` along the ray.
    virtual Vec3 at(float distance, uint64_t shadow_sets) const = 0;

   protected:
    ~LinkedAttenuation() = default;
  };
  Vec3 shadow_linked_along_ray(const Vec3& p_prev, const Vec3& n_prev, const Vec3& dir, float t_min, float t_max,
                               uint64_t passed, uint8_t receiver_set, Vec3* by_group = nullptr,
                               const LinkedAttenuation* attenuation = nullptr) const;
  // What a ray from p along dir sees of strategy `index` alone, unoccluded (its MIS density too).
  bool hit(size_t index, const Vec3& p, const Vec3& n, const Vec3& dir, LightHit& out) const;
  // Light tracing (caustics.h): whether light `index` can emit rays (a sun, point, spot or area
  // light without a node graph: the emissive triangles and the world cannot), a ray of it, and
  // the power it sends into the scene's sphere.
  bool can_emit(size_t index) const {
    return index < lights_.size() && (index >= shaders_.size() || !shaders_[index]);
  }
  EmittedRay emit(size_t index, const glm::vec4& u, float u_target, const EmissionTargets& targets) const;
  float emitted_power(size_t index, const EmissionTargets& targets) const;
  // Strategy `index`'s light of each kind, or nullptr when it is another kind.
  const SunLight* sun(size_t index) const { return get<SunLight>(index); }
  const PointLight* point(size_t index) const { return get<PointLight>(index); }
  const AreaLight* area(size_t index) const { return get<AreaLight>(index); }

  // False when no BSDF-sampled ray can ever see a light (only delta lights, no world or
  // emitting shapes), so emission_along_ray can be skipped.
  bool any_hittable() const;
  // escaped: the state of the ray that left the scene (emission_along_ray's `escaped` too).
  Vec3 world_radiance(const Vec3& dir, const PathState& escaped = {}) const { return world_.radiance(dir, escaped); }
  bool has_world() const { return !world_.black(); }
  bool world_in_nee() const { return world_.in_nee(); }
  // Whether the world's radiance depends on the ray's path state (the path tracer tracks it).
  bool world_reads_path() const { return world_.reads_path(); }

 private:
  // Calls f with the concrete light of NEE strategy `index` (see count()).
  template <typename F>
  auto visit(size_t index, F&& f) const {
    if (index < lights_.size()) return std::visit(f, lights_[index]);
    if (mesh_ && index == lights_.size()) return f(*mesh_);
    return f(world_);
  }
  float importance(size_t index, const Vec3& p, const Vec3& n, bool two_sided = false) const;
  // The factor light `index`'s shader (1 without one) gives the point at `distance` along wi
  // from p (or, infinitely far, in direction wi).
  Vec3 shader_factor(size_t index, const Vec3& p, const Vec3& wi, float distance, const PathState& state) const;
  template <typename Light>
  const Light* get(size_t index) const {
    return index < lights_.size() ? std::get_if<Light>(&lights_[index]) : nullptr;
  }

  std::vector<std::variant<SunLight, PointLight, AreaLight>> lights_;
  std::vector<std::shared_ptr<const EmissionShader>> shaders_;  // per light of lights_; null: none
  std::vector<int8_t> groups_;  // per light of lights_ (shorter: -1), its light group
  std::vector<uint8_t> link_entries_;  // per light of lights_ (shorter: 0), its light linking entry
  LightLinks links_;
  int8_t world_group_ = -1;
  std::optional<MeshLight> mesh_;
  WorldLight world_{Vec3(0.0f)};
  LightSelection selection_ = LightSelection::Contribution;
};

}  // namespace torrance
