#include "bindings.h"

#include "torrance/film/image_io.h"

#include <string>

namespace torrance::python {

void init_image(py::module_& m) {
  m.def(
      "write_image",
      [](const std::string& path, const py::object& array) {
        const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(
            numeric_array(array, "image", 2 * sizeof(float)));  // + its RGBA float copy
        if (!a || a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4))
          throw py::value_error("image must have shape (height, width, 3 or 4)");
        Image image{int(a.shape(1)), int(a.shape(0)), {}};
        const int channels = int(a.shape(2));
        image.rgba.assign(size_t(image.width) * image.height * 4, 1.0f);
        for (size_t i = 0, n = size_t(image.width) * image.height; i < n; ++i)
          for (int c = 0; c < channels; ++c) image.rgba[4 * i + c] = a.data()[i * channels + c];
        py::gil_scoped_release release;
        write_image(path, image);
      },
      py::arg("path"), py::arg("image"),
      "Writes linear RGB(A): EXR/TIFF/HDR as float, PNG/JPEG as sRGB 8-bit.");
  m.def(
      "read_image",
      [](const std::string& path, int subimage) {
        ImageData data;
        {
          py::gil_scoped_release release;
          data = read_image(path, 0.0, subimage);
        }
        py::array_t<float> a({py::ssize_t(data.height), py::ssize_t(data.width), py::ssize_t(data.channels)});
        std::copy(data.pixels.begin(), data.pixels.end(), a.mutable_data());
        return a;
      },
      py::arg("path"), py::arg("subimage") = 0,
      "Reads an image's stored values as float32 (height, width, channels); subimage: the part of a "
      "multi-part file (an EXR Blender 5.x writes holds one pass a part).");
}

}  // namespace torrance::python
