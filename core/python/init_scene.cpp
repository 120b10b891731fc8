#include "bindings.h"
#include "shader_arrays.h"

#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <stdexcept>
#include <vector>
#include <string>

namespace torrance::python {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;
using IndexArray = py::array_t<int64_t, py::array::c_style | py::array::forcecast>;

IndexArray as_indices(const py::object& obj, const char* name) {
  const py::array raw = numeric_array(obj, name, sizeof(int64_t));
  if (raw.size() > 0 && raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u')
    throw py::type_error(std::string(name) + " must hold integers, got dtype " + std::string(py::str(raw.dtype())));
  return IndexArray::ensure(raw);
}

struct MeshArrays {
  FloatArray p, n, uv;
  IndexArray t, m;
  size_t num_triangles = 0;
  bool has_n = false, has_m = false, has_uv = false;
  size_t num_vertices() const { return size_t(p.size() / 3); }
  const float* normals() const { return has_n ? n.data() : nullptr; }
  const int64_t* materials() const { return has_m ? m.data() : nullptr; }
  const float* uvs() const { return has_uv ? uv.data() : nullptr; }
};

MeshArrays mesh_arrays(const py::object& positions, const py::object& triangles, const py::object& corner_normals,
                       const py::object& material_indices, const char* materials_name, const py::object& corner_uvs) {
  MeshArrays a;
  a.p = shaped_array<float>(positions, "positions", {-1, 3});
  a.t = as_indices(triangles, "triangles");
  if (!((a.t.ndim() == 2 && a.t.shape(1) == 3) || a.t.size() == 0))
    throw py::value_error("triangles must have shape (M, 3), got " + shape_string(a.t));
  const py::ssize_t num_tris = a.t.size() / 3;
  a.num_triangles = size_t(num_tris);
  if (!corner_normals.is_none()) {
    a.n = FloatArray::ensure(numeric_array(corner_normals, "corner_normals", sizeof(float)));
    if (!a.n || a.n.size() != num_tris * 9)
      throw py::value_error("corner_normals must have shape (M, 3, 3) with M = " + std::to_string(num_tris) +
                            " triangles");
    a.has_n = true;
  }
  if (!material_indices.is_none()) {
    a.m = as_indices(material_indices, materials_name);
    if (a.m.size() != num_tris)
      throw py::value_error(std::string(materials_name) + " must have shape (M,) with M = " +
                            std::to_string(num_tris) + ", got " + shape_string(a.m));
    a.has_m = true;
  }
  if (!corner_uvs.is_none()) {
    a.uv = FloatArray::ensure(numeric_array(corner_uvs, "corner_uvs", sizeof(float)));
    if (!a.uv || a.uv.size() != num_tris * 6)
      throw py::value_error("corner_uvs must have shape (M, 3, 2) with M = " + std::to_string(num_tris) +
                            " triangles");
    a.has_uv = true;
  }
  return a;
}

// Affine matrices (N, 4, 4) or (N, 3, 4), or one (4, 4) / (3, 4) when expected is 1 or -1, as
// N x 12 floats (row-major 3x4). Checked: dtype and memory budget (numeric_array), shape, NaN/Inf,
// a 4x4's last row (0, 0, 0, 1), float range; the core checks the 1e12 bounds (check_transform).
std::vector<float> affine_rows(const py::object& obj, const char* name, py::ssize_t expected) {
  // Real numbers only, and their double copy plus the float result within the memory budget.
  const py::array raw = numeric_array(obj, name, sizeof(double) + sizeof(float));
  using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
  const DoubleArray a = DoubleArray::ensure(raw);
  const bool single = a.ndim() == 2 && expected <= 1;
  const py::ssize_t rows = a.ndim() >= 2 ? a.shape(a.ndim() - 2) : 0;
  const bool ok = (a.ndim() == 3 || single) && (rows == 3 || rows == 4) && a.shape(a.ndim() - 1) == 4;
  const py::ssize_t count = single ? 1 : (a.ndim() == 3 ? a.shape(0) : 0);
  if (!ok || (expected >= 0 && count != expected))
    throw py::value_error(std::string(name) + " must have shape (N, 4, 4) or (N, 3, 4)" +
                          (expected >= 0 ? " with N = " + std::to_string(expected) : std::string()) + ", got " +
                          shape_string(a));
  std::vector<float> out(size_t(count) * 12);
  const double* d = a.data();
  for (py::ssize_t i = 0; i < count; ++i) {
    const double* m = d + i * rows * 4;
    for (int k = 0; k < rows * 4; ++k)
      if (!std::isfinite(m[k]))
        throw py::value_error(std::string(name) + "[" + std::to_string(i) + "] has a NaN or Inf entry");
    if (rows == 4 && !(m[12] == 0.0 && m[13] == 0.0 && m[14] == 0.0 && m[15] == 1.0))
      throw py::value_error(std::string(name) + "[" + std::to_string(i) +
                            "] is not affine: its last row must be (0, 0, 0, 1)");
    for (int k = 0; k < 12; ++k) {
      out[size_t(i) * 12 + k] = float(m[k]);
      if (!std::isfinite(out[size_t(i) * 12 + k]))
        throw py::value_error(std::string(name) + "[" + std::to_string(i) + "] has an entry beyond float range");
    }
  }
  return out;
}

Vec3 vec3(const std::array<float, 3>& a) { return Vec3(a[0], a[1], a[2]); }

ColorSpace parse_colorspace(const std::string& s) {
  if (s == "sRGB") return ColorSpace::SRGB;
  if (s == "Non-Color" || s == "Linear" || s == "Raw") return ColorSpace::Linear;
  throw py::value_error("colorspace must be 'sRGB', 'Non-Color', 'Linear' or 'Raw', got '" + s + "'");
}

Interpolation parse_interpolation(const std::string& s) {
  if (s == "Linear") return Interpolation::Linear;
  if (s == "Closest") return Interpolation::Closest;
  if (s == "Cubic") return Interpolation::Cubic;
  throw py::value_error("interpolation must be 'Linear', 'Closest' or 'Cubic', got '" + s + "'");
}

CoatLayering parse_coat_layering(const std::string& s) {
  if (s == "CYCLES_4_2") return CoatLayering::Cycles4_2;
  if (s == "CYCLES_4_5") return CoatLayering::Cycles4_5;
  if (s == "CYCLES_5_1") return CoatLayering::Cycles5_1;
  throw py::value_error("coat_layering must be 'CYCLES_4_2', 'CYCLES_4_5' or 'CYCLES_5_1', got '" + s + "'");
}

SensorFit parse_fit(const std::string& s) {
  if (s == "AUTO") return SensorFit::Auto;
  if (s == "HORIZONTAL") return SensorFit::Horizontal;
  if (s == "VERTICAL") return SensorFit::Vertical;
  throw py::value_error("sensor_fit must be 'AUTO', 'HORIZONTAL' or 'VERTICAL', got '" + s + "'");
}

PanoramaType parse_panorama_type(const std::string& s) {
  if (s == "EQUIRECTANGULAR") return PanoramaType::Equirectangular;
  if (s == "FISHEYE_EQUIDISTANT") return PanoramaType::FisheyeEquidistant;
  if (s == "FISHEYE_EQUISOLID") return PanoramaType::FisheyeEquisolid;
  if (s == "MIRRORBALL") return PanoramaType::MirrorBall;
  if (s == "FISHEYE_LENS_POLYNOMIAL") return PanoramaType::FisheyeLensPolynomial;
  if (s == "EQUIANGULAR_CUBEMAP_FACE") return PanoramaType::EquiangularCubemapFace;
  if (s == "CENTRAL_CYLINDRICAL") return PanoramaType::CentralCylindrical;
  throw py::value_error("panorama type must be one of EQUIRECTANGULAR, FISHEYE_EQUIDISTANT, "
                        "FISHEYE_EQUISOLID, MIRRORBALL, FISHEYE_LENS_POLYNOMIAL, "
                        "EQUIANGULAR_CUBEMAP_FACE, CENTRAL_CYLINDRICAL; got '" + s + "'");
}

// set_camera's `panorama` dict (keys as PanoramaParams, Blender's names; missing keys keep the
// defaults); unknown keys are an error.
PanoramaParams parse_panorama(const py::dict& d) {
  PanoramaParams p;
  for (const auto& item : d) {
    const std::string key = py::cast<std::string>(item.first);
    const py::handle v = item.second;
    if (key == "type") p.type = parse_panorama_type(py::cast<std::string>(v));
    else if (key == "fisheye_fov") p.fisheye_fov = py::cast<float>(v);
    else if (key == "fisheye_lens") p.fisheye_lens_mm = py::cast<float>(v);
    else if (key == "latitude_min") p.latitude_min = py::cast<float>(v);
    else if (key == "latitude_max") p.latitude_max = py::cast<float>(v);
    else if (key == "longitude_min") p.longitude_min = py::cast<float>(v);
    else if (key == "longitude_max") p.longitude_max = py::cast<float>(v);
    else if (key == "polynomial") p.polynomial = py::cast<std::array<float, 5>>(v);
    else if (key == "cylinder") p.cylinder = py::cast<std::array<float, 4>>(v);
    else if (key == "sensor_width") p.sensor_width_mm = py::cast<float>(v);
    else if (key == "sensor_height") p.sensor_height_mm = py::cast<float>(v);
    else if (key == "viewplane") p.viewplane = py::cast<std::array<float, 4>>(v);
    else throw py::value_error("unknown panorama setting '" + key + "'");
  }
  return p;
}

// set_camera's `stereo` dict (keys as SphericalStereo's); unknown keys are an error.
SphericalStereo parse_stereo(const py::dict& d) {
  SphericalStereo st;
  for (const auto& item : d) {
    const std::string key = py::cast<std::string>(item.first);
    const float v = py::cast<float>(item.second);
    if (key == "eye_offset") st.eye_offset = v;
    else if (key == "convergence_distance") st.convergence_distance = v;
    else if (key == "pole_merge_from") st.pole_merge_from = v;
    else if (key == "pole_merge_to") st.pole_merge_to = v;
    else throw py::value_error("unknown stereo setting '" + key + "'");
  }
  return st;
}

}  // namespace

void init_scene(py::module_& m) {
  py::class_<Scene, std::shared_ptr<Scene>>(m, "Scene", "Meshes, materials, lights and camera, in Blender's world space and units.")
      .def(py::init<>())
      .def(
          "add_material",
          [](Scene& s, std::array<float, 3> base_color, float metallic, float roughness, float specular,
             std::array<float, 3> emission, float emission_strength, float specular_tint, int base_color_texture,
             int metallic_texture, int roughness_texture, int emission_texture, int normal_texture,
             float normal_strength, float ior, std::array<float, 3> specular_tint_color, bool multiscatter_ggx,
             int bump_texture, float bump_strength, float bump_distance,
             float transmission, float transmission_roughness, bool glass,
             float alpha, int alpha_texture, std::array<float, 3> transparent_color,
             const std::string& distribution, bool alpha_from_luminance, bool alpha_inverted, int program,
             int base_color_register, int metallic_register, int roughness_register, int emission_register,
             int normal_register, int alpha_register, int surface_normal_register, int transmission_register,
             float coat_weight,
             float coat_roughness, float coat_ior, std::array<float, 3> coat_tint, int coat_weight_register,
             int coat_roughness_register, int coat_ior_register, int coat_tint_register, int coat_normal_register,
             float sheen_weight,
             float sheen_roughness, float sheen_tint, std::array<float, 3> sheen_tint_color,
             int sheen_weight_register, int sheen_roughness_register, int sheen_tint_register, float anisotropy,
             float anisotropic_rotation, int anisotropy_register, int anisotropic_rotation_register,
             int tangent_register, float hair_offset, float subsurface, std::array<float, 3> subsurface_radius,
             std::array<float, 3> subsurface_color, float subsurface_ior, float subsurface_anisotropy,
             int subsurface_register, int subsurface_radius_register, int subsurface_color_register,
             bool subsurface_fixed_radius, float subsurface_entry_alpha, bool subsurface_skin,
             float subsurface_min_footprint, bool subsurface_after_diffuse, bool subsurface_van_de_hulst,
             bool subsurface_burley, float thin_film_thickness, float thin_film_ior, bool thin_film_cycles5,
             int thin_film_thickness_register, int thin_film_ior_register, bool thin_wall,
             float diffuse_roughness, bool emission_under_layers, const std::string& coat_layering,
             bool multiscatter_walk, float dispersion, bool glass_cycles4, bool transmission_anisotropic,
             int dispersion_register, std::array<float, 3> portal_direction, int portal_position_register,
             int portal_direction_register, int specular_tint_color_register, int diffuse_roughness_register,
             int transmission_roughness_register, int specular_register, int ior_register,
             int specular_tint_register, float hair_aspect_ratio, std::array<float, 3> hair_lobe_weights,
             float hair_random_roughness, float hair_random_color, float hair_random, const std::string& hair_coloring,
             float hair_melanin, float hair_melanin_redness, std::array<float, 3> hair_color) {
            if (distribution != "GGX" && distribution != "BECKMANN" && distribution != "ASHIKHMIN_SHIRLEY")
              throw py::value_error("distribution must be 'GGX', 'BECKMANN' or 'ASHIKHMIN_SHIRLEY', got '" +
                                    distribution + "'");
            if (glass && distribution == "ASHIKHMIN_SHIRLEY")
              throw py::value_error("distribution 'ASHIKHMIN_SHIRLEY' is the Glossy closure's, not glass's");
            Material mat;
            mat.coat_layering = parse_coat_layering(coat_layering);
            mat.base_color = vec3(base_color);
            mat.metallic = metallic;
            mat.roughness = roughness;
            mat.specular = specular;
            mat.emission = vec3(emission) * emission_strength;
            mat.specular_tint = specular_tint;
            mat.ior = ior;
            mat.specular_tint_color = vec3(specular_tint_color);
            mat.multiscatter_ggx = multiscatter_ggx;
            mat.multiscatter_walk = multiscatter_walk;
            mat.transmission = transmission;
            mat.transmission_roughness = transmission_roughness;
            mat.hair_offset = hair_offset;
            mat.hair_aspect_ratio = hair_aspect_ratio;
            mat.hair_lobe_weights = vec3(hair_lobe_weights);
            if (hair_coloring != "ABSORPTION" && hair_coloring != "MELANIN" && hair_coloring != "COLOR")
              throw py::value_error("hair_coloring must be 'ABSORPTION', 'MELANIN' or 'COLOR', got '" +
                                    hair_coloring + "'");
            mat.hair_coloring = hair_coloring == "MELANIN" ? 1 : hair_coloring == "COLOR" ? 2 : 0;
            mat.hair_random_roughness = hair_random_roughness;
            mat.hair_random_color = hair_random_color;
            mat.hair_random = hair_random;
            mat.hair_melanin = hair_melanin;
            mat.hair_melanin_redness = hair_melanin_redness;
            mat.hair_color = vec3(hair_color);
            mat.glass_node = glass;
            mat.distribution = distribution == "BECKMANN"            ? MicrofacetDistribution::Beckmann
                               : distribution == "ASHIKHMIN_SHIRLEY" ? MicrofacetDistribution::AshikhminShirley
                                                                     : MicrofacetDistribution::GGX;
            mat.glass_cycles4 = glass_cycles4;
            mat.transmission_anisotropic = transmission_anisotropic;
            mat.alpha = alpha;
            mat.transparent_color = vec3(transparent_color);
            mat.coat_weight = coat_weight;
            mat.coat_roughness = coat_roughness;
            mat.coat_ior = coat_ior;
            mat.coat_tint = vec3(coat_tint);
            mat.sheen_weight = sheen_weight;
            mat.sheen_roughness = sheen_roughness;
            mat.sheen_tint = sheen_tint;
            mat.sheen_tint_color = vec3(sheen_tint_color);
            mat.anisotropy = anisotropy;
            mat.anisotropic_rotation = anisotropic_rotation;
            mat.subsurface = subsurface;
            mat.subsurface_radius = vec3(subsurface_radius);
            mat.subsurface_color = vec3(subsurface_color);
            mat.subsurface_ior = subsurface_ior;
            mat.subsurface_anisotropy = subsurface_anisotropy;
            mat.subsurface_fixed_radius = subsurface_fixed_radius;
            mat.subsurface_entry_alpha = subsurface_entry_alpha;
            mat.subsurface_skin = subsurface_skin;
            mat.subsurface_min_footprint = subsurface_min_footprint;
            mat.subsurface_after_diffuse = subsurface_after_diffuse;
            mat.subsurface_van_de_hulst = subsurface_van_de_hulst;
            mat.subsurface_burley = subsurface_burley;
            mat.thin_film_thickness = thin_film_thickness;
            mat.thin_film_ior = thin_film_ior;
            mat.thin_film_cycles5 = thin_film_cycles5;
            mat.thin_wall = thin_wall;
            mat.dispersion = dispersion;
            mat.portal_direction = vec3(portal_direction);
            mat.emission_under_layers = emission_under_layers;
            mat.diffuse_roughness = std::isfinite(diffuse_roughness) ? clamp01(diffuse_roughness) : 0.0f;
            MaterialTextures tex;
            tex.base_color = base_color_texture;
            tex.metallic = metallic_texture;
            tex.roughness = roughness_texture;
            tex.emission = emission_texture;
            tex.emission_strength = emission_strength;
            tex.normal = normal_texture;
            tex.normal_strength = normal_strength;
            tex.bump = bump_texture;
            tex.bump_strength = bump_strength;
            tex.bump_distance = bump_distance;
            tex.alpha = alpha_texture;
            tex.alpha_from_luminance = alpha_from_luminance;
            tex.alpha_inverted = alpha_inverted;
            tex.program = program_outputs(program, base_color_register, metallic_register, roughness_register,
                                          emission_register, normal_register, alpha_register,
                                          surface_normal_register);
            tex.program.transmission = program_register(transmission_register);
            tex.program.coat_weight = program_register(coat_weight_register);
            tex.program.coat_roughness = program_register(coat_roughness_register);
            tex.program.coat_ior = program_register(coat_ior_register);
            tex.program.coat_tint = program_register(coat_tint_register);
            tex.program.coat_normal = program_register(coat_normal_register);
            tex.program.sheen_weight = program_register(sheen_weight_register);
            tex.program.sheen_roughness = program_register(sheen_roughness_register);
            tex.program.sheen_tint = program_register(sheen_tint_register);
            tex.program.anisotropy = program_register(anisotropy_register);
            tex.program.anisotropic_rotation = program_register(anisotropic_rotation_register);
            tex.program.tangent = program_register(tangent_register);
            tex.program.subsurface = program_register(subsurface_register);
            tex.program.subsurface_radius = program_register(subsurface_radius_register);
            tex.program.subsurface_color = program_register(subsurface_color_register);
            tex.program.thin_film_thickness = program_register(thin_film_thickness_register);
            tex.program.thin_film_ior = program_register(thin_film_ior_register);
            tex.program.dispersion = program_register(dispersion_register);
            tex.program.portal_position = program_register(portal_position_register);
            tex.program.portal_direction = program_register(portal_direction_register);
            tex.program.specular_tint_color = program_register(specular_tint_color_register);
            tex.program.diffuse_roughness = program_register(diffuse_roughness_register);
            tex.program.transmission_roughness = program_register(transmission_roughness_register);
            tex.program.specular = program_register(specular_register);
            tex.program.ior = program_register(ior_register);
            tex.program.specular_tint = program_register(specular_tint_register);
            return s.add_material(mat, tex);
          },
          py::arg("base_color") = std::array<float, 3>{0.8f, 0.8f, 0.8f}, py::arg("metallic") = 0.0f,
          py::arg("roughness") = 0.5f, py::arg("specular") = 0.5f,
          py::arg("emission") = std::array<float, 3>{0.0f, 0.0f, 0.0f}, py::arg("emission_strength") = 0.0f,
          py::arg("specular_tint") = 0.0f, py::arg("base_color_texture") = -1, py::arg("metallic_texture") = -1,
          py::arg("roughness_texture") = -1, py::arg("emission_texture") = -1, py::arg("normal_texture") = -1,
          py::arg("normal_strength") = 1.0f, py::arg("ior") = 1.45f,
          py::arg("specular_tint_color") = std::array<float, 3>{1.0f, 1.0f, 1.0f}, py::arg("multiscatter_ggx") = true,
          py::arg("bump_texture") = -1, py::arg("bump_strength") = 1.0f, py::arg("bump_distance") = 1.0f,
          py::arg("transmission") = 0.0f,
          py::arg("transmission_roughness") = 0.0f, py::arg("glass") = false, py::arg("alpha") = 1.0f,
          py::arg("alpha_texture") = -1, py::arg("transparent_color") = std::array<float, 3>{1.0f, 1.0f, 1.0f},
          py::arg("distribution") = "GGX", py::arg("alpha_from_luminance") = false,
          py::arg("alpha_inverted") = false, py::arg("program") = -1, py::arg("base_color_register") = -1,
          py::arg("metallic_register") = -1, py::arg("roughness_register") = -1, py::arg("emission_register") = -1,
          py::arg("normal_register") = -1, py::arg("alpha_register") = -1,
          py::arg("surface_normal_register") = -1, py::arg("transmission_register") = -1,
          py::arg("coat_weight") = 0.0f, py::arg("coat_roughness") = 0.03f,
          py::arg("coat_ior") = 1.5f, py::arg("coat_tint") = std::array<float, 3>{1.0f, 1.0f, 1.0f},
          py::arg("coat_weight_register") = -1, py::arg("coat_roughness_register") = -1,
          py::arg("coat_ior_register") = -1, py::arg("coat_tint_register") = -1,
          py::arg("coat_normal_register") = -1, py::arg("sheen_weight") = 0.0f,
          py::arg("sheen_roughness") = 0.5f, py::arg("sheen_tint") = 0.5f,
          py::arg("sheen_tint_color") = std::array<float, 3>{1.0f, 1.0f, 1.0f}, py::arg("sheen_weight_register") = -1,
          py::arg("sheen_roughness_register") = -1, py::arg("sheen_tint_register") = -1,
          py::arg("anisotropy") = 0.0f, py::arg("anisotropic_rotation") = 0.0f, py::arg("anisotropy_register") = -1,
          py::arg("anisotropic_rotation_register") = -1, py::arg("tangent_register") = -1,
          py::arg("hair_offset") = 0.0f, py::arg("subsurface") = 0.0f,
          py::arg("subsurface_radius") = std::array<float, 3>{1.0f, 0.2f, 0.1f},
          py::arg("subsurface_color") = std::array<float, 3>{0.8f, 0.8f, 0.8f}, py::arg("subsurface_ior") = 1.4f,
          py::arg("subsurface_anisotropy") = 0.0f, py::arg("subsurface_register") = -1,
          py::arg("subsurface_radius_register") = -1, py::arg("subsurface_color_register") = -1,
          py::arg("subsurface_fixed_radius") = false, py::arg("subsurface_entry_alpha") = -1.0f,
          py::arg("subsurface_skin") = false, py::arg("subsurface_min_footprint") = 0.0f,
          py::arg("subsurface_after_diffuse") = false, py::arg("subsurface_van_de_hulst") = false,
          py::arg("subsurface_burley") = false, py::arg("thin_film_thickness") = 0.0f,
          py::arg("thin_film_ior") = 1.33f, py::arg("thin_film_cycles5") = false,
          py::arg("thin_film_thickness_register") = -1, py::arg("thin_film_ior_register") = -1,
          py::arg("thin_wall") = false, py::arg("diffuse_roughness") = 0.0f,
          py::arg("emission_under_layers") = false, py::arg("coat_layering") = "CYCLES_4_5",
          py::arg("multiscatter_walk") = false, py::arg("dispersion") = 0.0f, py::arg("glass_cycles4") = false,
          py::arg("transmission_anisotropic") = false, py::arg("dispersion_register") = -1,
          py::arg("portal_direction") = std::array<float, 3>{0.0f, 0.0f, 0.0f},
          py::arg("portal_position_register") = -1, py::arg("portal_direction_register") = -1,
          py::arg("specular_tint_color_register") = -1, py::arg("diffuse_roughness_register") = -1,
          py::arg("transmission_roughness_register") = -1, py::arg("specular_register") = -1,
          py::arg("ior_register") = -1, py::arg("specular_tint_register") = -1,
          py::arg("hair_aspect_ratio") = 1.0f, py::arg("hair_lobe_weights") = std::array<float, 3>{1.0f, 1.0f, 1.0f},
          py::arg("hair_random_roughness") = 0.0f, py::arg("hair_random_color") = 0.0f, py::arg("hair_random") = 0.0f,
          py::arg("hair_coloring") = "ABSORPTION", py::arg("hair_melanin") = 0.0f,
          py::arg("hair_melanin_redness") = 0.0f, py::arg("hair_color") = std::array<float, 3>{1.0f, 1.0f, 1.0f},
          "Adds a metallic/roughness material; returns its index. *_texture are ids from add_texture "
          "(-1: none); a texture replaces the constant (emission: texture colour * emission_strength); "
          "bump_texture: a height map (luminance) as Blender's Bump node, used when there is no normal map. "
          "specular_tint_color and multiscatter_ggx are read by PRINCIPLED_V2 only; multiscatter_walk by "
          "PRINCIPLED only (Blender 3.x's Multiscatter GGX: the specular lobe a random walk when roughness > "
          "0.075 and the material has no glass; its glass the random walk of multiscatter_glass_bsdf.h when roughness > "
          "0.05), and by the Glass BSDF (glass=True, GGX: Blender 3.x's Multiscatter GGX glass). dispersion: PRINCIPLED_V2's transmission's inverse Abbe number "
          "(Blender 5.x's Transmission Dispersion Scale / Abbe Number; finite, >= 0, 0: none), rendered as Cycles "
          "5.x (dispersion.h); dispersion_register: the program's value of it per hit instead (x, negative: 0). "
          "transmission, ior, transmission_roughness: the Principled BSDF's glass (transmission and "
          "transmission_roughness in [0, 1], ior in (0, 1000]; ior is also PRINCIPLED_V2's IOR); glass=True: "
          "Blender's Glass BSDF node "
          "(base_color its Color, roughness, ior; distribution 'GGX' or 'BECKMANN', also a mixture's Refraction, "
          "Metallic and Glossy closures', and 'ASHIKHMIN_SHIRLEY' the Glossy closure's alone; glass_cycles4: as "
          "Cycles 4.0+ renders it, GGX with the Fresnel per microfacet and multiscatter_ggx its Multiscatter GGX, "
          "else as Cycles 3.4). alpha in "
          "[0, 1] (or alpha_texture: a texture's alpha channel; its colour's luminance with alpha_from_luminance; 1 - "
          "that with alpha_inverted): rays pass straight through with "
          "probability 1 - alpha, tinted by transparent_color (Principled Alpha: white; Transparent "
          "BSDF: alpha 0 and its Color). program: an id from add_shader_program whose registers "
          "*_register (-1: none) feed those inputs instead of the constant or texture (floats read x; "
          "emission: the colour x emission_strength; normal_register: the Normal, a vector facing the viewer, "
          "which replaces normal_texture and bump_texture; alpha_register: the alpha, clamped to [0, 1], which "
          "replaces alpha and alpha_texture, run wherever a ray meets the surface, shadow rays included; "
          "surface_normal_register: the surface's normal after the Material Output's Displacement, as bump, "
          "what the shadow terminator's smoothing compares the Normal with; transmission_register: PRINCIPLED_V2's "
          "Transmission Weight, clamped to [0, 1], for a material added with transmission > 0). coat_*: the Principled BSDF's "
          "coat (weight >= 0, 0: none; roughness in [0, 1]; ior >= 1 and tint >= 0, PRINCIPLED_V2 only: v1's "
          "clearcoat has IOR 1.5 and no tint), from the program's coat_*_register when given (coat_normal_register: "
          "the Clearcoat / Coat Normal, a vector facing the viewer; without it the coat shades with the surface's "
          "normal before the Normal's bump or normal map). sheen_*: the "
          "Principled BSDF's sheen (weight >= 0, 0: none; PRINCIPLED: sheen_tint in [0, 1]; PRINCIPLED_V2: "
          "sheen_roughness in [0, 1] and sheen_tint_color >= 0), from the program's sheen_*_register when given "
          "(sheen_tint_register: v1's factor its x, v2's colour). anisotropy in [-1, 1] and anisotropic_rotation "
          "(turns about the normal): a Glossy closure's anisotropy (glossy_bsdf.h) along the tangent the "
          "program's tangent_register gives (a world direction; none: isotropic), from the program's "
          "anisotropy_register / anisotropic_rotation_register when given (also the Principled BSDF's Anisotropic "
          "and Anisotropic Rotation). transmission_anisotropic (Cycles 5.x): the glass is stretched too, "
          "PRINCIPLED_V2's transmission as its reflection, a Glass BSDF's (glass=True, glass_cycles4) by "
          "anisotropy as a Glossy closure's (principled_glass_v2.h). subsurface_*: subsurface scattering by "
          "Cycles' Random Walk: PRINCIPLED's Subsurface in [0, 1] (0: none) with its Radius (metres, >= 0), "
          "Color, IOR and Anisotropy (subsurface_fixed_radius: Cycles' Random Walk (Fixed Radius): the "
          "radius / 4 pi, no IOR adjustment; subsurface_entry_alpha >= 0: Cycles 4.x's rough refractive entry "
          "of that GGX alpha, < 0: 3.4's Lambertian one; subsurface_skin: 4.x's Random Walk (Skin); "
          "subsurface_min_footprint: Cycles 4.0-4.4's diffuse fallback below that share of the ray's footprint; "
          "subsurface_after_diffuse: Cycles 5.x's walks after a diffuse bounce; subsurface_van_de_hulst: "
          "Blender 5.3's Random Walk; subsurface_burley: Christensen-Burley's disk), Principled v2's Subsurface Weight (brdf_model PRINCIPLED_V2: "
          "subsurface), or a Subsurface Scattering node's closure (a mixture's 'subsurface' "
          "component: base_color its Color, subsurface_radius its Radius x Scale), from the program's "
          "subsurface_register / subsurface_radius_register / subsurface_color_register when given. "
          "thin_film_*: a Thin Film (PRINCIPLED_V2's Principled BSDF, a Metallic closure): thickness in nm "
          "(<= 0.1: none) and IOR (> 0), from the program's thin_film_*_register when given; "
          "thin_film_cycles5: Cycles 5.x's film (else 4.x's). "
          "thin_wall: PRINCIPLED_V2's Thin Wall (Blender 5.x): the transmission is a thin slab and the "
          "subsurface a diffuse reflection and translucency (Subsurface Anisotropy splits them), "
          "no walk. diffuse_roughness: PRINCIPLED_V2's Diffuse Roughness (Blender 4.3+), the diffuse layer "
          "an energy-preserving Oren-Nayar above 0. emission_under_layers: PRINCIPLED_V2's Principled BSDF, whose "
          "emission Cycles 4.x darkens by its coat and sheen seen from the view (as the layers under them). "
          "coat_layering: how PRINCIPLED_V2's coat darkens the layers under it, as Cycles 'CYCLES_4_2' (4.0-4.4), "
          "'CYCLES_4_5' (4.5-5.0) or 'CYCLES_5_1' (5.1+) does (principled_coat.h). portal_direction: a mixture's "
          "'ray_portal' closure's Direction (world; zero: the ray's own; base_color its Color), from the "
          "program's portal_direction_register when given; portal_position_register: its linked Position "
          "(world; none: the hit point). specular_tint_color_register: the program's specular_tint_color per hit "
          "(at least 0: PRINCIPLED_V2's Specular Tint, a Metallic closure's Edge Tint or IOR); "
          "diffuse_roughness_register, transmission_roughness_register: the program's diffuse_roughness "
          "(PRINCIPLED_V2) and transmission_roughness (a Toon closure's Smooth) per hit, clamped to [0, 1]; "
          "specular_register, ior_register: the program's specular (at least 0) and ior (clamped to "
          "[1e-5, 1000]) per hit; specular_tint_register: the program's specular_tint (PRINCIPLED's Specular "
          "Tint, clamped to [0, 1]) per hit.")
      .def(
          "add_shader_program",
          [](Scene& s, const py::object& constants, const py::object& code, int registers, const py::object& data) {
            return s.add_shader_program(shader_program(s, constants, code, registers, data));
          },
          py::arg("constants"), py::arg("code"), py::arg("registers"), py::arg("data") = py::none(),
          "Adds a shader program (docs/python_api.md): constants (N, 4) float32 preloaded into registers "
          "0..N-1, code (M, 17) int32 rows [opcode, mode, flags, resource, out, in0 .. in11] (resource: an "
          "Image's texture id, or the offset in data of an op's table: its length n, then n floats), "
          "registers the register count, data (K,) float32 or None. Raises ValueError naming a bad "
          "instruction. Returns its id.")
      .def(
          "set_mesh_attributes",
          [](Scene& s, uint32_t mesh, const py::object& values, const py::object& ids, bool prototype) {
            const auto v = shaped_array<float>(values, "values", {-1, -1, 3});
            const auto i = shaped_array<int32_t>(ids, "ids", {-1});
            if (v.ndim() != 3 || v.shape(0) != i.size())
              throw py::value_error("values must have shape (len(ids), 3 * triangles, 3), got " + shape_string(v));
            s.set_mesh_attributes(mesh, prototype, v.data(), size_t(v.shape(1)), i.data(), size_t(i.size()));
          },
          py::arg("mesh"), py::arg("values"), py::arg("ids"), py::arg("prototype") = false,
          "Per-corner attributes of a mesh (or, with prototype=True, of a prototype) that shader programs "
          "read with the Attribute op: values (A, 3 * triangles, 3) float32 (triangle t's corners at 3t, 3t + 1, "
          "3t + 2), ids (A,) int32 naming each layer. NaN/Inf read as 0.")
      .def(
          "set_instance_constants",
          [](Scene& s, const py::object& ids, const py::object& layer_ids, const py::object& values) {
            const IndexArray id = as_indices(ids, "ids");
            if (id.ndim() != 1) throw py::value_error("ids must have shape (N,), got " + shape_string(id));
            const auto layers = shaped_array<int32_t>(layer_ids, "layer_ids", {-1});
            const auto v = shaped_array<float>(values, "values", {-1, -1, 3});
            if (v.shape(0) != id.size() || v.shape(1) != layers.size())
              throw py::value_error("values must have shape (len(ids), len(layer_ids), 3), got " + shape_string(v));
            s.set_instance_constants(id.data(), size_t(id.size()), layers.data(), size_t(layers.size()), v.data());
          },
          py::arg("ids"), py::arg("layer_ids"), py::arg("values"),
          "Constant attributes of instances (an instanced object's Object Info), which the Attribute op reads "
          "where the prototype has no such per-corner layer: ids (N,) instance ids, layer_ids (A,) int32, values "
          "(N, A, 3) float32. A layer an instance was never given reads 0; NaN/Inf read as 0.")
      .def("set_mesh_pass_index", &Scene::set_mesh_pass_index, py::arg("mesh"), py::arg("index"),
           "Blender's pass index of a mesh's object (from add_mesh), for the Object Index pass (default 0).")
      .def(
          "set_instance_pass_indices",
          [](Scene& s, const py::object& ids, const py::object& values) {
            const IndexArray id = as_indices(ids, "ids");
            const auto v = shaped_array<float>(values, "values", {-1});
            if (id.ndim() != 1 || v.size() != id.size())
              throw py::value_error("ids and values must have shape (N,), got " + shape_string(id) + " and " +
                                    shape_string(v));
            s.set_instance_pass_indices(id.data(), size_t(id.size()), v.data());
          },
          py::arg("ids"), py::arg("values"),
          "Blender's pass indices of instances (ids from add_instances), for the Object Index pass (default 0).")
      .def("set_mesh_holdout", &Scene::set_mesh_holdout, py::arg("mesh"), py::arg("holdout") = true,
           "Whether a mesh's object (from add_mesh) is a holdout (Blender's Object > Visibility > Holdout): "
           "camera rays that meet it leave the pixel transparent (its alpha's transparency kept).")
      .def(
          "set_instance_holdouts",
          [](Scene& s, const py::object& ids, bool holdout) {
            const IndexArray id = as_indices(ids, "ids");
            if (id.ndim() != 1) throw py::value_error("ids must have shape (N,), got " + shape_string(id));
            s.set_instance_holdouts(id.data(), size_t(id.size()), holdout);
          },
          py::arg("ids"), py::arg("holdout") = true,
          "Whether instances (ids from add_instances) are holdouts, as set_mesh_holdout.")
      .def("set_mesh_shadow_catcher", &Scene::set_mesh_shadow_catcher, py::arg("mesh"), py::arg("catcher") = true,
           "Whether a mesh's object (from add_mesh) is a shadow catcher (Blender's Object > Visibility > Shadow "
           "Catcher): camera paths that meet it split as Cycles' (the Shadow Catcher pass, Combined's matte).")
      .def(
          "set_instance_shadow_catchers",
          [](Scene& s, const py::object& ids, bool catcher) {
            const IndexArray id = as_indices(ids, "ids");
            if (id.ndim() != 1) throw py::value_error("ids must have shape (N,), got " + shape_string(id));
            s.set_instance_shadow_catchers(id.data(), size_t(id.size()), catcher);
          },
          py::arg("ids"), py::arg("catcher") = true,
          "Whether instances (ids from add_instances) are shadow catchers, as set_mesh_shadow_catcher.")
      .def_property_readonly("has_shadow_catchers", &Scene::has_shadow_catchers,
                             "Whether some object is a shadow catcher.")
      .def_property_readonly("has_holdouts", &Scene::has_holdouts,
                             "Whether some object is a holdout or some mixture has a Holdout closure.")
      .def(
          "set_material_pass_indices",
          [](Scene& s, const py::object& values) {
            const auto v = shaped_array<float>(values, "values", {-1});
            s.set_material_pass_indices(v.data(), size_t(v.size()));
          },
          py::arg("values"),
          "Blender's pass index of each material (by material id), for the Material Index pass (others 0).")
      .def(
          "run_shader_program",
          [](const Scene& s, int program, const py::object& uvs, float footprint, const py::object& positions,
             const py::object& normals, const py::object& true_normals, const py::object& incoming,
             const py::object& backfacing, const py::object& attributes) {
            return run_shader_program(s, program, uvs, footprint,
                                      {positions, normals, true_normals, incoming, backfacing, attributes});
          },
          py::arg("program"), py::arg("uvs"), py::arg("footprint") = 0.0f, py::kw_only(),
          py::arg("positions") = py::none(), py::arg("normals") = py::none(), py::arg("true_normals") = py::none(),
          py::arg("incoming") = py::none(), py::arg("backfacing") = py::none(), py::arg("attributes") = py::none(),
          "Every register of shader program `program` after running it at each UV of uvs (N, 2): "
          "a float32 array (N, registers, 4) (for tests and tools). The hits' other globals, each "
          "optional (else ShaderGlobals' defaults): positions, normals, true_normals, incoming (N, 3), "
          "backfacing (N,) (non-zero: a back face), attributes (N, A, 3) (layer a has the id a).")
      .def(
          "add_texture",
          [](Scene& s, const py::object& pixels, const std::string& colorspace, const std::string& interpolation) {
            const FloatArray a = FloatArray::ensure(numeric_array(pixels, "texture pixels", sizeof(float)));
            if (!a || a.ndim() != 3 || a.shape(0) < 1 || a.shape(1) < 1 || a.shape(2) < 1 || a.shape(2) > 4)
              throw py::value_error("texture pixels must have shape (height, width, 1..4)");
            return s.add_texture(Texture(int(a.shape(1)), int(a.shape(0)), int(a.shape(2)), a.data(),
                                         parse_colorspace(colorspace), parse_interpolation(interpolation)));
          },
          py::arg("pixels"), py::arg("colorspace") = "sRGB", py::arg("interpolation") = "Linear",
          "Adds an image texture from pixels with row 0 = BOTTOM (Blender's Image.pixels order); "
          "sRGB images are interpolated as stored and decoded after (as Cycles). Returns its id.")
      .def(
          "add_texture_file",
          [](Scene& s, const std::string& path, const std::string& colorspace, const std::string& interpolation) {
            const ColorSpace space = parse_colorspace(colorspace);
            const Interpolation interp = parse_interpolation(interpolation);
            py::gil_scoped_release release;
            return s.add_texture(Texture::from_file(path, space, interp));
          },
          py::arg("path"), py::arg("colorspace") = "sRGB", py::arg("interpolation") = "Linear",
          "Adds an image texture read with OpenImageIO; returns its id.")
      .def(
          "add_mesh",
          [](Scene& s, const py::object& positions, const py::object& triangles, const py::object& corner_normals,
             const py::object& material_indices, const py::object& corner_uvs) {
            const MeshArrays a = mesh_arrays(positions, triangles, corner_normals, material_indices,
                                             "material_indices", corner_uvs);
            return s.add_mesh(a.p.data(), a.num_vertices(), a.t.data(), a.num_triangles, a.normals(), a.materials(),
                              a.uvs());
          },
          py::arg("positions"), py::arg("triangles"), py::arg("corner_normals") = py::none(),
          py::arg("material_indices") = py::none(), py::arg("corner_uvs") = py::none(),
          "Adds a triangle mesh in world space; raises ValueError for malformed input.")
      .def(
          "add_curves",
          [](Scene& s, const py::object& keys, const py::object& radii, const py::object& curve_offsets,
             const py::object& materials, const std::string& shape, const py::object& random,
             const py::object& normals) {
            if (shape != "ROUND" && shape != "RIBBON")
              throw py::value_error("shape must be 'ROUND' or 'RIBBON', got '" + shape + "'");
            const auto k = shaped_array<float>(keys, "keys", {-1, 3});
            const size_t n = size_t(k.shape(0));
            const auto r = shaped_array<float>(radii, "radii", {py::ssize_t(n)});
            const auto offsets = shaped_array<int64_t>(curve_offsets, "curve_offsets", {-1});
            if (offsets.size() < 1) throw py::value_error("curve_offsets must hold at least one offset (0)");
            const size_t num_curves = size_t(offsets.size()) - 1;
            for (size_t c = 0; c < num_curves; ++c)
              if (offsets.data()[c + 1] < offsets.data()[c]) throw py::value_error("curve_offsets must ascend");
            if (offsets.data()[0] != 0 || offsets.data()[num_curves] != int64_t(n))
              throw py::value_error("curve_offsets must run from 0 to the number of keys (" + std::to_string(n) + ")");
            py::array_t<int64_t, py::array::c_style | py::array::forcecast> m;
            if (!materials.is_none()) m = shaped_array<int64_t>(materials, "materials", {py::ssize_t(num_curves)});
            py::array_t<float, py::array::c_style | py::array::forcecast> rnd;
            if (!random.is_none()) rnd = shaped_array<float>(random, "random", {py::ssize_t(num_curves)});
            py::array_t<float, py::array::c_style | py::array::forcecast> nrm;
            if (!normals.is_none()) nrm = shaped_array<float>(normals, "normals", {py::ssize_t(n), 3});
            return s.add_curves(k.data(), r.data(), n, offsets.data(), num_curves, materials.is_none() ? nullptr : m.data(),
                                shape == "ROUND" ? CurveShape::Round : CurveShape::Ribbon,
                                random.is_none() ? nullptr : rnd.data(), normals.is_none() ? nullptr : nrm.data());
          },
          py::arg("keys"), py::arg("radii"), py::arg("curve_offsets"), py::arg("materials") = py::none(),
          py::arg("shape") = "ROUND", py::arg("random") = py::none(), py::arg("normals") = py::none(),
          "Adds hair strands in world space: keys (K, 3), radii (K,), curve_offsets (C + 1,) from 0 to K "
          "(curve c: keys offsets[c] .. offsets[c + 1] - 1), materials (C,) or None; traced as Cycles' "
          "Catmull-Rom curves, shape 'ROUND' (3D Curves) or 'RIBBON' (Rounded Ribbons); random (C,) or None: the "
          "Curves Info node's Random per curve; normals (K, 3) or None: the curves' normal attribute (world space), "
          "which a Huang hair ellipse's major axis follows. Returns its id.")
      .def_property_readonly("num_curve_segments", &Scene::num_curve_segments)
      .def(
          "add_prototype",
          [](Scene& s, const py::object& positions, const py::object& triangles, const py::object& corner_normals,
             const py::object& material_slots, const py::object& corner_uvs) {
            const MeshArrays a =
                mesh_arrays(positions, triangles, corner_normals, material_slots, "material_slots", corner_uvs);
            return s.add_prototype(a.p.data(), a.num_vertices(), a.t.data(), a.num_triangles, a.normals(),
                                   a.materials(), a.uvs());
          },
          py::arg("positions"), py::arg("triangles"), py::arg("corner_normals") = py::none(),
          py::arg("material_slots") = py::none(), py::arg("corner_uvs") = py::none(),
          "Adds a mesh in object space to be instanced (its BVH is built now, once); material_slots "
          "(M,) >= 0 index the material table of each instance. Returns the prototype id.")
      .def(
          "add_instances",
          [](Scene& s, int64_t prototype, const py::object& transforms, const py::object& materials) {
            if (prototype < 0 || uint64_t(prototype) >= s.num_prototypes())
              throw py::value_error("prototype " + std::to_string(prototype) + " does not exist (the scene has " +
                                    std::to_string(s.num_prototypes()) + " prototypes)");
            const std::vector<float> xf = affine_rows(transforms, "transforms", -1);
            const size_t count = xf.size() / 12;
            const IndexArray table = as_indices(materials, "materials");
            const bool per_instance = table.ndim() == 2;
            if (!(table.ndim() == 1 || (per_instance && size_t(table.shape(0)) == count)) || table.size() == 0)
              throw py::value_error("materials must be a non-empty slot -> material table of shape (K,), or (N, K) "
                                    "with N = " + std::to_string(count) + " instances, got " + shape_string(table));
            const size_t table_size = size_t(per_instance ? table.shape(1) : table.shape(0));
            return s.add_instances(uint32_t(prototype), xf.data(), count, table.data(), table_size, per_instance);
          },
          py::arg("prototype"), py::arg("transforms"), py::arg("materials"),
          "Adds N instances of a prototype: transforms (N, 4, 4) or (N, 3, 4) object-to-world "
          "(matrix_world), materials the slot -> material table (K,) or one per instance (N, K). "
          "Returns the first id; the instances get ids first .. first + N - 1.")
      .def(
          "set_instance_transforms",
          [](Scene& s, const py::object& ids, const py::object& transforms) {
            const IndexArray id = as_indices(ids, "ids");
            if (id.ndim() > 1) throw py::value_error("ids must have shape (N,), got " + shape_string(id));
            const std::vector<float> xf = affine_rows(transforms, "transforms", id.size());
            s.set_instance_transforms(id.data(), xf.data(), size_t(id.size()));
          },
          py::arg("ids"), py::arg("transforms"),
          "Moves instances: ids (N,), transforms (N, 4, 4) or (N, 3, 4) (or one matrix for one id). "
          "Only the top-level BVH is rebuilt, at the next render.")
      .def(
          "remove_instances",
          [](Scene& s, const py::object& ids) {
            const IndexArray id = as_indices(ids, "ids");
            if (id.ndim() > 1) throw py::value_error("ids must have shape (N,), got " + shape_string(id));
            s.remove_instances(id.data(), size_t(id.size()));
          },
          py::arg("ids"), "Removes instances (ids (N,)); their ids are not reused.")
      .def(
          "add_sun",
          [](Scene& s, std::array<float, 3> direction, float strength, std::array<float, 3> color, float angle) {
            s.edit_lights([&](Lights& l) { l.add_sun(vec3(direction), strength, vec3(color), angle); });
          },
          py::arg("direction") = std::array<float, 3>{0, 0, -1}, py::arg("strength") = 1.0f,
          py::arg("color") = std::array<float, 3>{1, 1, 1}, py::arg("angle") = 0.00918f,
          "Sun: direction of travel, strength in W/m^2, angular diameter in radians.")
      .def(
          "add_point_light",
          [](Scene& s, std::array<float, 3> position, float power, std::array<float, 3> color, float radius) {
            s.edit_lights([&](Lights& l) { l.add_point(vec3(position), power, vec3(color), radius); });
          },
          py::arg("position"), py::arg("power") = 1000.0f, py::arg("color") = std::array<float, 3>{1, 1, 1},
          py::arg("radius") = 0.1f, "Point light: power in W, radius in m.")
      .def(
          "add_spot_light",
          [](Scene& s, std::array<float, 3> position, std::array<float, 3> direction, float power,
             std::array<float, 3> color, float radius, float spot_size, float spot_blend, bool cosine_falloff) {
            s.edit_lights([&](Lights& l) {
              l.add_spot(vec3(position), vec3(direction), power, vec3(color), radius, spot_size, spot_blend,
                         cosine_falloff);
            });
          },
          py::arg("position"), py::arg("direction") = std::array<float, 3>{0, 0, -1}, py::arg("power") = 1000.0f,
          py::arg("color") = std::array<float, 3>{1, 1, 1}, py::arg("radius") = 0.1f,
          py::arg("spot_size") = 0.785398f, py::arg("spot_blend") = 0.15f, py::arg("cosine_falloff") = true,
          "Spot light: a point light (W, m) limited to a cone of full angle spot_size (radians), "
          "pointing along direction (Blender: the light's -Z). cosine_falloff: its light also falls off "
          "with the cosine to its axis, as Cycles 3.x's (Cycles 4.x's does not).")
      .def(
          "add_area_light",
          [](Scene& s, std::array<float, 3> center, std::array<float, 3> edge_u, std::array<float, 3> edge_v,
             std::array<float, 3> direction, const std::string& shape, float power, std::array<float, 3> color,
             float spread) {
            if (shape != "RECTANGLE" && shape != "ELLIPSE")
              throw py::value_error("area light shape must be 'RECTANGLE' or 'ELLIPSE', got '" + shape + "'");
            s.edit_lights([&](Lights& l) {
              l.add_area(vec3(center), vec3(edge_u), vec3(edge_v), vec3(direction), shape == "ELLIPSE", power,
                         vec3(color), spread);
            });
          },
          py::arg("center"), py::arg("edge_u"), py::arg("edge_v"), py::arg("direction") = std::array<float, 3>{0, 0, -1},
          py::arg("shape") = "RECTANGLE", py::arg("power") = 10.0f, py::arg("color") = std::array<float, 3>{1, 1, 1},
          py::arg("spread") = 3.14159265f,
          "Area light: edges are full-size perpendicular vectors (object X * size, Y * size_y, scale "
          "included); it emits one-sided, on the side of its plane that direction points to, with "
          "radiance power / (4 area), like Cycles. ValueError for edges not perpendicular or a "
          "direction in the plane.")
      .def(
          "set_world",
          [](Scene& s, std::array<float, 3> color, float strength) {
            s.edit_lights([&](Lights& l) { l.set_world(vec3(color), strength); });
          },
          py::arg("color"), py::arg("strength") = 1.0f, "Uniform world radiance = color * strength.")
      .def("set_world_texture", &Scene::set_world_texture, py::arg("texture"), py::arg("strength") = 1.0f,
           "HDRI world: an equirectangular texture (from add_texture*) around the scene, mapped like "
           "Cycles' Environment Texture, importance-sampled.")
      .def("set_light_program", &Scene::set_light_program, py::arg("program"), py::arg("radiance_register"),
           "The light added last takes its node graph: program (from add_shader_program) run at each point of "
           "the light seen by a receiver (its ray length the distance), radiance_register's colour multiplying the "
           "light's. ValueError for a bad program or register, or when there is no light.")
      .def(
          "set_world_program",
          [](Scene& s, uint32_t program, int radiance_register, int resolution, const py::object& sun) {
            SunGuide guide;
            if (!sun.is_none()) {
              const auto v = sun.cast<std::array<float, 4>>();
              guide = SunGuide{Vec3(v[0], v[1], v[2]), v[3]};
            }
            s.set_world_program(program, radiance_register, resolution, guide);
          },
          py::arg("program"), py::arg("radiance_register"), py::arg("resolution") = 1024, py::arg("sun") = py::none(),
          "The world's node graph: program (from add_shader_program) run per direction as Cycles' background "
          "shader, its radiance in radiance_register; next-event estimation samples a map of it `resolution` "
          "cells wide (Cycles' world Map Resolution), and with sun = (x, y, z, half angle) a sun disc's cone "
          "as Cycles' sun guiding does (4 of 5 samples; the map then at least 512 wide). ValueError for a bad "
          "program, register, resolution or sun.")
      .def(
          "set_camera",
          [](Scene& s, const py::object& matrix, float lens, float sensor_width, float sensor_height,
             const std::string& sensor_fit, float shift_x, float shift_y, float clip_start, float clip_end,
             const std::string& type, float ortho_scale, std::optional<float> fstop,
             std::optional<float> aperture_radius, float focus_distance, int blades, float rotation, float ratio,
             std::optional<py::dict> panorama, std::optional<py::dict> stereo) {
            const FloatArray mat = FloatArray::ensure(numeric_array(matrix, "camera matrix", sizeof(float)));
            if (!mat || mat.size() != 16) throw py::value_error("camera matrix must be a 4x4 array");
            CameraParams c;
            std::copy_n(mat.data(), 16, c.camera_to_world.begin());
            if (type == "PERSP") c.type = CameraType::Perspective;
            else if (type == "ORTHO") c.type = CameraType::Orthographic;
            else if (type == "PANO") c.type = CameraType::Panoramic;
            else throw py::value_error("camera type must be 'PERSP', 'ORTHO' or 'PANO', got '" + type + "'");
            if (panorama && c.type != CameraType::Panoramic)
              throw py::value_error("panorama settings are for type 'PANO' only");
            if (panorama) c.panorama = parse_panorama(*panorama);
            if (stereo) c.stereo = parse_stereo(*stereo);
            c.lens_mm = lens;
            c.ortho_scale = ortho_scale;
            c.sensor_width_mm = sensor_width;
            c.sensor_height_mm = sensor_height;
            c.sensor_fit = parse_fit(sensor_fit);
            c.shift_x = shift_x;
            c.shift_y = shift_y;
            c.clip_start = clip_start;
            c.clip_end = clip_end;
            if (fstop && aperture_radius) throw py::value_error("give fstop or aperture_radius, not both");
            if (fstop) c.aperture_radius = aperture_radius_from_fstop(c.type, lens, *fstop);
            if (aperture_radius) c.aperture_radius = *aperture_radius;
            c.focus_distance = focus_distance;
            c.blades = blades;
            c.blade_rotation = rotation;
            c.aperture_ratio = ratio;
            Camera(c, 2, 2, 1.0f, 1.0f);  // validates now, so the error names the call that caused it
            s.set_camera(c);
          },
          py::arg("matrix"), py::arg("lens") = 50.0f, py::arg("sensor_width") = 36.0f,
          py::arg("sensor_height") = 24.0f, py::arg("sensor_fit") = "AUTO", py::arg("shift_x") = 0.0f,
          py::arg("shift_y") = 0.0f, py::arg("clip_start") = 0.1f, py::arg("clip_end") = 100.0f,
          py::kw_only(), py::arg("type") = "PERSP", py::arg("ortho_scale") = 6.0f, py::arg("fstop") = py::none(),
          py::arg("aperture_radius") = py::none(), py::arg("focus_distance") = 10.0f, py::arg("blades") = 0,
          py::arg("rotation") = 0.0f, py::arg("ratio") = 1.0f, py::arg("panorama") = py::none(),
          py::arg("stereo") = py::none(),
          "Blender camera, PERSP, ORTHO or PANO; matrix is camera-to-world (row-major, like matrix_world). "
          "PANO: panorama is a dict of type (Blender's panorama_type), fisheye_fov, fisheye_lens, "
          "latitude_min/max, longitude_min/max (radians), polynomial (k0..k4), cylinder (Central Cylindrical's "
          "u_min, u_max, v_min / radius, v_max / radius), sensor_width/height (the "
          "fitted sensor, mm), viewplane (left, right, bottom, top; default 0, 1, 0, 1, shift included). "
          "Depth of field: fstop (Blender's F-Stop, converted like Cycles) or aperture_radius (scene "
          "units), focus_distance, blades (< 3: round), rotation (radians), ratio (anamorphic). "
          "stereo (Spherical Stereo's eye, PERSP and PANO): a dict of eye_offset (left -interocular/2, right "
          "+interocular/2), convergence_distance (inf: parallel), pole_merge_from/to (radians; to <= 0: off).")
      .def_property_readonly("num_triangles", &Scene::num_triangles)
      .def_property_readonly("num_materials", &Scene::num_materials)
      .def_property_readonly("num_textures", &Scene::num_textures)
      .def_property_readonly("num_prototypes", &Scene::num_prototypes)
      .def_property_readonly("num_instances", &Scene::num_instances)
      .def_property_readonly("num_hidden_instances", &Scene::num_hidden_instances)
      .def_property_readonly("num_material_tables", &Scene::num_material_tables)
      .def_property_readonly("num_lights", [](const Scene& s) { return s.lights().count(); });
}

}  // namespace torrance::python
