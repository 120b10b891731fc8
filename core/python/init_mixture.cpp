// Scene.add_mixture: materials made of weighted closures (Mix Shader / Add Shader), bound onto
// the Scene class that init_scene defines.
#include "bindings.h"

#include "torrance/scene/scene.h"

#include <pybind11/stl.h>

#include <array>
#include <string>

namespace torrance::python {
namespace {

ClosureType parse_closure(const std::string& s) {
  if (s == "principled") return ClosureType::Principled;
  if (s == "diffuse") return ClosureType::Diffuse;
  if (s == "diffuse_energy_preserving") return ClosureType::DiffuseEnergyPreserving;
  if (s == "glossy") return ClosureType::Glossy;
  if (s == "glossy_multiscatter_v1") return ClosureType::GlossyMultiscatterV1;
  if (s == "emission") return ClosureType::Emission;
  if (s == "transparent") return ClosureType::Transparent;
  if (s == "holdout") return ClosureType::Holdout;
  if (s == "ray_portal") return ClosureType::RayPortal;
  if (s == "velvet") return ClosureType::Velvet;
  if (s == "sheen") return ClosureType::Sheen;
  if (s == "translucent") return ClosureType::Translucent;
  if (s == "principled_hair") return ClosureType::PrincipledHair;
  if (s == "principled_hair_huang") return ClosureType::PrincipledHairHuang;
  if (s == "refraction") return ClosureType::Refraction;
  if (s == "toon_diffuse") return ClosureType::ToonDiffuse;
  if (s == "toon_glossy") return ClosureType::ToonGlossy;
  if (s == "toon_diffuse_cycles4") return ClosureType::ToonDiffuseCycles4;
  if (s == "toon_glossy_cycles4") return ClosureType::ToonGlossyCycles4;
  if (s == "metallic_f82") return ClosureType::MetallicF82;
  if (s == "metallic_conductor") return ClosureType::MetallicConductor;
  if (s == "subsurface") return ClosureType::Subsurface;
  if (s == "hair_reflection") return ClosureType::HairReflection;
  if (s == "hair_transmission") return ClosureType::HairTransmission;
  throw py::value_error(
      "closure type must be 'principled', 'diffuse', 'diffuse_energy_preserving', 'glossy', 'glossy_multiscatter_v1', 'emission', 'transparent', 'holdout', 'ray_portal', 'velvet', "
      "'sheen', "
      "'translucent', 'principled_hair', 'principled_hair_huang', 'refraction', 'toon_diffuse', 'toon_glossy', "
      "'toon_diffuse_cycles4', "
      "'toon_glossy_cycles4', 'metallic_f82', 'metallic_conductor', 'subsurface', 'hair_reflection' or "
      "'hair_transmission', got '" + s + "'");
}

MixFactor parse_factor(const py::handle& h) {
  if (!py::isinstance<py::dict>(h)) throw py::type_error("each mix factor must be a dict");
  const py::dict d = py::reinterpret_borrow<py::dict>(h);
  for (const auto& item : d) {
    const std::string key = py::str(item.first);
    if (key != "kind" && key != "value" && key != "texture" && key != "scale" && key != "color1" && key != "color2" &&
        key != "register")
      throw py::value_error("unknown mix factor key '" + key +
                            "' (kind, value, texture, scale, color1, color2, register)");
  }
  MixFactor f;
  const std::string kind = d.contains("kind") ? py::str(d["kind"]).cast<std::string>() : "constant";
  if (kind == "constant") {
    f.kind = MixFactor::Kind::Constant;
    if (d.contains("value")) f.value = d["value"].cast<float>();
  } else if (kind == "image") {
    f.kind = MixFactor::Kind::Image;
    if (!d.contains("texture")) throw py::value_error("an image mix factor needs 'texture'");
    f.texture = d["texture"].cast<int>();
  } else if (kind == "program") {
    f.kind = MixFactor::Kind::Program;
    if (!d.contains("register")) throw py::value_error("a program mix factor needs 'register'");
    f.register_index = d["register"].cast<int>();
  } else if (kind == "checker") {
    f.kind = MixFactor::Kind::Checker;
    if (d.contains("scale")) f.checker_scale = d["scale"].cast<float>();
    if (d.contains("color1")) f.checker_color1 = d["color1"].cast<float>();
    if (d.contains("color2")) f.checker_color2 = d["color2"].cast<float>();
  } else {
    throw py::value_error("mix factor kind must be 'constant', 'image', 'checker' or 'program', got '" + kind + "'");
  }
  return f;
}

}  // namespace

void init_mixture(py::module_& m) {
  py::object cls = m.attr("Scene");
  auto add_mixture = [](Scene& s, const std::vector<std::tuple<std::string, int64_t, std::vector<int>>>& closures,
                        const py::list& factors, int normal_texture, float normal_strength, int bump_texture,
                        float bump_strength, float bump_distance, float alpha, int alpha_texture,
                        bool alpha_from_luminance, bool alpha_inverted, std::array<float, 3> transparent_color,
                        int program, int normal_register, int surface_normal_register, int coat_normal_register) {
    Mixture mixture;
    mixture.program = program;
    for (const auto& f : factors) mixture.factors.push_back(parse_factor(f));
    for (const auto& [type, material, terms] : closures) {
      if (material < 0 || material > int64_t(UINT32_MAX))
        throw py::value_error("closure material must be a material index >= 0, got " + std::to_string(material));
      mixture.components.push_back({parse_closure(type), uint32_t(material), terms});
    }
    MaterialTextures normal;
    normal.normal = normal_texture;
    normal.normal_strength = normal_strength;
    normal.bump = bump_texture;
    normal.bump_strength = bump_strength;
    normal.bump_distance = bump_distance;
    normal.alpha = alpha_texture;
    normal.alpha_from_luminance = alpha_from_luminance;
    normal.alpha_inverted = alpha_inverted;
    for (int r : {normal_register, surface_normal_register, coat_normal_register})
      if (r < -1 || r >= ShaderProgram::kMaxRegisters)
        throw py::value_error("normal_register, surface_normal_register and coat_normal_register must lie in [-1, " +
                              std::to_string(ShaderProgram::kMaxRegisters) + "), got " + std::to_string(r));
    normal.program.normal = int16_t(normal_register);
    normal.program.surface_normal = int16_t(surface_normal_register);
    normal.program.coat_normal = int16_t(coat_normal_register);
    return s.add_mixture(mixture, normal, alpha, Vec3(transparent_color[0], transparent_color[1], transparent_color[2]));
  };
  cls.attr("add_mixture") = py::cpp_function(
      add_mixture, py::name("add_mixture"), py::is_method(cls),
      py::sibling(py::getattr(cls, "add_mixture", py::none())),
      py::arg("closures"), py::arg("factors") = py::list(), py::arg("normal_texture") = -1,
      py::arg("normal_strength") = 1.0f, py::arg("bump_texture") = -1, py::arg("bump_strength") = 1.0f,
      py::arg("bump_distance") = 1.0f, py::arg("alpha") = 1.0f, py::arg("alpha_texture") = -1,
      py::arg("alpha_from_luminance") = false, py::arg("alpha_inverted") = false,
      py::arg("transparent_color") = std::array<float, 3>{1.0f, 1.0f, 1.0f}, py::arg("program") = -1,
      py::arg("normal_register") = -1, py::arg("surface_normal_register") = -1, py::arg("coat_normal_register") = -1,
      "Adds a material made of weighted closures (Mix Shader / Add Shader); returns its material index. "
      "closures: [(type, material, terms)], type 'principled' | 'diffuse' | 'diffuse_energy_preserving' (Blender 4.3+'s Diffuse BSDF: a rough one is the "
      "energy-preserving Oren-Nayar) | 'glossy' | 'emission' | 'transparent' | "
      "'holdout' | 'velvet' | 'sheen' | 'translucent' | 'refraction' | 'toon_diffuse' | 'toon_glossy' (sampled as Cycles 3.x; "
      "'toon_diffuse_cycles4' | 'toon_glossy_cycles4': as Cycles 4.x) | 'metallic_f82' | 'metallic_conductor' "
      "(the Metallic BSDF: mixture.h's ClosureType), material an add_material "
      "index holding the closure's inputs (diffuse/glossy/velvet/sheen: base_color = Color, roughness = Roughness "
      "or Sigma; translucent: base_color; refraction: base_color, roughness, ior, distribution; toon: "
      "base_color, roughness = Size, transmission_roughness = Smooth; transparent: transparent_color = Color: "
      "rays pass through with the closures' weight; holdout: its weight is taken off camera rays' alpha), terms the "
      "weight's factors (t >= 0: factor t, t < 0: 1 - factor -t-1). factors: dicts {'kind': 'constant', 'value'} | "
      "{'kind': 'image', 'texture'} (luminance) | {'kind': 'checker', 'scale', 'color1', 'color2'} (Blender's "
      "Checker Texture at the UV) | {'kind': 'program', 'register'} (register x of shader program `program`, "
      "from add_shader_program: the Fac's node graph). alpha, alpha_texture, alpha_from_luminance, alpha_inverted, "
      "transparent_color: as add_material's (a Mix Shader of a Transparent BSDF and this mixture). "
      "normal_register: register of `program` holding the Normal of all closures, surface_normal_register the "
      "surface's after the Material Output's Displacement (as add_material's), coat_normal_register the Coat Normal "
      "of its coated Principled closures (as add_material's). ValueError "
      "for malformed mixtures.");
}

}  // namespace torrance::python
