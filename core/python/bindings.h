// Shared declarations of the pybind11 module: one init_<concept> per file, bindings only.
#pragma once

#include "torrance/integrator.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace torrance::python {

namespace py = pybind11;

void init_scene(py::module_& m);
void init_render(py::module_& m);
void init_image(py::module_& m);
void init_bsdf(py::module_& m);

// "PAPER" / "PRINCIPLED" -> BrdfModel; ValueError otherwise.
BrdfModel parse_model(const std::string& s);

// (height, width, 4) float32 copy of an image.
py::array_t<float> to_numpy(const Image& image);

}  // namespace torrance::python
