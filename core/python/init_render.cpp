#include "bindings.h"

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <memory>

#include "torrance/session.h"

namespace torrance::python {
namespace {

std::string model_name(BrdfModel m) {
  switch (m) {
    case BrdfModel::Paper: return "PAPER";
    case BrdfModel::Principled: return "PRINCIPLED";
    case BrdfModel::PrincipledV2: return "PRINCIPLED_V2";
  }
  return "PAPER";
}
LightSelection parse_light_selection(const std::string& s) {
  if (s == "CONTRIBUTION") return LightSelection::Contribution;
  if (s == "UNIFORM") return LightSelection::Uniform;
  if (s == "IRRADIANCE") return LightSelection::Irradiance;
  throw py::value_error("light_selection must be 'CONTRIBUTION', 'IRRADIANCE' or 'UNIFORM', got '" + s + "'");
}

bool parse_sampler_is_sobol(const std::string& s) {
  if (s != "SOBOL" && s != "RANDOM") throw py::value_error("sampler must be 'SOBOL' or 'RANDOM', got '" + s + "'");
  return s == "SOBOL";
}

uint32_t parse_passes(const std::vector<std::string>& names) {
  uint32_t mask = 0;
  for (const std::string& name : names) {
    bool known = false;
    for (const PassInfo& p : kPasses)
      if (name == p.name) {
        mask |= p.pass;
        known = true;
      }
    if (!known) {
      std::string all;
      for (const PassInfo& p : kPasses) all += std::string(all.empty() ? "" : ", ") + p.name;
      throw py::value_error("unknown pass '" + name + "'; available: " + all);
    }
  }
  return mask;
}

}  // namespace

BrdfModel parse_model(const std::string& s) {
  if (s == "PAPER") return BrdfModel::Paper;
  if (s == "PRINCIPLED") return BrdfModel::Principled;
  if (s == "PRINCIPLED_V2") return BrdfModel::PrincipledV2;
  throw py::value_error("brdf_model must be 'PAPER', 'PRINCIPLED' or 'PRINCIPLED_V2', got '" + s + "'");
}

py::array_t<float> to_numpy(const Image& image) {
  py::array_t<float> a({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(image.channels)});
  std::copy(image.rgba.begin(), image.rgba.end(), a.mutable_data());
  return a;
}

void init_render(py::module_& m) {
  py::class_<RenderSettings>(m, "RenderSettings")
      .def(py::init([](int width, int height, int samples, int max_bounces, uint32_t seed, float pixel_aspect_x,
                       float pixel_aspect_y, float filter_width, bool transparent_background,
                       const std::string& brdf_model, std::optional<std::array<int, 4>> window, int threads,
                       const std::string& light_selection, const std::vector<std::string>& passes,
                       const std::string& sampler, bool specialize, float adaptive_threshold,
                       int adaptive_min_samples, double time_limit, float clamp_direct, float clamp_indirect,
                       int max_transparent_bounces, bool guiding, float guiding_training_fraction,
                       bool efficiency_roulette, bool mirror_images, bool nee_every_light,
                       int first_bounce_splits, bool filter_splatting) {
             RenderSettings s;
             s.width = width;
             s.height = height;
             s.samples = samples;
             s.max_bounces = max_bounces;
             s.seed = seed;
             s.pixel_aspect_x = pixel_aspect_x;
             s.pixel_aspect_y = pixel_aspect_y;
             s.filter_width = filter_width;
             s.transparent_background = transparent_background;
             s.brdf_model = parse_model(brdf_model);
             s.window = window;
             s.threads = threads;
             s.light_selection = parse_light_selection(light_selection);
             s.passes = parse_passes(passes);
             s.sobol = parse_sampler_is_sobol(sampler);
             s.specialize = specialize;
             s.adaptive_threshold = adaptive_threshold;
             s.adaptive_min_samples = adaptive_min_samples;
             s.time_limit = time_limit;
             s.clamp_direct = clamp_direct;
             s.clamp_indirect = clamp_indirect;
             s.max_transparent_bounces = max_transparent_bounces;
             s.guiding = guiding;
             s.guiding_training_fraction = guiding_training_fraction;
             s.efficiency_roulette = efficiency_roulette;
             s.mirror_images = mirror_images;
             s.nee_every_light = nee_every_light;
             s.first_bounce_splits = first_bounce_splits;
             s.filter_splatting = filter_splatting;
             s.validate();
             return s;
           }),
           py::arg("width") = 640, py::arg("height") = 480, py::arg("samples") = 64, py::arg("max_bounces") = 8,
           py::arg("seed") = 0, py::arg("pixel_aspect_x") = 1.0f, py::arg("pixel_aspect_y") = 1.0f,
           py::arg("filter_width") = 1.5f, py::arg("transparent_background") = false,
           py::arg("brdf_model") = "PAPER", py::arg("window") = py::none(), py::arg("threads") = 0,
           py::arg("light_selection") = "CONTRIBUTION", py::arg("passes") = std::vector<std::string>{},
           py::arg("sampler") = "SOBOL", py::arg("specialize") = true, py::arg("adaptive_threshold") = 0.0f,
           py::arg("adaptive_min_samples") = 0, py::arg("time_limit") = 0.0, py::arg("clamp_direct") = 0.0f,
           py::arg("clamp_indirect") = 0.0f, py::arg("max_transparent_bounces") = 8,
           py::arg("guiding") = false, py::arg("guiding_training_fraction") = 0.25f,
           py::arg("efficiency_roulette") = true, py::arg("mirror_images") = true,
           py::arg("nee_every_light") = true, py::arg("first_bounce_splits") = 1,
           py::arg("filter_splatting") = true)
      .def_readwrite("specialize", &RenderSettings::specialize)
      .def_readwrite("camera_packets", &RenderSettings::camera_packets)
      .def_readwrite("efficiency_roulette", &RenderSettings::efficiency_roulette)
      .def_readwrite("mirror_images", &RenderSettings::mirror_images)
      .def_readwrite("nee_every_light", &RenderSettings::nee_every_light)
      .def_readwrite("filter_splatting", &RenderSettings::filter_splatting)
      .def_property(
          "first_bounce_splits", [](const RenderSettings& s) { return s.first_bounce_splits; },
          [](RenderSettings& s, int n) {
            RenderSettings checked = s;
            checked.first_bounce_splits = n;
            checked.validate();
            s.first_bounce_splits = n;
          })
      .def_readwrite("roulette_min_survival", &RenderSettings::roulette_min_survival)
      .def_property(
          "sampler", [](const RenderSettings& s) { return std::string(s.sobol ? "SOBOL" : "RANDOM"); },
          [](RenderSettings& s, const std::string& v) { s.sobol = parse_sampler_is_sobol(v); })
      .def_readwrite("width", &RenderSettings::width)
      .def_readwrite("height", &RenderSettings::height)
      .def_readwrite("samples", &RenderSettings::samples)
      .def_readwrite("max_bounces", &RenderSettings::max_bounces)
      .def_readwrite("max_transparent_bounces", &RenderSettings::max_transparent_bounces)
      .def_readwrite("seed", &RenderSettings::seed)
      .def_readwrite("filter_width", &RenderSettings::filter_width)
      .def_readwrite("transparent_background", &RenderSettings::transparent_background)
      .def_readwrite("window", &RenderSettings::window)
      .def_readwrite("threads", &RenderSettings::threads)
      .def_readwrite("adaptive_threshold", &RenderSettings::adaptive_threshold)
      .def_readwrite("adaptive_min_samples", &RenderSettings::adaptive_min_samples)
      .def_readwrite("time_limit", &RenderSettings::time_limit)
      .def_readwrite("clamp_direct", &RenderSettings::clamp_direct)
      .def_readwrite("clamp_indirect", &RenderSettings::clamp_indirect)
      .def_readwrite("guiding", &RenderSettings::guiding)
      .def_readwrite("guiding_training_fraction", &RenderSettings::guiding_training_fraction)
      .def_property_readonly("effective_adaptive_min_samples", &RenderSettings::effective_adaptive_min_samples)
      .def_property(
          "light_selection",
          [](const RenderSettings& s) {
            return std::string(s.light_selection == LightSelection::Uniform      ? "UNIFORM"
                               : s.light_selection == LightSelection::Irradiance ? "IRRADIANCE"
                                                                                 : "CONTRIBUTION");
          },
          [](RenderSettings& s, const std::string& v) { s.light_selection = parse_light_selection(v); })
      .def_property(
          "brdf_model", [](const RenderSettings& s) { return model_name(s.brdf_model); },
          [](RenderSettings& s, const std::string& v) { s.brdf_model = parse_model(v); });

  py::class_<RenderResult, std::shared_ptr<RenderResult>>(m, "RenderResult")
      .def_property_readonly("image",
                             [](py::object self) {
                               const auto& r = self.cast<const RenderResult&>();
                               return py::array_t<float>({py::ssize_t(r.image.height), py::ssize_t(r.image.width),
                                                          py::ssize_t(4)},
                                                         r.image.rgba.data(), self);
                             })
      .def_property_readonly("passes",
                             [](const RenderResult& r) {
                               py::dict d;
                               for (const auto& [name, image] : r.passes) d[py::str(name)] = to_numpy(image);
                               return d;
                             })
      .def_readonly("samples_done", &RenderResult::samples_done)
      .def_readonly("stopped", &RenderResult::stopped)
      .def_readonly("seconds", &RenderResult::seconds)
      .def_readonly("setup_seconds", &RenderResult::setup_seconds)
      .def_readonly("nonfinite_samples", &RenderResult::nonfinite_samples)
      .def_readonly("samples_spent", &RenderResult::samples_spent)
      .def_readonly("time_limit_reached", &RenderResult::time_limit_reached)
      .def_readonly("closest_rays", &RenderResult::closest_rays)
      .def_readonly("occlusion_rays", &RenderResult::occlusion_rays)
      .def_readonly("guiding", &RenderResult::guiding)
      .def_readonly("first_bounce_splits", &RenderResult::first_bounce_splits)
      .def_readonly("filter_splatting", &RenderResult::filter_splatting)
      .def_readonly("first_bounce_optimum", &RenderResult::first_bounce_optimum)
      .def_property_readonly("rays_traced", &RenderResult::rays_traced)
      .def_property_readonly("sample_counts", [](const RenderResult& r) {
        py::array_t<float> a({py::ssize_t(r.sample_counts.height), py::ssize_t(r.sample_counts.width)});
        std::copy(r.sample_counts.rgba.begin(), r.sample_counts.rgba.end(), a.mutable_data());
        return a;
      });

  py::class_<RenderSession>(m, "RenderSession",
                            "A render on a background thread for interactive use: start(), poll latest(), stop().")
      .def(py::init<std::shared_ptr<Scene>, RenderSettings>(), py::arg("scene"), py::arg("settings"))
      .def("start", &RenderSession::start)
      .def("stop", &RenderSession::stop, py::call_guard<py::gil_scoped_release>(),
           "Stops the render and waits for its thread (well under a second).")
      .def("request_stop", &RenderSession::request_stop,
           "Asks the render to stop without waiting; stop() (or dropping the session) joins it.")
      .def(
          "latest",
          [](const RenderSession& s, uint64_t since_version) -> py::object {
            Image image;
            int done = 0;
            uint64_t version = since_version;
            if (!s.latest(image, done, version)) return py::none();
            return py::make_tuple(to_numpy(image), done, version);
          },
          py::arg("since_version") = 0,
          "(image, samples_done, version) if a newer image than since_version exists, else None.")
      .def_property_readonly("running", &RenderSession::running)
      .def_property_readonly("finished", &RenderSession::finished)
      .def_property_readonly("error", &RenderSession::error);

  py::list pass_names;
  for (const PassInfo& p : kPasses) pass_names.append(py::make_tuple(p.name, p.channels));
  m.attr("PASSES") = pass_names;

  m.def(
      "render",
      [](Scene& scene, const RenderSettings& settings, const py::object& on_pass, const py::object& should_stop) {
        RenderCallbacks callbacks;
        if (!on_pass.is_none())
          callbacks.on_pass = [on_pass](const Image& image, int done, int total) {
            py::gil_scoped_acquire gil;
            on_pass(to_numpy(image), done, total);
          };
        if (!should_stop.is_none())
          callbacks.should_stop = [should_stop]() {
            py::gil_scoped_acquire gil;
            return py::bool_(should_stop());
          };
        auto result = std::make_shared<RenderResult>();
        {
          py::gil_scoped_release release;
          *result = render(scene, settings, callbacks);
        }
        return result;
      },
      py::arg("scene"), py::arg("settings"), py::arg("on_pass") = py::none(), py::arg("should_stop") = py::none(),
      "Renders progressively with the GIL released; returns a RenderResult.");
}

}  // namespace torrance::python
