#include "bindings.h"

#include "torrance/shader/shader_sky.h"

#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <vector>

namespace torrance::python {

namespace {

// A precomputed table (a fraction of a second of work) made with the GIL released, as float32.
template <class Compute>
py::array_t<float> table_without_gil(const Compute& compute) {
  std::vector<float> table;
  {
    py::gil_scoped_release release;
    table = compute();
  }
  py::array_t<float> a(py::ssize_t(table.size()));
  std::copy(table.begin(), table.end(), a.mutable_data());
  return a;
}

}  // namespace

// The Sky Texture node's tables (shader_sky.h), computed as Cycles' SkyTextureNode does.
void init_sky(py::module_& m) {
  m.def(
      "preetham_sky_table",
      [](const std::array<float, 3>& sun_direction, float turbidity) {
        return shader::preetham_table(Vec3(sun_direction[0], sun_direction[1], sun_direction[2]), turbidity);
      },
      py::arg("sun_direction"), py::arg("turbidity"),
      "The Sky Texture's Preetham table (TexSky mode 0) for a unit sun direction (z up).");
  m.def(
      "hosek_sky_table",
      [](const std::array<float, 3>& sun_direction, float turbidity, float ground_albedo) {
        return shader::hosek_table(Vec3(sun_direction[0], sun_direction[1], sun_direction[2]), turbidity,
                                   ground_albedo);
      },
      py::arg("sun_direction"), py::arg("turbidity"), py::arg("ground_albedo"),
      "The Sky Texture's Hosek / Wilkie table (TexSky mode 3) for a unit sun direction (z up).");
  m.def(
      "nishita_sky_table",
      [](float sun_elevation, float sun_rotation, float sun_size, float sun_intensity, bool sun_disc, float altitude,
         float air, float dust, float ozone, bool wrap_elevation) {
        const shader::NishitaSky sky{sun_elevation, sun_rotation, sun_size, sun_intensity, sun_disc,
                                     altitude,      air,          dust,     ozone,         wrap_elevation};
        return table_without_gil([&] { return shader::nishita_table(sky); });
      },
      py::arg("sun_elevation"), py::arg("sun_rotation"), py::arg("sun_size"), py::arg("sun_intensity"),
      py::arg("sun_disc"), py::arg("altitude"), py::arg("air"), py::arg("dust"), py::arg("ozone"),
      py::arg("wrap_elevation") = false,
      "The Sky Texture's Nishita table (TexSky mode 1): the sun disc's colours and settings, then "
      "the precomputed sky texture (float32).");
  m.def(
      "scattering_sky_table",
      [](bool multiple, float sun_elevation, float sun_rotation, float sun_size, float sun_intensity, bool sun_disc,
         float altitude, float air, float aerosol, float ozone) {
        const shader::ScatteringSky sky{multiple, sun_elevation, sun_rotation, sun_size, sun_intensity,
                                        sun_disc, altitude,      air,          aerosol,  ozone};
        return table_without_gil([&] { return shader::scattering_table(sky); });
      },
      py::arg("multiple"), py::arg("sun_elevation"), py::arg("sun_rotation"), py::arg("sun_size"),
      py::arg("sun_intensity"), py::arg("sun_disc"), py::arg("altitude"), py::arg("air"), py::arg("aerosol"),
      py::arg("ozone"),
      "The Sky Texture's table of Blender 5.x's Single (multiple=False) or Multiple Scattering "
      "(TexSky mode 2): the sun disc's colours and settings, then the precomputed sky texture "
      "(float32).");
}

}  // namespace torrance::python
