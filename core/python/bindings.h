// Shared declarations of the pybind11 module: one init_<concept> per file, bindings only.
#pragma once

#include "torrance/integrator.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

namespace torrance::python {

namespace py = pybind11;

void init_scene(py::module_& m);
void init_mixture(py::module_& m);  // after init_scene: adds Scene.add_mixture
void init_render(py::module_& m);
void init_image(py::module_& m);
void init_bsdf(py::module_& m);
void init_rays(py::module_& m);  // record_rays, replay_rays
void init_world_mesh(py::module_& m);  // triangle_normals, transform_points, corner_normals

// "PAPER" / "PRINCIPLED" -> BrdfModel; ValueError otherwise.
BrdfModel parse_model(const std::string& s);

// (height, width, 4) float32 copy of an image.
py::array_t<float> to_numpy(const Image& image);

// obj as a numpy array, not copied (a list becomes one), once it is known to hold real numbers
// (bool, int, float: TypeError otherwise) and a copy of it with itemsize-byte items fits the
// memory budget (ValueError otherwise) -- checked before any conversion allocates.
py::array numeric_array(const py::object& obj, const std::string& name, size_t itemsize);
std::string shape_string(const py::array& a);  // "(2, 3)"

}  // namespace torrance::python
