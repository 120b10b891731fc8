// The path tracer of render() (integrator.cpp): one camera sample's radiance, split as Blender's
// passes, by trace_path compiled once per set of scene features (textures, light passes, lights a
// BSDF-sampled ray can hit, glass, alpha, mixtures), so that a scene pays only for what it has.
#pragma once

#include "torrance/integrator/roulette.h"
#include "torrance/integrator/guiding.h"
#include "torrance/integrator/first_bounce_splits.h"
#include "torrance/film/cryptomatte.h"
#include "torrance/film/extra_passes.h"
#include "torrance/integrator/integrator.h"
#include "torrance/integrator/bump_shadowing.h"
#include "torrance/bsdfs/material_bsdf.h"
#include "torrance/lights/mirror_images.h"
#include "torrance/util/sampling.h"
#include "media/medium_stack.h"
#include "film/shadow_catcher.h"

#include <array>
#include <optional>
#include <vector>

namespace torrance {

class CausticPartition;
class MotionVectors;

struct PathContext {
  const Scene& scene;
  const Lights& lights;
  const RenderSettings& settings;
  std::vector<MaterialBsdf> bsdfs;  // one per material, built once per render
  Vec3 camera_forward;
  float pixel_spread;  // radians per pixel: texture footprints grow with the path's length
  float pixel_width = 0.0f;  // Camera::pixel_width: the ray differentials' length at the camera
  // A panoramic camera's position: the Depth pass is the distance from it (Cycles'
  // camera_z_depth), not the distance along camera_forward.
  std::optional<Vec3> depth_from = std::nullopt;
  // Path guiding (RenderSettings::guiding): the field sampled where it has learned something, and
  // whether this pass also records into it (a training pass). Null: no guiding.
  GuidingField* guide = nullptr;
  bool guide_training = false;
  // Efficiency-aware Russian roulette (roulette.h): learned and used; null: the classic rule only.
  RouletteField* roulette = nullptr;
  // The caustic paths the light tracer takes (caustics.h); null: none.
  const CausticPartition* caustics = nullptr;
  // Suns seen in planar mirrors (mirror_images.h), sampled by NEE; null: none, or not used.
  const MirrorImages* mirror_images = nullptr;
  bool nee_every_light = false;  // RenderSettings::nee_every_light, in a scene of few enough lights
  int first_bounce_splits = 1;   // branches at the first hit (first_bounce_splits.h): set or chosen
  // Per material, what shading it reads of ShaderGlobals (Scene::globals_read; empty: all).
  std::vector<uint8_t> globals_read = {};
  // The camera's position and kind, for the Mist pass's distance (Cycles' camera_distance).
  Vec3 camera_position{0.0f};
  bool orthographic = false;
  // The camera's right, up and forward: Cycles' camera space, of the Denoising Normal pass.
  std::array<Vec3, 3> camera_axes{Vec3(1.0f, 0.0f, 0.0f), Vec3(0.0f, 1.0f, 0.0f), Vec3(0.0f, 0.0f, -1.0f)};
  // The media around the camera (media/medium_stack.h), where paths start; empty without volumes.
  MediumStack camera_media = {};
  // Shadow catchers (film/shadow_catcher.h): camera paths split at the first catcher they meet
  // (false without catchers, and for the catcher-only half).
  bool split_at_catchers = false;
  // The catcher-only half (shadow_catcher_split.h): its camera ray's media are the split
  // path's, whose throughput it takes, so its first segment passes them untouched.
  bool catcher_half = false;
  // The Vector pass's motion of the first surfaces (film/motion_vectors.h); null: none made.
  const MotionVectors* motion_vectors = nullptr;  // Some material disperses (has_dispersion): each path draws a wavelength (dispersion.h).
  bool dispersion = false;
};

// Where a camera sample goes.
struct PixelSample {
  int x = 0, y = 0;           // in the rendered window
  float guide_weight = 1.0f;  // what the path records for guiding is multiplied by it (pixel_weight, guiding.h)
  BranchRecord* record = nullptr;  // the pilot's (first_bounce_splits.h); null in the render
  // The media the path starts in, if not the camera's: the catcher-only half's, the split's.
  const MediumStack* start_media = nullptr;
};

// Everything one camera sample brings back, split as Blender's passes.
struct PathRadiance {
  Vec3 emission{0.0f}, environment{0.0f};
  Vec3 diffuse_direct{0.0f}, diffuse_indirect{0.0f}, glossy_direct{0.0f}, glossy_indirect{0.0f};
  float alpha = 1.0f;
  float depth = 1e10f;  // the Depth pass: set by first_sample_data (film_passes.h) only
  Vec3 normal{0.0f}, albedo{0.0f}, glossy_color{0.0f};
  // The data passes of the first hit (0 on the world): the Mist pass's (1 - mist) x the mean of
  // the transparency the camera ray passed, the active UV map's (u, v, 1), the AO pass's
  // unoccluded share (times that transparency), the position, the object's and the material's
  // pass index.
  float mist = 0.0f;
  Vec3 uv{0.0f}, ao{0.0f}, position{0.0f};
  float object_index = 0.0f, material_index = 0.0f;
  // Cycles' denoising features (denoising_features.h): Denoising Albedo, Normal (camera space)
  // and Depth.
  Vec3 denoising_albedo{0.0f}, denoising_normal{0.0f};
  float denoising_depth = 0.0f;
  // The Vector pass's (film/motion_vectors.h) vector of the first surface, and 1 where one was made.
  glm::vec4 motion{0.0f};
  float motion_weight = 0.0f;
  // The scene's AOV and light-group channels (extra_passes.h): the first
  // Scene::extra_passes().channels() are set by the tracer, the rest left uninitialised.
  float extras[kMaxExtraChannels];
  // The surfaces the camera ray gave Cryptomatte ids to (film/cryptomatte.h; only with it).
  CryptomatteSample cryptomatte;
  // The split at a shadow catcher (film/shadow_catcher.h; only in scenes with catchers).
  ShadowCatcherSample catcher;
  // With media: those at the split (shadow_catcher_split.h); optional, so that a sample does not
  // zero a MediumStack it never uses.
  std::optional<MediumStack> catcher_media;

  Vec3 combined() const {
    return emission + environment + diffuse_direct + diffuse_indirect + glossy_direct + glossy_indirect;
  }
};

// Offsets a ray origin off the surface along the geometric normal, on the side `dir` leaves to.
// Always inlined: GCC had come to keep it out of line in the path loop.
[[gnu::always_inline]] inline Vec3 offset_origin(const Vec3& p, const Vec3& ng, const Vec3& dir) {
  const float scale = std::max(1.0f, std::max(std::abs(p.x), std::max(std::abs(p.y), std::abs(p.z))));
  const float eps = 2e-5f * scale;
  return p + (glm::dot(ng, dir) >= 0.0f ? eps : -eps) * ng;
}

// Whether light can leave (or arrive) along world direction wi at a vertex with geometric normal
// ng (turned towards the viewer) and wi's shading-frame z wi_z: an opaque surface only above its
// geometric surface; a transmitting one on either side, where the geometric and the shading
// normal agree on the side (as Cycles: a direction they disagree on carries nothing).
inline bool leaves_geometric_side(const Vec3& wi, const Vec3& ng, float wi_z, bool transmits) {
  const float cos_geometric = glm::dot(wi, ng);
  return transmits ? cos_geometric != 0.0f && (cos_geometric > 0.0f) == (wi_z > 0.0f) : cos_geometric > 0.0f;
}

// The camera ray's answer when the integrator traced it already (Scene::intersect_packet): the
// hit lives in the integrator's packet (not copied per sample: a SurfaceHit is large).
struct FirstHit {
  const SurfaceHit* hit = nullptr;
  bool found = false;
};

// first: the camera ray's answer, or nullptr to trace it.
using TraceFn = PathRadiance (*)(const PathContext&, Ray, SobolSampler&, const FirstHit* first, const PixelSample& pixel);

// The path tracer for the scene's features under the settings (specialize false: the generic
// one, which has every feature).
TraceFn select_path_tracer(const Scene& scene, const RenderSettings& settings);

// Whether some material of the scene has alpha below 1 or an alpha texture.
bool has_alpha(const Scene& scene);
// Whether some material (or a mixture's closure) has a subsurface closure.
bool has_subsurface(const Scene& scene);
// Whether some material (or a mixture's closure) has dispersion (Material::dispersion > 0).
bool has_dispersion(const Scene& scene);

}  // namespace torrance
