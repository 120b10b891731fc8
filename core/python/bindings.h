// Shared declarations of the pybind11 module: one init_<concept> per file, bindings only.
#pragma once

#include "torrance/integrator/integrator.h"
#include "torrance/scene/object_settings.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <initializer_list>
#include <string>
#include <utility>

namespace torrance::python {

namespace py = pybind11;

void init_scene(py::module_& m);
void init_mixture(py::module_& m);  // after init_scene: adds Scene.add_mixture
void init_cryptomatte(py::module_& m);   // after init_scene: cryptomatte_hash, Scene.set_cryptomatte
void init_object_settings(py::module_& m);  // after init_scene: Scene.set_curves_settings
void init_points(py::module_& m);  // after init_scene: Scene.add_points, set_points_settings
// An object's settings (init_object_settings.cpp: set_curves_settings' and set_points_settings'
// arguments), checked: ValueError for a light group or linking set out of range.
ObjectSettings object_settings(float pass_index, bool holdout, bool shadow_catcher, int light_group, int receiver_set,
                               int blocker_set, int32_t cryptomatte);
void init_media(py::module_& m);    // after init_scene: adds Scene.set_material_volume, set_world_volume
void init_motion(py::module_& m);  // after init_scene: Scene.set_mesh_motion, set_camera_motion
void init_frame_motion(py::module_& m);  // after init_scene: Scene.set_frame_motion_* (the Vector pass)
void init_extra_passes(py::module_& m);  // after init_scene: Scene.set_aovs, set_light_groups
void init_light_linking(py::module_& m);  // after init_scene: Scene.set_light_link_table, ...
void init_render(py::module_& m);  // init_render_settings first
void init_render_settings(py::module_& m);  // RenderSettings, from render_settings_fields.h
void init_image(py::module_& m);
void init_bsdf(py::module_& m);
void init_rays(py::module_& m);  // record_rays, replay_rays
void init_world_mesh(py::module_& m);  // triangle_normals, transform_points, corner_normals, vertex_normals
void init_sky(py::module_& m);  // preetham_sky_table, nishita_sky_table
void init_denoise(py::module_& m);  // Denoiser (Open Image Denoise, loaded at run time)

// "PAPER" / "PRINCIPLED" -> BrdfModel; ValueError otherwise.
BrdfModel parse_model(const std::string& s);

// (height, width, 4) float32 copy of an image.
py::array_t<float> to_numpy(const Image& image);

// obj as a numpy array, not copied (a list becomes one), once it is known to hold real numbers
// (bool, int, float: TypeError otherwise) and a copy of it with itemsize-byte items fits the
// memory budget (ValueError otherwise) -- checked before any conversion allocates.
py::array numeric_array(const py::object& obj, const std::string& name, size_t itemsize);
std::string shape_string(const py::array& a);  // "(2, 3)"

// obj as a C-contiguous array of T (numeric_array's checks, then converted) whose shape is
// `shape`, -1 standing for any length (an empty array passes when the first one is -1); a
// ValueError "<name> must have shape (N, 3), got (2, 2)" otherwise.
template <typename T>
py::array_t<T, py::array::c_style | py::array::forcecast> shaped_array(const py::object& obj, const char* name,
                                                                      std::initializer_list<py::ssize_t> shape) {
  using Array = py::array_t<T, py::array::c_style | py::array::forcecast>;
  Array a = Array::ensure(numeric_array(obj, name, sizeof(T)));
  if (!a) throw py::type_error(std::string(name) + " must be a numeric array");
  bool ok = a.ndim() == py::ssize_t(shape.size());
  py::ssize_t axis = 0;
  for (const py::ssize_t n : shape) {
    ok = ok && (n < 0 || a.shape(axis) == n);
    ++axis;
  }
  if (!ok && a.size() == 0 && shape.size() > 0 && *shape.begin() < 0) ok = true;
  if (!ok) {
    std::string want;
    for (const py::ssize_t n : shape)
      want += (want.empty() ? "(" : ", ") + (n < 0 ? std::string("N") : std::to_string(n));
    throw py::value_error(std::string(name) + " must have shape " + want + "), got " + shape_string(a));
  }
  return a;
}

// Adds `f` as the method `name` of the already bound class `cls` (for bindings split over
// several files, each adding its methods to Scene).
template <typename F, typename... Extra>
void add_method(py::object& cls, const char* name, F&& f, const Extra&... extra) {
  cls.attr(name) = py::cpp_function(std::forward<F>(f), py::name(name), py::is_method(cls), extra...);
}

}  // namespace torrance::python
