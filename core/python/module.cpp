#include "bindings.h"

#ifndef TORRANCE_VERSION
#error "TORRANCE_VERSION (CMake's project version) must be defined by the build"
#endif

PYBIND11_MODULE(_core, m) {
  m.doc() = "Torrance's C++ core: an Embree path tracer with a Cook-Torrance BSDF (see docs/python_api.md)";
  m.attr("__version__") = TORRANCE_VERSION;  // CMake's project(VERSION)
  torrance::python::init_scene(m);
  torrance::python::init_mixture(m);
  torrance::python::init_media(m);
  torrance::python::init_extra_passes(m);
  torrance::python::init_light_linking(m);
  torrance::python::init_cryptomatte(m);
  torrance::python::init_object_settings(m);
  torrance::python::init_points(m);
  torrance::python::init_motion(m);
  torrance::python::init_frame_motion(m);
  torrance::python::init_render(m);
  torrance::python::init_image(m);
  torrance::python::init_bsdf(m);
  torrance::python::init_rays(m);
  torrance::python::init_world_mesh(m);
  torrance::python::init_sky(m);
  torrance::python::init_denoise(m);
}
