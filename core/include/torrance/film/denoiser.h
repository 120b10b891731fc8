// Denoiser: Intel Open Image Denoise 2.x's "RT" filter (a neural denoiser for path-traced images,
// guided by an albedo and a normal image), on the CPU.
//
// The library is not linked: it is loaded at run time from the file the caller names, or, given
// no name, found among the libraries already loaded in the process (Blender 4.x and 5.x ship
// libOpenImageDenoise.so.2 and load it at start). Only OIDN's C API is used (its calls are
// stable across 2.x), so any 2.x library serves and a render without it loses nothing but the
// denoising: the constructor throws std::runtime_error saying why it could not load one.
//
// Prefiltering follows Cycles' Denoise settings (integrator/denoiser_oidn.cpp): None (the guides
// are noise-free as given: cleanAux on), Fast (noisy guides, denoised together with the colour by
// the one RT filter: cleanAux off), Accurate (the albedo and the normal are denoised first, each
// by its own RT filter, then cleanAux on).
#pragma once

#include <functional>
#include <memory>
#include <string>

namespace torrance {

enum class DenoisePrefilter { None, Fast, Accurate };

// OIDN's filter quality (OIDNQuality's values).
enum class DenoiseQuality { Default = 0, Fast = 4, Balanced = 5, High = 6 };

struct DenoiseOptions {
  DenoisePrefilter prefilter = DenoisePrefilter::Accurate;
  DenoiseQuality quality = DenoiseQuality::High;
  bool hdr = true;  // colour values beyond 1 (a render's radiance); false: a [0, 1] image
};

class Denoiser {
 public:
  // Loads `library` (a path or file name dlopen takes), or with an empty one the OIDN library
  // already loaded in the process; creates a CPU device. std::runtime_error if either fails.
  explicit Denoiser(const std::string& library = "");
  ~Denoiser();
  Denoiser(const Denoiser&) = delete;
  Denoiser& operator=(const Denoiser&) = delete;

  // The file the library was loaded from (from dladdr), for reports.
  const std::string& library_path() const;

  // Denoises `color` (width x height RGB float, rows top to bottom, tightly packed) into
  // `output` (the same layout; it may be `color`). albedo and normal: guides of the same layout,
  // or null (a normal needs an albedo, as OIDN). progress(fraction done) returns false to
  // cancel: then denoise returns false and `output` is unspecified. std::runtime_error with
  // OIDN's message on its errors (out of memory, bad sizes).
  bool denoise(const float* color, const float* albedo, const float* normal, float* output,
               int width, int height, const DenoiseOptions& options,
               const std::function<bool(double)>& progress = {}) const;

 private:
  struct Api;
  std::unique_ptr<Api> api_;
};

}  // namespace torrance
