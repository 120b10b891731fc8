// Scene.set_material_volume and Scene.set_world_volume: homogeneous volumes (media/scene_media.h),
// bound onto the Scene class that init_scene defines.
#include "bindings.h"

#include "torrance/scene/scene.h"

#include <pybind11/stl.h>

#include <array>
#include <string>

namespace torrance::python {
namespace {

// Blender's names of the Volume Scatter node's Phase menu (its enum identifiers).
PhaseKind phase_kind(const std::string& name) {
  if (name == "HENYEY_GREENSTEIN") return PhaseKind::HenyeyGreenstein;
  if (name == "RAYLEIGH") return PhaseKind::Rayleigh;
  if (name == "DRAINE") return PhaseKind::Draine;
  if (name == "FOURNIER_FORAND") return PhaseKind::FournierForand;
  if (name == "MIE") return PhaseKind::Mie;
  throw py::value_error("unknown volume phase '" + name +
                        "' (HENYEY_GREENSTEIN, RAYLEIGH, DRAINE, FOURNIER_FORAND or MIE)");
}

// Blender's names of the material's and world's Volume Sampling (cycles' volume_sampling).
VolumeSampling volume_sampling(const std::string& name) {
  if (name == "DISTANCE") return VolumeSampling::Distance;
  if (name == "EQUIANGULAR") return VolumeSampling::Equiangular;
  if (name == "MULTIPLE_IMPORTANCE") return VolumeSampling::MultipleImportance;
  throw py::value_error("unknown volume sampling '" + name + "' (DISTANCE, EQUIANGULAR or MULTIPLE_IMPORTANCE)");
}

HomogeneousMedium medium(std::array<float, 3> sigma_a, std::array<float, 3> sigma_s, std::array<float, 3> emission,
                         float anisotropy, const std::string& phase, float phase_a, float phase_b,
                         const std::string& sampling) {
  HomogeneousMedium m;
  m.sampling = volume_sampling(sampling);
  m.phase = phase_kind(phase);
  m.phase_a = phase_a;
  m.phase_b = phase_b;
  m.sigma_a = Vec3(sigma_a[0], sigma_a[1], sigma_a[2]);
  m.sigma_s = Vec3(sigma_s[0], sigma_s[1], sigma_s[2]);
  m.emission = Vec3(emission[0], emission[1], emission[2]);
  m.anisotropy = anisotropy;
  return m;
}

}  // namespace

void init_media(py::module_& m) {
  auto scene = py::reinterpret_borrow<py::class_<Scene, std::shared_ptr<Scene>>>(m.attr("Scene"));
  constexpr std::array<float, 3> kZero{0.0f, 0.0f, 0.0f};
  scene.def(
      "set_material_volume",
      [](Scene& s, uint32_t material, std::array<float, 3> sigma_a, std::array<float, 3> sigma_s,
         std::array<float, 3> emission, float anisotropy, bool pass_through, const std::string& phase, float phase_a,
         float phase_b, const std::string& sampling) {
        s.set_material_volume(
            material, medium(sigma_a, sigma_s, emission, anisotropy, phase, phase_a, phase_b, sampling), pass_through);
      },
      py::arg("material"), py::arg("sigma_a") = kZero, py::arg("sigma_s") = kZero, py::arg("emission") = kZero,
      py::arg("anisotropy") = 0.0f, py::arg("pass_through") = false, py::arg("phase") = "HENYEY_GREENSTEIN",
      py::arg("phase_a") = 0.0f, py::arg("phase_b") = 0.0f, py::arg("sampling") = "MULTIPLE_IMPORTANCE",
      "The homogeneous volume inside the closed meshes of `material`: absorption and scattering "
      "coefficients per metre (RGB), emitted radiance per metre, the anisotropy g of its scattering. phase: "
      "its phase function as Blender's Volume Scatter names it (HENYEY_GREENSTEIN, RAYLEIGH, DRAINE: g and "
      "alpha = phase_a, FOURNIER_FORAND: IOR = phase_a and backscatter = phase_b, MIE: diameter in "
      "micrometres = phase_a). pass_through: the material has no surface shader (paths cross its surface without a "
      "bounce). sampling: the material's Volume Sampling (DISTANCE, EQUIANGULAR or MULTIPLE_IMPORTANCE, "
      "Cycles' default): how the point lit by next-event estimation is drawn (equiangular toward a point, spot or "
      "area light: media/equiangular.h). ValueError for a negative or non-finite value, |anisotropy| > 1 or an unknown material.");
  scene.def(
      "set_material_volume_program",
      [](Scene& s, uint32_t material, uint32_t program, int sigma_a, int sigma_s, int emission, float anisotropy,
         std::array<float, 3> bounds_min, std::array<float, 3> bounds_max, bool pass_through,
         const std::string& phase, float phase_a, float phase_b) {
        VaryingMedium v;
        v.phase = phase_kind(phase);
        v.phase_a = phase_a;
        v.phase_b = phase_b;
        v.program = program;
        v.sigma_a = int16_t(sigma_a);
        v.sigma_s = int16_t(sigma_s);
        v.emission = int16_t(emission);
        v.anisotropy = anisotropy;
        v.bounds_min = Vec3(bounds_min[0], bounds_min[1], bounds_min[2]);
        v.bounds_max = Vec3(bounds_max[0], bounds_max[1], bounds_max[2]);
        s.set_material_volume(material, v, pass_through);
      },
      py::arg("material"), py::arg("program"), py::arg("sigma_a") = -1, py::arg("sigma_s") = -1,
      py::arg("emission") = -1, py::arg("anisotropy") = 0.0f, py::arg("bounds_min") = kZero,
      py::arg("bounds_max") = kZero, py::arg("pass_through") = false, py::arg("phase") = "HENYEY_GREENSTEIN",
      py::arg("phase_a") = 0.0f, py::arg("phase_b") = 0.0f,
      "A heterogeneous volume inside the closed meshes of `material`: shader program `program` (from "
      "add_shader_program), run at points inside (Geometry > Position the point's), computes the absorption "
      "and scattering coefficients and the emitted radiance per metre in colour registers sigma_a, sigma_s "
      "and emission (-1: zero; negative values count as 0); the anisotropy and phase function (as "
      "set_material_volume's) are constant. "
      "bounds_min/bounds_max: a world box holding the material's meshes, where the majorant is found. Its points are "
      "drawn by distance sampling (delta tracking) whatever the material's Volume Sampling. "
      "ValueError for an unknown material or program, a register the program does not write, |anisotropy| > 1.");
  scene.def(
      "add_volume_grid",
      [](Scene& s, const py::object& bricks, const py::object& origins, const py::object& world_to_index,
         const py::object& clip_min, const py::object& clip_max) {
        const auto b = shaped_array<float>(bricks, "bricks", {-1, VolumeGrid::kBrickSize, VolumeGrid::kBrickSize,
                                                              VolumeGrid::kBrickSize, -1});
        const auto o = shaped_array<int32_t>(origins, "origins", {-1, 3});
        const auto m = shaped_array<double>(world_to_index, "world_to_index", {4, 4});
        if (o.shape(0) != b.shape(0)) throw py::value_error("bricks and origins must have as many rows");
        std::vector<glm::ivec3> corner(size_t(o.shape(0)));
        for (size_t i = 0; i < corner.size(); ++i)
          corner[i] = glm::ivec3(o.data()[3 * i], o.data()[3 * i + 1], o.data()[3 * i + 2]);
        Mat4 matrix;
        for (int r = 0; r < 4; ++r)
          for (int c = 0; c < 4; ++c) matrix[c][r] = float(m.data()[4 * r + c]);
        try {
          VolumeGrid grid(b.ndim() == 5 ? int(b.shape(4)) : 1, matrix, corner,
                          std::vector<float>(b.data(), b.data() + b.size()));
          if (!clip_min.is_none() || !clip_max.is_none()) {
            const auto lo = shaped_array<double>(clip_min, "clip_min", {3});
            const auto hi = shaped_array<double>(clip_max, "clip_max", {3});
            grid.clip(Vec3(float(lo.data()[0]), float(lo.data()[1]), float(lo.data()[2])),
                      Vec3(float(hi.data()[0]), float(hi.data()[1]), float(hi.data()[2])));
          }
          return s.add_volume_grid(std::move(grid));
        } catch (const std::invalid_argument& e) {
          throw py::value_error(e.what());
        }
      },
      py::arg("bricks"), py::arg("origins"), py::arg("world_to_index"), py::arg("clip_min") = py::none(),
      py::arg("clip_max") = py::none(),
      "A sparse voxel grid heterogeneous volumes' programs read (VolumeGrid ops): bricks (N, 8, 8, 8, C) "
      "float32 indexed [z, y, x, channel], C 1 (a scalar) to 4 (RGBA), brick i's first voxel at origins[i] "
      "(index space, multiples of 8), world_to_index (4, 4, row-major) taking a world point to index "
      "space, where voxel centres lie at integers. Trilinear lookups; voxels outside the bricks are 0, "
      "NaN and infinite ones read as 0; clip_min/clip_max (index space, both or neither): lookups outside that box "
      "read 0. Returns the grid's id. ValueError for a bad shape, an unaligned "
      "or repeated origin, a singular transform.");
  scene.def(
      "set_world_volume",
      [](Scene& s, std::array<float, 3> sigma_a, std::array<float, 3> sigma_s, std::array<float, 3> emission,
         float anisotropy, const std::string& phase, float phase_a, float phase_b, const std::string& sampling) {
        s.set_world_volume(medium(sigma_a, sigma_s, emission, anisotropy, phase, phase_a, phase_b, sampling));
      },
      py::arg("sigma_a") = kZero, py::arg("sigma_s") = kZero, py::arg("emission") = kZero,
      py::arg("anisotropy") = 0.0f, py::arg("phase") = "HENYEY_GREENSTEIN", py::arg("phase_a") = 0.0f,
      py::arg("phase_b") = 0.0f, py::arg("sampling") = "MULTIPLE_IMPORTANCE",
      "The homogeneous volume around everything (the World's Volume), as set_material_volume's.");
}

}  // namespace torrance::python
