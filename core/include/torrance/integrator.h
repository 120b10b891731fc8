// The path-tracing integrator: unidirectional paths with next-event estimation to every light,
// multiple importance sampling against BSDF sampling, Russian roulette and a bounce limit.
// Progressive: samples are rendered in passes over TBB-parallel tiles; every pass is reported.
// Deterministic: a pixel's samples depend only on (pixel, sample index, seed), never on threads.
#pragma once

#include "torrance/bsdf.h"
#include "torrance/scene.h"

#include <functional>
#include <optional>
#include <vector>

namespace torrance {

struct RenderSettings {
  int width = 640, height = 480;  // the full frame, in pixels
  int samples = 64;               // per pixel
  int max_bounces = 8;            // 0 = direct light only
  uint32_t seed = 0;
  float pixel_aspect_x = 1.0f, pixel_aspect_y = 1.0f;
  float filter_width = 1.5f;      // Blackman-Harris, in pixels (Cycles' default)
  bool transparent_background = false;
  BrdfModel brdf_model = BrdfModel::Paper;
  LightSelection light_selection = LightSelection::Contribution;
  // Optional window [x0, x1) x [y0, y1) of the frame to render, y counted from the top row.
  std::optional<std::array<int, 4>> window;
  int threads = 0;  // 0 = all cores

  void validate() const;  // throws std::invalid_argument
};

// Linear RGBA, row-major, row 0 = top of the image.
struct Image {
  int width = 0, height = 0;
  std::vector<float> rgba;
};

struct RenderCallbacks {
  // Called on the thread that called render(), after each pass, with the image so far.
  std::function<void(const Image&, int samples_done, int samples_total)> on_pass;
  // Polled on the thread that called render() about every 50 ms; true stops the render promptly.
  std::function<bool()> should_stop;
};

struct RenderResult {
  Image image;
  int samples_done = 0;
  bool stopped = false;
  double seconds = 0.0;
  uint64_t nonfinite_samples = 0;  // discarded NaN/Inf path samples (a bug if ever non-zero)
};

RenderResult render(Scene& scene, const RenderSettings& settings, const RenderCallbacks& callbacks = {});

}  // namespace torrance
