// The shader-program arguments of Scene.add_shader_program and Scene.add_material, from numpy
// arrays to the core's ShaderProgram and ShaderOutputs (the core validates the program itself).
#pragma once

#include "bindings.h"

#include "torrance/scene/scene.h"
#include "torrance/shader/shader_program.h"

#include <limits>
#include <vector>

namespace torrance::python {

// A code row: opcode, mode, flags, resource, out, then kShaderInputs input registers. Bits 6-7
// of flags hold ShaderInstruction::offset.
constexpr int kCodeColumns = 5 + kShaderInputs;

inline ShaderProgram shader_program(const Scene& scene, const py::object& constants, const py::object& code,
                                    int registers, const py::object& data) {
  const auto c = shaped_array<float>(constants, "constants", {-1, 4});
  const auto k = shaped_array<int32_t>(code, "code", {-1, kCodeColumns});
  std::vector<float> table;
  if (!data.is_none()) {
    const auto d = shaped_array<float>(data, "data", {-1});
    table.assign(d.data(), d.data() + d.size());
  }
  std::vector<glm::vec4> values(size_t(c.size() / 4));
  for (size_t i = 0; i < values.size(); ++i)
    values[i] = glm::vec4(c.data()[4 * i], c.data()[4 * i + 1], c.data()[4 * i + 2], c.data()[4 * i + 3]);
  std::vector<ShaderInstruction> instructions(size_t(k.size() / kCodeColumns));
  constexpr int32_t kShort = std::numeric_limits<int16_t>::max();
  for (size_t i = 0; i < instructions.size(); ++i) {
    const int32_t* row = k.data() + kCodeColumns * i;
    for (int j = 0; j < kCodeColumns; ++j)
      if ((j != 3 && (row[j] < -1 || row[j] > kShort)) || (j < 3 && row[j] < 0) || (j < 3 && row[j] > 255))
        throw py::value_error("code row " + std::to_string(i) + ": column " + std::to_string(j) + " holds " +
                              std::to_string(row[j]) + ", out of range");
    ShaderInstruction& ins = instructions[i];
    ins.op = ShaderOpcode(row[0]);
    ins.mode = uint8_t(row[1]);
    ins.flags = uint8_t(row[2] & 63);
    ins.offset = uint8_t(row[2] >> 6);  // flags bits 6-7: where the op reads the hit
    ins.resource = row[3];
    ins.out = int16_t(row[4]);
    for (int j = 0; j < kShaderInputs; ++j) ins.in[size_t(j)] = int16_t(row[5 + j]);
  }
  try {
    return ShaderProgram(std::move(values), std::move(instructions), registers, scene.num_textures(),
                         std::move(table));
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

// A material's program register from Python (-1: none), checked.
inline int16_t program_register(int r) {
  if (r < -1 || r >= ShaderProgram::kMaxRegisters)
    throw py::value_error("a material's program register must lie in [-1, " +
                          std::to_string(ShaderProgram::kMaxRegisters) + "), got " + std::to_string(r));
  return int16_t(r);
}

inline ShaderOutputs program_outputs(int program, int base_color, int metallic, int roughness, int emission,
                                    int normal = -1, int alpha = -1, int surface_normal = -1) {
  for (int r : {base_color, metallic, roughness, emission, normal, alpha, surface_normal})
    if (r < -1 || r >= ShaderProgram::kMaxRegisters)
      throw py::value_error("a material's program register must lie in [-1, " +
                            std::to_string(ShaderProgram::kMaxRegisters) + "), got " + std::to_string(r));
  ShaderOutputs o;
  o.program = program;
  o.base_color = int16_t(base_color);
  o.metallic = int16_t(metallic);
  o.roughness = int16_t(roughness);
  o.emission = int16_t(emission);
  o.normal = int16_t(normal);
  o.alpha = int16_t(alpha);
  o.surface_normal = int16_t(surface_normal);
  return o;
}

// The hit of each point run_shader_program runs a program at, beyond its UV: optional arrays
// (N, 3) of positions, shading normals, true normals and incoming directions, (N,) backfacing
// flags and (N, A, 3) attribute layers (layer a has the id a; the point's value at every corner).
struct ShaderHits {
  py::object positions, normals, true_normals, incoming, backfacing, attributes;
};

inline std::vector<float> hit_column(const py::object& values, const char* name, py::ssize_t n,
                                     std::initializer_list<py::ssize_t> shape) {
  if (values.is_none()) return {};
  const auto a = shaped_array<float>(values, name, shape);
  if (a.shape(0) != n)
    throw py::value_error(std::string(name) + " must have one row per UV, got " + shape_string(a));
  return std::vector<float>(a.data(), a.data() + a.size());
}

inline py::array_t<float> run_shader_program(const Scene& scene, int program, const py::object& uvs,
                                             float footprint, const ShaderHits& hits = {}) {
  if (program < 0 || size_t(program) >= scene.num_shader_programs())
    throw py::value_error("shader program " + std::to_string(program) + " but the scene has " +
                          std::to_string(scene.num_shader_programs()) + " programs");
  const auto a = shaped_array<float>(uvs, "uvs", {-1, 2});
  const py::ssize_t n = a.size() / 2;
  const std::vector<float> position = hit_column(hits.positions, "positions", n, {-1, 3});
  const std::vector<float> normal = hit_column(hits.normals, "normals", n, {-1, 3});
  const std::vector<float> true_normal = hit_column(hits.true_normals, "true_normals", n, {-1, 3});
  const std::vector<float> incoming = hit_column(hits.incoming, "incoming", n, {-1, 3});
  const std::vector<float> backfacing = hit_column(hits.backfacing, "backfacing", n, {-1});
  const std::vector<float> attributes = hit_column(hits.attributes, "attributes", n, {-1, -1, 3});
  const int layers = n > 0 && !attributes.empty() ? int(attributes.size() / (3 * size_t(n))) : 0;
  std::vector<int32_t> ids(static_cast<size_t>(layers));
  for (int i = 0; i < layers; ++i) ids[size_t(i)] = i;
  const int registers = scene.shader_program(uint32_t(program)).registers();
  py::array_t<float> out({n, py::ssize_t(registers), py::ssize_t(4)});
  float* dst = out.mutable_data();
  const float* src = a.data();
  auto vec3 = [](const std::vector<float>& v, py::ssize_t i, Vec3 fallback) {
    return v.empty() ? fallback : Vec3(v[3 * size_t(i)], v[3 * size_t(i) + 1], v[3 * size_t(i) + 2]);
  };
  {
    py::gil_scoped_release release;
    std::vector<glm::vec4> regs(static_cast<size_t>(registers), glm::vec4(0.0f));
    std::vector<Vec3> corners(3 * static_cast<size_t>(layers));
    for (py::ssize_t i = 0; i < n; ++i) {
      ShaderGlobals g{Vec2(src[2 * i], src[2 * i + 1]), footprint};
      g.position = vec3(position, i, g.position);
      g.normal = vec3(normal, i, g.normal);
      g.true_normal = vec3(true_normal, i, g.true_normal);
      g.incoming = vec3(incoming, i, g.incoming);
      g.backfacing = !backfacing.empty() && backfacing[size_t(i)] != 0.0f;
      if (layers > 0) {
        for (int c = 0; c < 3; ++c)
          for (int l = 0; l < layers; ++l) corners[size_t(c * layers + l)] = vec3(attributes, i * layers + l, Vec3(0.0f));
        g.corner_attributes = corners.data();
        g.attribute_ids = ids.data();
        g.num_attributes = layers;
        g.corner_weights = Vec3(1.0f, 0.0f, 0.0f);
      }
      scene.run_shader_program(uint32_t(program), g, regs.data());
      for (int r = 0; r < registers; ++r)
        for (int c = 0; c < 4; ++c) dst[(size_t(i) * registers + r) * 4 + c] = regs[size_t(r)][c];
    }
  }
  return out;
}

}  // namespace torrance::python
