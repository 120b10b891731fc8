// The export's bulk mesh arrays (torrance/scene/world_mesh.h, vertex_normals.h): forwarded with their
// shapes checked.
#include "bindings.h"

#include "torrance/scene/vertex_normals.h"
#include "torrance/scene/world_mesh.h"

#include <cstdint>
#include <string>

namespace torrance::python {
namespace {

using Float32Array = py::array_t<float, py::array::c_style | py::array::forcecast>;
using Int32Array = py::array_t<int32_t, py::array::c_style | py::array::forcecast>;
using BoolArray = py::array_t<bool, py::array::c_style | py::array::forcecast>;

// An array of any integer dtype as int32 (values are `what`); wider integers only if every value
// fits (a wrapped one would pass the callers' checks).
Int32Array index_array(const py::object& obj, const char* name, const char* what) {
  const py::array raw = numeric_array(obj, name, sizeof(int32_t));
  if (raw.size() > 0 && raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u')
    throw py::type_error(std::string(name) + " must hold integers, got dtype " + std::string(py::str(raw.dtype())));
  if (raw.size() > 0 && raw.dtype().itemsize() > 4) {
    // Compared as Python integers: a uint64 beyond int64 would not cast.
    const py::object lo = raw.attr("min")(), hi = raw.attr("max")();
    if (lo < py::int_(0) || hi > py::int_(INT32_MAX))
      throw py::value_error(std::string(name) + " use " + what + " outside [0, 2^31)");
  }
  return Int32Array::ensure(raw);
}

// Triangles (M, 3) of any integer dtype as int32.
Int32Array triangle_indices(const py::object& triangles) {
  const Int32Array t = index_array(triangles, "triangles", "vertex indices");
  if (!((t.ndim() == 2 && t.shape(1) == 3) || t.size() == 0))
    throw py::value_error("triangles must have shape (M, 3), got " + shape_string(t));
  return t;
}

// A one-dimensional index array of any integer dtype as int32, of `length` entries (-1: any).
Int32Array index_list(const py::object& obj, const char* name, const char* what, py::ssize_t length = -1) {
  const Int32Array a = index_array(obj, name, what);
  if (!(a.ndim() == 1 && (length < 0 || a.shape(0) == length)) && !(a.size() == 0 && length <= 0))
    throw py::value_error(std::string(name) + " must have shape (" +
                          (length < 0 ? std::string("N") : std::to_string(length)) + ",), got " + shape_string(a));
  return a;
}

}  // namespace

void init_world_mesh(py::module_& m) {
  m.def(
      "triangle_normals",
      [](const py::object& positions, const py::object& triangles) {
        const Float32Array p = shaped_array<float>(positions, "positions", {-1, 3});
        const Int32Array t = triangle_indices(triangles);
        const size_t num_triangles = size_t(t.size() / 3);
        py::array_t<float> normals({py::ssize_t(num_triangles), py::ssize_t(3)});
        py::array_t<bool> usable{py::ssize_t(num_triangles)};
        {
          py::gil_scoped_release release;
          triangle_normals(p.data(), size_t(p.size() / 3), t.data(), num_triangles, normals.mutable_data(),
                           reinterpret_cast<uint8_t*>(usable.mutable_data()));
        }
        return py::make_tuple(normals, usable);
      },
      py::arg("positions"), py::arg("triangles"),
      "Unit geometric normals (M, 3) float32 of triangles (M, 3) over positions (N, 3) -- "
      "cross(p1 - p0, p2 - p0) normalised, as numpy computes it in float32, bit for bit -- and "
      "usable (M,) bool: False where the length is not finite or <= 1e-30 (normal 0 there).");

  m.def(
      "transform_points",
      [](const py::object& points, const py::object& matrix) {
        const Float32Array p = shaped_array<float>(points, "points", {-1, 3});
        const auto mat = shaped_array<double>(matrix, "matrix", {4, 4});
        const size_t count = size_t(p.size() / 3);
        py::array_t<float> out({py::ssize_t(count), py::ssize_t(3)});
        {
          py::gil_scoped_release release;
          transform_points(p.data(), count, mat.data(), out.mutable_data());
        }
        return out;
      },
      py::arg("points"), py::arg("matrix"),
      "Points (N, 3) moved by the affine 4x4 matrix in float64, rounded to float32 (N, 3): "
      "(points.astype(float64) @ matrix[:3, :3].T + matrix[:3, 3]).astype(float32), bit for bit.");

  m.def(
      "corner_normals",
      [](const py::object& normals, const py::object& triangles, const py::object& geometric,
         const py::object& matrix, const py::object& smooth, bool per_vertex) {
        const Int32Array t = triangle_indices(triangles);
        const size_t num_triangles = size_t(t.size() / 3);
        const py::ssize_t rows = per_vertex ? -1 : py::ssize_t(3 * num_triangles);
        const Float32Array n = shaped_array<float>(normals, "normals", {rows, 3});
        const Float32Array g =
            shaped_array<float>(geometric, "geometric", {py::ssize_t(num_triangles), 3});
        Float32Array mat;
        if (!matrix.is_none()) mat = shaped_array<float>(matrix, "matrix", {3, 3});
        BoolArray flat_mask;
        if (!smooth.is_none())
          flat_mask = shaped_array<bool>(smooth, "smooth", {py::ssize_t(num_triangles)});
        py::array_t<float> out({py::ssize_t(num_triangles), py::ssize_t(3), py::ssize_t(3)});
        {
          py::gil_scoped_release release;
          corner_normals(n.data(), size_t(n.size() / 3), per_vertex, t.data(), num_triangles,
                         matrix.is_none() ? nullptr : mat.data(),
                         smooth.is_none() ? nullptr : reinterpret_cast<const uint8_t*>(flat_mask.data()), g.data(),
                         out.mutable_data());
        }
        return out;
      },
      py::arg("normals"), py::arg("triangles"), py::arg("geometric"), py::arg("matrix") = py::none(),
      py::arg("smooth") = py::none(), py::arg("per_vertex") = true,
      "Unit corner normals (M, 3, 3) float32 of triangles (M, 3): normals (N, 3) per vertex (per_vertex) "
      "or (3 M, 3) per corner, times matrix.T (3x3 float32, optional), normalised in float32 as numpy "
      "does; where that fails, and on triangles whose smooth (M,) entry is False, the triangle's "
      "geometric normal (M, 3).");

  m.def(
      "vertex_normals",
      [](const py::object& positions, const py::object& corner_vertices, const py::object& polygon_starts,
         const py::object& polygon_sizes) {
        const Float32Array p = shaped_array<float>(positions, "positions", {-1, 3});
        const Int32Array corners = index_list(corner_vertices, "corner_vertices", "vertex indices");
        const Int32Array starts = index_list(polygon_starts, "polygon_starts", "corner indices");
        const Int32Array sizes = index_list(polygon_sizes, "polygon_sizes", "sizes", py::ssize_t(starts.size()));
        const size_t num_vertices = size_t(p.size() / 3);
        py::array_t<float> out({py::ssize_t(num_vertices), py::ssize_t(3)});
        {
          py::gil_scoped_release release;
          vertex_normals(p.data(), num_vertices, corners.data(), size_t(corners.size()), starts.data(), sizes.data(),
                         size_t(starts.size()), out.mutable_data());
        }
        return out;
      },
      py::arg("positions"), py::arg("corner_vertices"), py::arg("polygon_starts"), py::arg("polygon_sizes"),
      "Smooth-shading vertex normals (N, 3) float32 of a polygon mesh: positions (N, 3), each corner's "
      "vertex (L,), each polygon's first corner and number of corners (P,) -- Blender's definition "
      "(angle-weighted unit polygon normals, normalised; a vertex without one: its position "
      "normalised), summed in one fixed order, so the same mesh always gives the same bits.");
}

}  // namespace torrance::python
