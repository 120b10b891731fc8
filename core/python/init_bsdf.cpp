#include "bindings.h"

#include "torrance/bsdfs/albedo.h"
#include "torrance/scene/scene.h"

#include <pybind11/stl.h>

namespace torrance::python {

void init_bsdf(py::module_& m) {
  m.def(
      "directional_albedo",
      [](const std::string& model, std::array<float, 3> base_color, float metallic, float roughness, float specular,
         float cos_o) {
        if (!(cos_o > 0.0f && cos_o <= 1.0f)) throw py::value_error("cos_o must be in (0, 1]");
        Material mat;
        mat.base_color = Vec3(base_color[0], base_color[1], base_color[2]);
        mat.metallic = metallic;
        mat.roughness = roughness;
        mat.specular = specular;
        check_material(mat);
        const MaterialBsdf bsdf(mat, parse_model(model));
        const Vec3 wo(std::sqrt(1.0f - cos_o * cos_o), 0.0f, cos_o);
        py::gil_scoped_release release;
        return roughness * roughness < ggx::kDeltaAlpha ? directional_albedo_sampled(bsdf, wo, 100000)
                                                         : directional_albedo_quadrature(bsdf, wo, roughness * roughness);
      },
      py::arg("model"), py::arg("base_color"), py::arg("metallic"), py::arg("roughness"), py::arg("specular") = 0.5f,
      py::arg("cos_o") = 1.0f,
      "Fraction of uniform incident light reflected towards a viewer at cos_o (red channel): the "
      "white-furnace value of the model, by quadrature (sampled for mirror-like roughness).");
}

}  // namespace torrance::python
