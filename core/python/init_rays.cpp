// The rays a render traces, recorded and replayed through raw Embree (ray_log.h, ray_replay.h).
#include "bindings.h"

#include "torrance/integrator/ray_replay.h"

#include <pybind11/stl.h>

#include <cmath>
#include <memory>

namespace torrance::python {
namespace {

struct RecordedRays {
  std::vector<LoggedRay> rays;
};

RayKind parse_kind(const std::string& s) {
  if (s == "CAMERA") return RayKind::Camera;
  if (s == "CLOSEST") return RayKind::Closest;
  if (s == "OCCLUSION") return RayKind::Occlusion;
  throw py::value_error("ray kind must be 'CAMERA', 'CLOSEST' or 'OCCLUSION', got '" + s + "'");
}

}  // namespace

void init_rays(py::module_& m) {
  py::class_<RecordedRays, std::shared_ptr<RecordedRays>>(
      m, "RecordedRays", "The Embree queries of a render with their answers (record_rays).")
      .def("__len__", [](const RecordedRays& r) { return r.rays.size(); })
      .def_property_readonly("counts",
                             [](const RecordedRays& r) {
                               size_t camera = 0, closest = 0, occlusion = 0, unbounded = 0;
                               for (const LoggedRay& ray : r.rays) {
                                 camera += ray.kind == RayKind::Camera;
                                 closest += ray.kind == RayKind::Closest;
                                 occlusion += ray.kind == RayKind::Occlusion;
                                 unbounded += ray.kind == RayKind::Occlusion && std::isinf(ray.tmax);
                               }
                               py::dict d;
                               d["CAMERA"] = camera;
                               d["CLOSEST"] = closest;
                               d["OCCLUSION"] = occlusion;
                               d["OCCLUSION_UNBOUNDED"] = unbounded;
                               return d;
                             })
      .def(
          "select",
          [](const RecordedRays& r, const std::string& kind, bool unbounded_only) {
            return std::make_shared<RecordedRays>(RecordedRays{select_rays(r.rays, parse_kind(kind), unbounded_only)});
          },
          py::arg("kind"), py::arg("unbounded_only") = false,
          "The rays of one kind ('CAMERA', 'CLOSEST', 'OCCLUSION'); unbounded_only: tmax = inf only.")
      .def(
          "mismatches",
          [](const RecordedRays& a, const RecordedRays& b) {
            if (a.rays.size() != b.rays.size()) throw py::value_error("the recordings differ in length");
            size_t n = 0;
            for (size_t i = 0; i < a.rays.size(); ++i) n += !a.rays[i].same_answer(b.rays[i]);
            return n;
          },
          "How many rays differ in query or answer from the other recording's.")
      .def("copy", [](const RecordedRays& r) { return std::make_shared<RecordedRays>(r); });

  m.def(
      "record_rays",
      [](Scene& scene, const RenderSettings& settings) {
        auto recorded = std::make_shared<RecordedRays>();
        py::gil_scoped_release release;
        recorded->rays = record_render_rays(scene, settings);
        return recorded;
      },
      py::arg("scene"), py::arg("settings"), "Renders (image discarded) and returns every ray it traced.");
  m.def(
      "replay_rays",
      [](const Scene& scene, RecordedRays& rays, int packet_width, int threads) {
        py::gil_scoped_release release;
        return replay_rays(scene, rays.rays, packet_width, threads);
      },
      py::arg("scene"), py::arg("rays"), py::arg("packet_width") = 1, py::arg("threads") = 0,
      "Traces the rays through raw Embree (packet_width 1 or 8), storing the answers in them; "
      "returns the seconds taken. The scene must have been rendered (its BVH built).");
}

}  // namespace torrance::python
