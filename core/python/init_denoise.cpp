#include "bindings.h"

#include <cmath>
#include <memory>
#include <optional>

#include "torrance/film/denoiser.h"

namespace torrance::python {

namespace {

DenoisePrefilter parse_prefilter(const std::string& s) {
  if (s == "NONE") return DenoisePrefilter::None;
  if (s == "FAST") return DenoisePrefilter::Fast;
  if (s == "ACCURATE") return DenoisePrefilter::Accurate;
  throw py::value_error("prefilter must be 'NONE', 'FAST' or 'ACCURATE', got '" + s + "'");
}

DenoiseQuality parse_quality(const std::string& s) {
  if (s == "DEFAULT") return DenoiseQuality::Default;
  if (s == "FAST") return DenoiseQuality::Fast;
  if (s == "BALANCED") return DenoiseQuality::Balanced;
  if (s == "HIGH") return DenoiseQuality::High;
  throw py::value_error("quality must be 'DEFAULT', 'FAST', 'BALANCED' or 'HIGH', got '" + s + "'");
}

// An image argument as a (height, width, 3) float32 copy whose NaN and Inf are 0 (a denoiser
// spreads one over its neighbourhood); None stays empty. Its first three channels are taken
// (RGBA passes are accepted).
std::optional<std::vector<float>> guide(const py::object& obj, const char* name, py::ssize_t height,
                                       py::ssize_t width) {
  if (obj.is_none()) return std::nullopt;
  const auto a = shaped_array<float>(obj, name, {height, width, -1});
  const py::ssize_t channels = a.shape(2);
  if (channels < 3) throw py::value_error(std::string(name) + " must have 3 or 4 channels, got " + shape_string(a));
  std::vector<float> out(size_t(height * width) * 3);
  const float* src = a.data();
  for (size_t i = 0, n = size_t(height * width); i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const float v = src[i * channels + c];
      out[3 * i + c] = std::isfinite(v) ? v : 0.0f;
    }
  return out;
}

}  // namespace

void init_denoise(py::module_& m) {
  py::class_<Denoiser>(m, "Denoiser",
                       "Open Image Denoise 2.x's RT filter on the CPU, its library loaded at run "
                       "time: `library` a file (or name) to load, or '' for the one already "
                       "loaded in the process (Blender 4.x/5.x). RuntimeError saying why when "
                       "there is none.")
      .def(py::init([](const std::string& library) {
             py::gil_scoped_release release;
             return std::make_unique<Denoiser>(library);
           }),
           py::arg("library") = "")
      .def_property_readonly("library", &Denoiser::library_path, "The library's file.")
      .def(
          "denoise",
          [](const Denoiser& d, const py::object& color, const py::object& albedo, const py::object& normal,
             const std::string& prefilter, const std::string& quality, bool hdr,
             const py::object& progress) -> py::object {
            DenoiseOptions options;
            options.prefilter = parse_prefilter(prefilter);
            options.quality = parse_quality(quality);
            options.hdr = hdr;
            const auto c = shaped_array<float>(color, "color", {-1, -1, -1});
            const py::ssize_t height = c.shape(0), width = c.shape(1);
            if (height == 0 || width == 0) throw py::value_error("color is empty: " + shape_string(c));
            auto rgb = guide(color, "color", height, width);
            auto alb = guide(albedo, "albedo", height, width);
            auto nor = guide(normal, "normal", height, width);
            if (nor && !alb) throw py::value_error("a normal guide needs an albedo guide too (as Open Image Denoise)");
            py::array_t<float> out({height, width, py::ssize_t(3)});
            float* out_data = out.mutable_data();
            std::optional<py::error_already_set> raised;
            std::function<bool(double)> report;
            if (!progress.is_none())
              report = [&](double done) {
                py::gil_scoped_acquire gil;
                try {
                  return py::bool_(progress(done)).cast<bool>();
                } catch (py::error_already_set& e) {
                  raised = std::move(e);
                  return false;
                }
              };
            bool finished;
            {
              py::gil_scoped_release release;
              finished = d.denoise(rgb->data(), alb ? alb->data() : nullptr, nor ? nor->data() : nullptr,
                                   out_data, int(width), int(height), options, report);
            }
            if (raised) throw std::move(*raised);
            if (!finished) return py::none();
            return std::move(out);
          },
          py::arg("color"), py::arg("albedo") = py::none(), py::arg("normal") = py::none(), py::kw_only(),
          py::arg("prefilter") = "ACCURATE", py::arg("quality") = "HIGH", py::arg("hdr") = true,
          py::arg("progress") = py::none(),
          "Denoises color ((H, W, 3 or 4) float, linear) guided by albedo and normal (the same "
          "shape, or None; a normal needs an albedo); NaN/Inf read as 0. prefilter: 'NONE' (the "
          "guides may be noisy), 'FAST' (taken as noise-free), 'ACCURATE' (denoised first); "
          "quality 'DEFAULT', 'FAST', 'BALANCED', 'HIGH'. progress(fraction) -> False cancels: "
          "then None is returned. Returns (H, W, 3) float32; the GIL is released meanwhile.");
}

}  // namespace torrance::python
