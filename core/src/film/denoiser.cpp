// Open Image Denoise through its C API, loaded with dlopen (see denoiser.h).
#include "torrance/film/denoiser.h"

#include <dlfcn.h>

#include <cstddef>
#include <stdexcept>
#include <vector>

namespace torrance {

namespace {

// The C API's types and the values Torrance passes (OIDN 2.x's oidn.h).
using OidnDevice = void*;
using OidnFilter = void*;
using ProgressFn = bool (*)(void* user, double done);
constexpr int kDeviceCpu = 1;      // OIDN_DEVICE_TYPE_CPU
constexpr int kFormatFloat3 = 3;   // OIDN_FORMAT_FLOAT3
constexpr int kErrorNone = 0;      // OIDN_ERROR_NONE
constexpr int kErrorCancelled = 6; // OIDN_ERROR_CANCELLED

// The library names Blender's builds load (4.x, 5.x), tried for an already loaded library.
constexpr const char* kLoadedNames[] = {"libOpenImageDenoise.so.2", "libOpenImageDenoise.so"};

// The stages of one denoise call, for the progress fraction: each filter run is one stage.
struct Progress {
  const std::function<bool(double)>* report;
  int stage, stages;
};

bool report_progress(void* user, double done) {
  auto* p = static_cast<Progress*>(user);
  return !*p->report || (*p->report)((p->stage + done) / p->stages);
}

}  // namespace

struct Denoiser::Api {
  void* handle = nullptr;
  bool owns_handle = false;
  std::string path;
  OidnDevice device = nullptr;

  OidnDevice (*new_device)(int) = nullptr;
  void (*commit_device)(OidnDevice) = nullptr;
  void (*release_device)(OidnDevice) = nullptr;
  int (*device_error)(OidnDevice, const char**) = nullptr;
  OidnFilter (*new_filter)(OidnDevice, const char*) = nullptr;
  void (*set_image)(OidnFilter, const char*, void*, int, size_t, size_t, size_t, size_t,
                    size_t) = nullptr;
  void (*set_bool)(OidnFilter, const char*, bool) = nullptr;
  void (*set_int)(OidnFilter, const char*, int) = nullptr;
  void (*set_progress)(OidnFilter, ProgressFn, void*) = nullptr;
  void (*commit_filter)(OidnFilter) = nullptr;
  void (*execute_filter)(OidnFilter) = nullptr;
  void (*release_filter)(OidnFilter) = nullptr;

  template <typename F>
  void bind(F& fn, const char* name) {
    fn = reinterpret_cast<F>(dlsym(handle, name));
    if (!fn) throw std::runtime_error(path + " has no " + name + " (not Open Image Denoise 2.x)");
  }

  // OIDN's message for its last error on the device, or "" when there was none; `code` its code.
  std::string error(int* code = nullptr) const {
    const char* message = nullptr;
    const int c = device_error(device, &message);
    if (code) *code = c;
    if (c == kErrorNone) return "";
    return message && *message ? message : "error " + std::to_string(c);
  }
};

Denoiser::Denoiser(const std::string& library) : api_(std::make_unique<Api>()) {
  Api& a = *api_;
  if (library.empty()) {
    for (const char* name : kLoadedNames)
      if ((a.handle = dlopen(name, RTLD_LAZY | RTLD_NOLOAD)) != nullptr) break;
    if (!a.handle)
      throw std::runtime_error(
          "no Open Image Denoise library is loaded in this process (Blender 4.x and 5.x load "
          "their own; give the library's file otherwise)");
  } else {
    a.handle = dlopen(library.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!a.handle) {
      const char* why = dlerror();
      throw std::runtime_error("cannot load Open Image Denoise from '" + library +
                               "': " + (why ? why : "unknown error"));
    }
  }
  a.owns_handle = true;
  a.path = library.empty() ? kLoadedNames[0] : library;
  try {
    a.bind(a.new_device, "oidnNewDevice");
    a.bind(a.commit_device, "oidnCommitDevice");
    a.bind(a.release_device, "oidnReleaseDevice");
    a.bind(a.device_error, "oidnGetDeviceError");
    a.bind(a.new_filter, "oidnNewFilter");
    a.bind(a.set_image, "oidnSetSharedFilterImage");
    a.bind(a.set_bool, "oidnSetFilterBool");
    a.bind(a.set_int, "oidnSetFilterInt");
    a.bind(a.set_progress, "oidnSetFilterProgressMonitorFunction");
    a.bind(a.commit_filter, "oidnCommitFilter");
    a.bind(a.execute_filter, "oidnExecuteFilter");
    a.bind(a.release_filter, "oidnReleaseFilter");
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(a.new_device), &info) && info.dli_fname)
      a.path = info.dli_fname;
    a.device = a.new_device(kDeviceCpu);
    if (!a.device) throw std::runtime_error("Open Image Denoise could not create a CPU device");
    a.commit_device(a.device);
    const std::string why = a.error();
    if (!why.empty()) throw std::runtime_error("Open Image Denoise's CPU device: " + why);
  } catch (...) {
    if (a.device) a.release_device(a.device);
    dlclose(a.handle);
    throw;
  }
}

Denoiser::~Denoiser() {
  if (api_->device) api_->release_device(api_->device);
  if (api_->owns_handle) dlclose(api_->handle);
}

const std::string& Denoiser::library_path() const { return api_->path; }

bool Denoiser::denoise(const float* color, const float* albedo, const float* normal,
                       float* output, int width, int height, const DenoiseOptions& options,
                       const std::function<bool(double)>& progress) const {
  const Api& a = *api_;
  if (width <= 0 || height <= 0) throw std::runtime_error("denoise: the image is empty");
  if (normal && !albedo) throw std::runtime_error("denoise: a normal guide needs an albedo");
  const size_t w = size_t(width), h = size_t(height);
  const bool prefilter = options.prefilter == DenoisePrefilter::Accurate;
  Progress stages{&progress, 0, 1 + (prefilter ? (albedo != nullptr) + (normal != nullptr) : 0)};

  // One RT filter run: `inputs` (name, image) into `out`; false when cancelled.
  auto run = [&](std::initializer_list<std::pair<const char*, const float*>> inputs, float* out,
                 bool hdr, bool clean_aux) {
    OidnFilter f = a.new_filter(a.device, "RT");
    if (!f) throw std::runtime_error("Open Image Denoise: no RT filter (" + a.error() + ")");
    for (const auto& [name, image] : inputs)
      a.set_image(f, name, const_cast<float*>(image), kFormatFloat3, w, h, 0, 0, 0);
    a.set_image(f, "output", out, kFormatFloat3, w, h, 0, 0, 0);
    a.set_bool(f, "hdr", hdr);
    a.set_bool(f, "cleanAux", clean_aux);
    a.set_int(f, "quality", int(options.quality));
    a.set_progress(f, report_progress, &stages);
    a.commit_filter(f);
    a.execute_filter(f);
    int code = 0;
    const std::string why = a.error(&code);
    a.release_filter(f);
    ++stages.stage;
    if (code == kErrorCancelled) return false;
    if (!why.empty()) throw std::runtime_error("Open Image Denoise: " + why);
    return true;
  };

  std::vector<float> clean_albedo, clean_normal;
  if (prefilter && albedo) {
    clean_albedo.resize(w * h * 3);
    if (!run({{"albedo", albedo}}, clean_albedo.data(), false, false)) return false;
    albedo = clean_albedo.data();
  }
  if (prefilter && normal) {
    clean_normal.resize(w * h * 3);
    if (!run({{"normal", normal}}, clean_normal.data(), false, false)) return false;
    normal = clean_normal.data();
  }
  // Cycles' meaning of the prefilter: None, the guides are clean as given; Accurate, cleaned by
  // the runs above; Fast, the RT filter takes them as noisy (cleanAux off).
  const bool clean_aux = options.prefilter != DenoisePrefilter::Fast && albedo;
  if (normal) return run({{"color", color}, {"albedo", albedo}, {"normal", normal}}, output,
                         options.hdr, clean_aux);
  if (albedo) return run({{"color", color}, {"albedo", albedo}}, output, options.hdr, clean_aux);
  return run({{"color", color}}, output, options.hdr, false);
}

}  // namespace torrance
