// The shadow catcher as Cycles 3.4 writes and reads it (kernel/integrator/shadow_catcher.h,
// kernel/film/light_passes.h, kernel/film/read.h). A camera path that meets a catcher object
// (through transparency, not a holdout) splits there: this path goes on with the catcher as an
// ordinary object (Cycles' PATH_RAY_SHADOW_CATCHER_HIT: into Combined only), and a second one,
// from the same camera ray, sees only the catchers (PATH_RAY_SHADOW_CATCHER_PASS: into the
// catcher pass only). Paths that split nowhere also make the matte (the CG objects alone).
// Per pixel the film sums: the matte's colour and alpha, the catcher-only light, the split
// samples (Shadow Catcher Sample Count) and, for an opaque film, the world behind the catcher.
#pragma once

#include "torrance/util/math.h"

#include <array>

namespace torrance {

// What the split brings of one camera sample (PathRadiance::catcher).
struct ShadowCatcherSample {
  bool split = false;          // the camera ray met a catcher
  Vec3 throughput{1.0f};       // the path's throughput there (transparency passed on the way)
  float alpha_at_split = 1.0f;  // the sample's alpha then (holdouts passed take theirs off)
  Vec3 before_split{0.0f};     // its light then: the matte's
  Vec3 catcher{0.0f};          // the catcher-only half's light (the Shadow Catcher pass's divisor)
  Vec3 background{0.0f};       // opaque film: the world along the camera ray, times throughput
};

// The film's channels of a sample: matte RGB, matte alpha, catcher-only RGB, split count, the
// Background pass's RGB (Cycles' PASS_BACKGROUND: the world seen directly, or behind a catcher).
constexpr int kShadowCatcherChannels = 11;
using ShadowCatcherValues = std::array<float, kShadowCatcherChannels>;

// combined, alpha, environment: the sample's Combined light, its alpha, its light of the world
// seen directly.
ShadowCatcherValues shadow_catcher_values(const ShadowCatcherSample& s, const Vec3& combined, float alpha,
                                          const Vec3& environment);

// How the film turns a pixel's means into Combined and the Shadow Catcher pass.
struct ShadowCatcherOutput {
  // Cycles' use_approximate_shadow_catcher (Blender: the view layer's Shadow Catcher pass off):
  // Combined is the matte over the catcher's shadow; else the matte alone.
  bool approximate = true;
  bool transparent_film = false;  // Film > Transparent
  bool catchers = false;          // the scene has some: the film keeps the channels above
  bool pass = false;              // the Shadow Catcher pass is requested (1 without catchers)
};

// The Shadow Catcher pass of a pixel (Cycles' film_calculate_shadow_catcher): the light with
// the CG objects over the light without them, per colour (1 where nothing was caught), over
// white by Combined's alpha. combined: the pixel's mean RGBA; catcher: its channels' means.
Vec3 shadow_catcher_pass(const double* combined, const double* catcher);
// Combined as Cycles shows it in a scene with catchers (film_calculate_shadow_catcher_matte_
// with_shadow when approximate, else the matte): RGBA.
std::array<float, 4> shadow_catcher_combined(const ShadowCatcherOutput& out, const double* combined,
                                             const double* catcher);

}  // namespace torrance
