// The path-tracing integrator: unidirectional paths with next-event estimation to every light,
// multiple importance sampling against BSDF sampling, Russian roulette and a bounce limit.
// Progressive: samples are rendered in passes over TBB-parallel tiles; every pass is reported.
// Deterministic: a pixel's samples depend only on (pixel, sample index, seed), never on threads.
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/integrator/guiding.h"
#include "torrance/scene/scene.h"

#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <optional>
#include <vector>

namespace torrance {

// Blender's render passes beyond Combined, as Cycles 3.4 writes them. The film divides the
// Diffuse and Glossy Direct/Indirect passes by Diffuse and Glossy Color (Cycles' division), so
// that Combined = Emit + Env + (DiffDir + DiffInd) x DiffCol + (GlossDir + GlossInd) x GlossCol.
enum Pass : uint32_t {
  kPassDepth = 1u << 0,             // distance from the camera plane, of the first sample (1e10: world)
  kPassNormal = 1u << 1,            // world-space shading normal at the first hit
  kPassAlbedo = 1u << 2,            // diffuse colour at the first hit: base colour (1 - metallic)(1 - transmission)
  kPassDiffuseDirect = 1u << 3,     // light reflected by the first hit's diffuse lobe, one bounce, / DiffCol
  kPassDiffuseIndirect = 1u << 4,   // ... more bounces
  kPassGlossyDirect = 1u << 5,      // the same for the specular lobe, / GlossCol
  kPassGlossyIndirect = 1u << 6,
  kPassEmission = 1u << 7,          // emission seen directly
  kPassEnvironment = 1u << 8,       // the world seen directly
  kPassMist = 1u << 9,              // 1 - the sample-mean of (1 - mist(distance)) (Cycles' Mist; 1 on the world)
  kPassUV = 1u << 10,               // the first hit's (u, v, 1) of the active UV map (0: no UVs, the world)
  kPassPosition = 1u << 11,         // world position of the first hit of the pixel's centre (0: world)
  kPassObjectIndex = 1u << 12,      // its object's pass index, of the first sample (0: world)
  kPassMaterialIndex = 1u << 13,    // its material's pass index, of the first sample (0: world)
  kPassGlossyColor = 1u << 15,      // the first hit's glossy (and glass) closures' weight (GlossCol)
  kPassAO = 1u << 14,               // the share of cosine-distributed rays from the first hit that travel
                                    // ao_distance unoccluded (Cycles' AO pass; 0 on the world)
  // Cycles' denoising features (Denoising Data): through smooth mirrors and glass to the first
  // rough surface, its albedo (the world's colour where the path escapes), its camera-space
  // normal, and the depth along the path to it.
  kPassDenoisingAlbedo = 1u << 16,
  kPassDenoisingNormal = 1u << 17,
  kPassDenoisingDepth = 1u << 18,
  // Cycles' Vector pass (film/motion_vectors.h): where the first surface's point was one frame
  // before and will be one after, in pixels (previous - now, now - next; y up), the mean over the
  // samples that hit a surface; and that count's share, which it is divided by (accumulated with
  // it, not a pass of its own). 0 without the scene's neighbouring frames.
  kPassVector = 1u << 19,
  kPassVectorWeight = 1u << 20,
};
inline constexpr uint32_t kDenoisingPasses = kPassDenoisingAlbedo | kPassDenoisingNormal | kPassDenoisingDepth;
// The passes whose pixel is the pixel's first sample's value, unfiltered (Cycles' sample-0 passes).
inline constexpr uint32_t kFirstSamplePasses = kPassDepth | kPassPosition | kPassObjectIndex | kPassMaterialIndex;
struct PassInfo {
  Pass pass;
  const char* name;  // Blender's short pass names (Cycles' "DiffDir" etc.; "Albedo" for DiffCol)
  int channels;
};
inline constexpr PassInfo kPasses[] = {
    {kPassNormal, "Normal", 3},         {kPassAlbedo, "Albedo", 3},
    {kPassDiffuseDirect, "DiffDir", 3}, {kPassDiffuseIndirect, "DiffInd", 3}, {kPassGlossyDirect, "GlossDir", 3},
    {kPassGlossyIndirect, "GlossInd", 3}, {kPassGlossyColor, "GlossCol", 3}, {kPassEmission, "Emit", 3},
    {kPassEnvironment, "Env", 3},
    {kPassMist, "Mist", 1},            {kPassUV, "UV", 3},                 {kPassAO, "AO", 3},
    {kPassDenoisingAlbedo, "DenoisingAlbedo", 3}, {kPassDenoisingNormal, "DenoisingNormal", 3},
    {kPassDenoisingDepth, "DenoisingDepth", 1},
    {kPassVector, "Vector", 4},         {kPassVectorWeight, "VectorWeight", 1},
    {kPassDepth, "Depth", 1},           {kPassPosition, "Position", 3},
    {kPassObjectIndex, "IndexOB", 1},  {kPassMaterialIndex, "IndexMA", 1},
};

// A window [x0, x1) x [y0, y1) of the frame, y counted from the top row (RenderSettings::window).
using PixelWindow = std::optional<std::array<int, 4>>;

struct RenderSettings {
  // The numbers and switches, one line each in render_settings_fields.h (the Python module binds
  // the same list).
#define TORRANCE_RENDER_SETTING(type, name, default_value, doc) type name = default_value;
#include "torrance/integrator/render_settings_fields.h"
#undef TORRANCE_RENDER_SETTING

  // Settings the Python module converts (bound by hand in core/python/init_render.cpp).
  // PAPER here, PRINCIPLED in the add-on (python_addon/torrance/settings_table.py), on purpose:
  // callers of the core (C++ and module tests, scripts) check renders against closed forms of the
  // brief's equations (a Lambert plane under a sun gives albedo * E / pi), while Blender users
  // expect F12 to look like Cycles' Principled BSDF on the same scene.
  BrdfModel brdf_model = BrdfModel::Paper;
  LightSelection light_selection = LightSelection::Contribution;
  bool sobol = true;    // Owen-scrambled Sobol samples; false: independent random numbers ("sampler")
  uint32_t passes = 0;  // a set of Pass flags, rendered besides Combined (Python: a list of names)
  GuidingOptions guiding_options;  // the SD-tree's parameters (C++ only: tests)

  static constexpr int kAdaptiveStep = 16;                // samples between convergence checks (Cycles' step)
  static constexpr float kAdaptiveThresholdScale = 5.0f;  // Cycles 3.4 multiplies the threshold by 5
  int effective_adaptive_min_samples() const;             // the minimum in use (automatic one resolved)

  void validate() const;  // throws std::invalid_argument
};

// Row-major pixels, row 0 = top of the image; linear RGBA unless a pass says otherwise.
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgba;  // width * height * channels values
  int channels = 4;
};

struct RenderCallbacks {
  // Called on the thread that called render(), after each pass, with the image so far.
  std::function<void(const Image&, int samples_done, int samples_total)> on_pass;
  // Optional: called just before on_pass with the requested passes of the same samples (they are
  // resolved at every pass only when this is set: the viewport's denoising guides).
  std::function<void(std::vector<std::pair<std::string, Image>>&& passes)> on_pass_passes;
  // Polled on the thread that called render() about every 50 ms; true stops the render promptly.
  std::function<bool()> should_stop;
};

struct RenderResult {
  Image image;
  std::vector<std::pair<std::string, Image>> passes;  // the requested passes, in kPasses order
  int samples_done = 0;
  bool stopped = false;
  double seconds = 0.0;
  double setup_seconds = 0.0;      // of `seconds`, before the first sample: top-level BVH, lights
  uint64_t nonfinite_samples = 0;  // discarded NaN/Inf path samples (a bug if ever non-zero)
  uint64_t samples_spent = 0;      // camera samples traced over all pixels (adaptive: < pixels * samples)
  Image sample_counts;             // per pixel of the rendered window, 1 channel: samples it received
  bool time_limit_reached = false;  // ended by RenderSettings::time_limit (samples_done < samples)
  uint64_t closest_rays = 0, occlusion_rays = 0;  // Embree queries traced (closest hit, shadow)
  uint64_t camera_packets = 0;  // 8-wide packets the camera rays among closest_rays went in
  // What path guiding did: "off" (not asked for), "too few samples" (its training could not
  // reach the decision pass, so it was not used), "guided" (to the end), "stopped after pass 3"
  // (it would not have paid), "stopped before deciding" (the time limit ended its training).
  std::string guiding = "off";
  int first_bounce_splits = 1;         // the branches used at the first hit (chosen, or as set)
  bool filter_splatting = false;       // whether samples were splatted (RenderSettings::filter_splatting)
  float first_bounce_optimum = 0.0f;   // the automatic choice's n* (0: not automatic, or unknown)
  uint64_t rays_traced() const { return closest_rays + occlusion_rays; }
};

RenderResult render(Scene& scene, const RenderSettings& settings, const RenderCallbacks& callbacks = {});

}  // namespace torrance
