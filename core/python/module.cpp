#include "bindings.h"

PYBIND11_MODULE(_core, m) {
  m.doc() = "Torrance's C++ core: an Embree path tracer with a Cook-Torrance BSDF (see docs/python_api.md)";
  m.attr("__version__") = "0.1.0";
  torrance::python::init_scene(m);
  torrance::python::init_render(m);
  torrance::python::init_image(m);
  torrance::python::init_bsdf(m);
}
