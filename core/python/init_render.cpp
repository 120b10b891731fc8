#include "bindings.h"

#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <memory>

#include "torrance/integrator/session.h"

namespace torrance::python {

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
  init_render_settings(m);  // first: the rest takes and returns RenderSettings

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
          [](const RenderSession& s, uint64_t since_version, bool with_passes) -> py::object {
            Image image;
            int done = 0;
            uint64_t version = since_version;
            std::vector<std::pair<std::string, Image>> passes;
            if (!s.latest(image, done, version, with_passes ? &passes : nullptr)) return py::none();
            if (!with_passes) return py::make_tuple(to_numpy(image), done, version);
            py::dict d;
            for (const auto& [name, pass] : passes) d[py::str(name)] = to_numpy(pass);
            return py::make_tuple(to_numpy(image), done, version, d);
          },
          py::arg("since_version") = 0, py::arg("passes") = false,
          "(image, samples_done, version) if a newer image than since_version exists, else None; "
          "with passes=True (image, samples_done, version, {name: the settings' pass of the same "
          "samples}).")
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
