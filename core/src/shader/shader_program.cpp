#include "torrance/shader/shader_program.h"

#include "torrance/shader/shader_bump.h"
#include "torrance/shader/shader_color.h"
#include "torrance/shader/shader_math.h"
// [family headers]
#include "torrance/shader/shader_convert.h"
#include "torrance/shader/shader_noise.h"
#include "torrance/shader/shader_noise4.h"
#include "torrance/shader/shader_gabor.h"
#include "torrance/shader/shader_voronoi.h"
#include "torrance/shader/shader_ies.h"
#include "torrance/shader/shader_voxel.h"
#include "torrance/shader/shader_image.h"
#include "torrance/shader/shader_sky.h"
#include "torrance/shader/shader_radial_tiling.h"
#include "torrance/shader/shader_textures.h"
#include "torrance/media/volume_grid.h"
#include "torrance/shader/shader_curves_info.h"
#include "torrance/shader/shader_geometry.h"
#include "torrance/shader/shader_bevel.h"
#include "torrance/shader/shader_raycast.h"
#include "torrance/shader/shader_vector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <cstring>
#include <stdexcept>
#include <string>

#include <xmmintrin.h>

namespace torrance {
namespace {

constexpr float kMaxValue = 1e30f;  // program values stay finite and well inside float's range

// Each component: NaN and infinities to 0, the rest clamped to [-kMaxValue, kMaxValue] (the sign
// of a zero kept), four at once, stored at `to`: run() does this to every instruction's output.
// A lane is finite where x - x is a number (0; NaN for an infinity or a NaN): no constants to load
// beyond the two bounds.
void store_finite(const OpValue& v, glm::vec4* to) {
  __m128 x;
  static_assert(sizeof x == sizeof v.lanes);
  std::memcpy(&x, &v.lanes, sizeof x);
  const __m128 clamped = _mm_min_ps(_mm_max_ps(x, _mm_set1_ps(-kMaxValue)), _mm_set1_ps(kMaxValue));
  const __m128 zero_if_finite = _mm_sub_ps(x, x);
  _mm_storeu_ps(&to->x, _mm_and_ps(clamped, _mm_cmpord_ps(zero_if_finite, zero_if_finite)));
}
glm::vec4 color(const Vec3& c, float w = 1.0f) { return glm::vec4(c, w); }
glm::vec4 value(float v) { return glm::vec4(v, 0.0f, 0.0f, 0.0f); }

// The core node families' ops (shader_math.h, shader_color.h); a register's kinds as the header says.
// Channel and Combine only move lanes of registers: run() does them in its loop (Step::kChannel,
// kCombine), their functions here for anything that calls an op through shader_op_info.
glm::vec4 channel_of(const ShaderInstruction& ins, const glm::vec4* regs) {
  return value((&regs[ins.in[0]].x)[ins.mode]);  // mode < 4 (checked at construction)
}
glm::vec4 combined(const ShaderInstruction& ins, const glm::vec4* regs) {
  return glm::vec4(regs[ins.in[0]].x, regs[ins.in[1]].x, regs[ins.in[2]].x, 1.0f);
}
OpValue channel(const ShaderOpContext& c) { return channel_of(c.ins, c.regs); }
OpValue combine(const ShaderOpContext& c) { return combined(c.ins, c.regs); }
OpValue math(const ShaderOpContext& c) {
  const float v = shader::math(shader::MathOp(c.ins.mode), c.value(0), c.value(1), c.value(2));
  return value((c.ins.flags & 1) ? std::clamp(v, 0.0f, 1.0f) : v);
}
OpValue vector_math(const ShaderOpContext& c) {
  Vec3 vector(0.0f);
  float scalar = 0.0f;
  shader::vector_math(shader::VectorMathOp(c.ins.mode), c.vector(0), c.vector(1), c.vector(2), c.value(3), &vector,
                      &scalar);
  return (c.ins.flags & 1) ? value(scalar) : glm::vec4(vector, 0.0f);
}
OpValue mix_color(const ShaderOpContext& c) {
  return color(shader::mix_color(shader::MixBlend(c.ins.mode), shader::mix_factor(c.value(0), c.ins.flags & 2),
                                 c.vector(1), c.vector(2), c.ins.flags & 1));
}
OpValue mix_float(const ShaderOpContext& c) {
  return value(shader::mix_float(shader::mix_factor(c.value(0), c.ins.flags & 2), c.value(1), c.value(2)));
}
OpValue mix_vector(const ShaderOpContext& c) {
  Vec3 factor = (c.ins.flags & 4) ? c.vector(0) : Vec3(c.value(0));
  if (c.ins.flags & 2) factor = glm::clamp(factor, Vec3(0.0f), Vec3(1.0f));
  return glm::vec4(shader::mix_vector(factor, c.vector(1), c.vector(2)), 0.0f);
}
OpValue color_model(const ShaderOpContext& c) {
  const Vec3 v = c.vector(0);
  switch (c.ins.mode) {
    case 0: return color(shader::rgb_to_hsv(v));
    case 1: return color(shader::hsv_to_rgb(v));
    case 2: return color(shader::rgb_to_hsl(v));
    default: return color(shader::hsl_to_rgb(v));
  }
}
OpValue invert(const ShaderOpContext& c) { return color(shader::invert(c.value(0), c.vector(1))); }
OpValue gamma(const ShaderOpContext& c) { return color(shader::gamma(c.vector(0), c.value(1))); }
OpValue bright_contrast(const ShaderOpContext& c) {
  return color(shader::bright_contrast(c.vector(0), c.value(1), c.value(2)));
}
OpValue hue_saturation(const ShaderOpContext& c) {
  return color(shader::hue_saturation_value(c.value(0), c.value(1), c.value(2), c.value(3), c.vector(4)));
}
OpValue luminance(const ShaderOpContext& c) { return value(shader::rgb_to_bw(c.vector(0))); }
OpValue average(const ShaderOpContext& c) { return value((c.in(0).x + c.in(0).y + c.in(0).z) / 3.0f); }
OpValue uv(const ShaderOpContext& c) { return glm::vec4(c.globals.uv, 0.0f, 0.0f); }

// The GlobalsRead flags of the globals an opcode reads beyond the hit's basics.
uint8_t globals_read_by(ShaderOpcode op) {
  switch (op) {
    case ShaderOpcode::Attribute: return kReadsAttributes;
    case ShaderOpcode::Tangent:
    case ShaderOpcode::NormalMap:
    case ShaderOpcode::VectorDisplacement: return kReadsTangent;
    case ShaderOpcode::Wireframe: return kReadsCorners;
    case ShaderOpcode::CurvesInfo: return kReadsTangent;  // Tangent Normal
    case ShaderOpcode::Bevel: return kReadsSampleShift;
    default: return 0;
  }
}

}  // namespace

ShaderOpInfo shader_op_info(ShaderOpcode op) {
  switch (op) {
    case ShaderOpcode::TexCoordUV: return {0, 1, false, uv};
    case ShaderOpcode::Image: return {1, 4, false, nullptr};
    case ShaderOpcode::Channel: return {1, 4, false, channel, true};
    case ShaderOpcode::Combine: return {3, 1, false, combine, true};
    case ShaderOpcode::Math: return {3, shader::kMathOpCount, false, math};
    case ShaderOpcode::VectorMath: return {4, shader::kVectorMathOpCount, false, vector_math};
    case ShaderOpcode::MixColor: return {3, shader::kMixBlendCount, false, mix_color};
    case ShaderOpcode::MixFloat: return {3, 1, false, mix_float};
    case ShaderOpcode::MixVector: return {3, 1, false, mix_vector};
    case ShaderOpcode::ColorModel: return {1, 4, false, color_model};
    case ShaderOpcode::Invert: return {2, 1, false, invert};
    case ShaderOpcode::Gamma: return {2, 1, false, gamma};
    case ShaderOpcode::BrightContrast: return {3, 1, false, bright_contrast};
    case ShaderOpcode::HueSaturation: return {5, 1, false, hue_saturation};
    case ShaderOpcode::Luminance: return {1, 1, false, luminance};
    case ShaderOpcode::Average: return {1, 1, false, average};
    case ShaderOpcode::Bump: return {7, 1, false, shader::bump_op};
    case ShaderOpcode::NormalMap: return {6, shader::kNormalMapModes, false, shader::normal_map_op};
    case ShaderOpcode::Displacement: return {8, 2, false, shader::displacement_op};
    case ShaderOpcode::VectorDisplacement: return {7, 3, false, shader::vector_displacement_op};
    // The node families' ops (a line each, in opcode order):
    // [noise ops]
    case ShaderOpcode::Noise: return {6, shader::kNoiseModes, false, shader::noise_op};
    case ShaderOpcode::WhiteNoise: return {2, shader::kWhiteNoiseModes, false, shader::white_noise_op};
    case ShaderOpcode::Musgrave: return {8, shader::kMusgraveModes, false, shader::musgrave_op};
    case ShaderOpcode::Wave: return {7, shader::kWaveModes, false, shader::wave_op};
    case ShaderOpcode::NoiseV4: return {9, shader::kNoise4Modes, false, shader::noise4_op};
    case ShaderOpcode::TexGabor: return {6, shader::kGaborModes, false, shader::gabor_op};
    // [voronoi ops]
    case ShaderOpcode::Voronoi: return {6, shader::kVoronoiModes, false, shader::voronoi_op};
    case ShaderOpcode::VoronoiV4: return {9, shader::kVoronoiModes, false, shader::voronoi4_op};
    // [texture ops]
    case ShaderOpcode::TexChecker: return {4, 1, false, shader::checker_op};
    case ShaderOpcode::TexGradient: return {1, shader::kGradientTypeCount, false, shader::gradient_op};
    case ShaderOpcode::TexBrick: return {11, 1, false, shader::brick_op};
    case ShaderOpcode::TexMagic: return {3, shader::kMagicDepths, false, shader::magic_op};
    case ShaderOpcode::ImageProjection:
      return {7, shader::kImageProjectionModes, false, shader::image_projection_op};
    case ShaderOpcode::TexSky: return {1, shader::kSkyModels, true, shader::sky_op};
    case ShaderOpcode::RadialTiling: return {3, shader::kRadialTilingModes, false, shader::radial_tiling_op};
    case ShaderOpcode::TexIES: return {2, shader::kIesLookups, true, shader::ies_op};
    case ShaderOpcode::TexPointDensity:
      return {1, shader::kVoxelInterpolations, true, shader::point_density_op};
    // [converter ops]
    case ShaderOpcode::ColorRamp: return {1, 1, true, shader::color_ramp_op};
    case ShaderOpcode::RGBCurves: return {2, 1, true, shader::rgb_curves_op};
    case ShaderOpcode::VectorCurves: return {2, 1, true, shader::vector_curves_op};
    case ShaderOpcode::FloatCurve: return {2, 1, true, shader::float_curve_op};
    case ShaderOpcode::MapRange: return {6, shader::kMapRangeModeCount, false, shader::map_range_op};
    case ShaderOpcode::VectorMapRange: return {6, shader::kMapRangeModeCount, false, shader::vector_map_range_op};
    case ShaderOpcode::Clamp: return {3, 2, false, shader::clamp_op};
    case ShaderOpcode::Blackbody: return {1, 1, false, shader::blackbody_op};
    case ShaderOpcode::Wavelength: return {1, 1, false, shader::wavelength_op};
    // [geometry ops]
    case ShaderOpcode::Geometry: return {0, 5, false, shader::geometry_op};
    case ShaderOpcode::Reflection: return {0, 1, false, shader::reflection_op};
    case ShaderOpcode::Fresnel: return {2, 1, false, shader::fresnel_op};
    case ShaderOpcode::LayerWeight: return {2, 2, false, shader::layer_weight_op};
    case ShaderOpcode::Attribute: return {0, 1, false, shader::attribute_op};
    case ShaderOpcode::Tangent: return {6, shader::kTangentModes, false, shader::tangent_op};
    case ShaderOpcode::Mapping: return {4, 4, false, shader::mapping_op};
    case ShaderOpcode::VectorRotate: return {5, 5, false, shader::vector_rotate_op};
    case ShaderOpcode::LightPath: return {0, shader::kLightPathModes, false, shader::light_path_op};
    case ShaderOpcode::LightFalloff: return {2, shader::kLightFalloffModes, false, shader::light_falloff_op};
    case ShaderOpcode::Wireframe: return {1, 2, false, shader::wireframe_op};
    case ShaderOpcode::VolumeGrid: return {1, 1, false, volume_grid_op};
    case ShaderOpcode::CurvesInfo: return {0, shader::kCurvesInfoModes, false, shader::curves_info_op};
    case ShaderOpcode::PointInfo: return {0, shader::kPointInfoModes, false, shader::point_info_op};
    case ShaderOpcode::AmbientOcclusion: return {4, 2, false, shader::ambient_occlusion_op};
    case ShaderOpcode::Bevel: return {3, 1, false, shader::bevel_op};
    case ShaderOpcode::Raycast: return {4, 3, false, shader::raycast_op};
    case ShaderOpcode::CameraTransform: return {4, shader::kCameraTransformModes, false, shader::camera_transform_op};
    case ShaderOpcode::VectorTransform: return {11, shader::kVectorTransformModes, false, shader::vector_transform_op};
    default: break;
  }
  return {0, 0, false, nullptr};
}

void ShaderProgram::check_bump_filter_width(const ShaderInstruction& ins, const std::string& where, int earlier) {
  const int r = ins.in[6];
  if (r < 0 || r >= int(constants_.size()))
    throw std::invalid_argument(where + ": a Bump's Filter Width (input 6) must be a constant");
  const float width = constants_[size_t(r)].x;
  if (!(width >= 0.0f)) throw std::invalid_argument(where + ": a Bump's Filter Width must be 0 or more");
  if (earlier > 0 && width != bump_filter_width_)
    throw std::invalid_argument(where + ": a Bump's Filter Width differs from an earlier Bump's (one per program)");
  bump_filter_width_ = width;
}

ShaderProgram::ShaderProgram(std::vector<glm::vec4> constants, std::vector<ShaderInstruction> code, int registers,
                             size_t num_textures, std::vector<float> data)
    : constants_(std::move(constants)), code_(std::move(code)), data_(std::move(data)), registers_(registers) {
  if (registers_ < 1 || registers_ > kMaxRegisters)
    throw std::invalid_argument("a shader program has 1 to " + std::to_string(kMaxRegisters) + " registers, got " +
                                std::to_string(registers_));
  if (int(constants_.size()) > registers_)
    throw std::invalid_argument("a shader program's constants (" + std::to_string(constants_.size()) +
                                ") exceed its registers (" + std::to_string(registers_) + ")");
  for (const glm::vec4& c : constants_)
    if (!std::isfinite(c.x) || !std::isfinite(c.y) || !std::isfinite(c.z) || !std::isfinite(c.w))
      throw std::invalid_argument("a shader program's constants must be finite");
  for (float d : data_)
    if (!std::isfinite(d)) throw std::invalid_argument("a shader program's data must be finite");
  std::vector<bool> written(size_t(registers_), false);
  for (size_t r = 0; r < constants_.size(); ++r) written[r] = true;
  int bump_filter_widths = 0;
  for (size_t i = 0; i < code_.size(); ++i) {
    const ShaderInstruction& ins = code_[i];
    const std::string where = "shader instruction " + std::to_string(i);
    const ShaderOpInfo s = shader_op_info(ins.op);
    if (s.modes == 0 || int(ins.op) >= kShaderOpcodes)  // run() looks opcodes up in a table of kShaderOpcodes
      throw std::invalid_argument(where + ": unknown opcode " + std::to_string(int(ins.op)));
    if (ins.offset > 2)
      throw std::invalid_argument(where + ": offset " + std::to_string(int(ins.offset)) + " is not 0, 1 or 2");
    offsets_ = offsets_ || ins.offset != 0;
    differentials_ = differentials_ || ins.offset != 0 || ins.op == ShaderOpcode::Bump;
    differentials_ = differentials_ || (ins.op == ShaderOpcode::Wireframe && ins.mode == 1);  // Pixel Size
    globals_read_ |= globals_read_by(ins.op);
    local_queries_ = local_queries_ || ins.op == ShaderOpcode::Bevel ||
                     (ins.op == ShaderOpcode::AmbientOcclusion && (ins.flags & shader::kAmbientOcclusionOnlyLocal)) ||
                     (ins.op == ShaderOpcode::Raycast && (ins.flags & shader::kRaycastOnlyLocal));
    if (ins.mode >= s.modes)
      throw std::invalid_argument(where + ": mode " + std::to_string(int(ins.mode)) + " out of range [0, " +
                                  std::to_string(s.modes) + ")");
    for (int k = 0; k < s.inputs; ++k) {
      const int r = ins.in[size_t(k)];
      if (r < 0 || r >= registers_ || !written[size_t(r)])
        throw std::invalid_argument(where + ": input " + std::to_string(k) + " reads register " + std::to_string(r) +
                                    ", which is not written before it");
    }
    if (ins.op == ShaderOpcode::Bump) check_bump_filter_width(ins, where, bump_filter_widths++);
    if (ins.out < int(constants_.size()) || ins.out >= registers_)
      throw std::invalid_argument(where + ": output register " + std::to_string(ins.out) + " outside [" +
                                  std::to_string(constants_.size()) + ", " + std::to_string(registers_) + ")");
    if (ins.op == ShaderOpcode::Image && (ins.resource < 0 || size_t(ins.resource) >= num_textures))
      throw std::invalid_argument(where + ": texture " + std::to_string(ins.resource) + " but the scene has " +
                                  std::to_string(num_textures) + " textures");
    if (s.data && (ins.resource < 0 || size_t(ins.resource) >= data_.size() || !(data_[size_t(ins.resource)] >= 0.0f) ||
                   double(ins.resource) + 1.0 + double(data_[size_t(ins.resource)]) > double(data_.size())))
      throw std::invalid_argument(where + ": its table at " + std::to_string(ins.resource) +
                                  " does not lie within the program's " + std::to_string(data_.size()) + " data");
    written[size_t(ins.out)] = true;
    const Step::Kind kind = ins.op == ShaderOpcode::Channel   ? Step::kChannel
                            : ins.op == ShaderOpcode::Combine ? Step::kCombine
                                                              : Step::kCall;
    steps_.push_back(
        {s.run, s.data ? ins.resource + 1 : 0, s.data ? int32_t(data_[size_t(ins.resource)]) : 0, !s.copies, kind});
  }
  written_ = std::move(written);
  if (differentials_) globals_read_ |= kReadsDifferentials;
  for (size_t i = 0; i + 3 < steps_.size(); ++i)
    if (steps_[i].kind == Step::kChannel && steps_[i + 1].kind == Step::kChannel &&
        steps_[i + 2].kind == Step::kChannel && steps_[i + 3].kind == Step::kCombine)
      steps_[i].kind = Step::kSeparateCombine;
}

void ShaderProgram::check_grids(size_t num_grids) const {
  for (size_t i = 0; i < code_.size(); ++i)
    if (code_[i].op == ShaderOpcode::VolumeGrid && (code_[i].resource < 0 || size_t(code_[i].resource) >= num_grids))
      throw std::invalid_argument("shader instruction " + std::to_string(i) + ": volume grid " +
                                  std::to_string(code_[i].resource) + " but the scene has " +
                                  std::to_string(num_grids) + " grids");
}

namespace {

// Runs the code (steps: ShaderProgram::Step of each instruction); at[k] holds the globals an
// instruction of offset k reads.
void run_code(const std::vector<ShaderInstruction>& code, const std::vector<ShaderProgram::Step>& steps,
              const std::vector<float>& data, const ShaderGlobals* const at[3],
              const std::vector<std::shared_ptr<const Texture>>& textures, glm::vec4* regs) {
  using Step = ShaderProgram::Step;
  // Plain pointers, read once: the stores to regs could otherwise alias the vectors' own.
  const ShaderInstruction* ins = code.data();
  const ShaderInstruction* const end = ins + code.size();
  const Step* s = steps.data();
  const float* const tables = data.data();
  while (ins != end) {
    if (s->kind != Step::kCall) {  // the moves, inline
      if (s->kind == Step::kSeparateCombine) {
        regs[ins[0].out] = channel_of(ins[0], regs);
        regs[ins[1].out] = channel_of(ins[1], regs);
        regs[ins[2].out] = channel_of(ins[2], regs);
        regs[ins[3].out] = combined(ins[3], regs);
        ins += 4, s += 4;
      } else {
        regs[ins->out] = s->kind == Step::kChannel ? channel_of(*ins, regs) : combined(*ins, regs);
        ++ins, ++s;
      }
      continue;
    }
    const ShaderGlobals& g = *at[ins->offset];
    const ShaderOpContext c{*ins, regs, g, tables + s->table, s->table_size};
    const OpValue out = s->run ? s->run(c)
                               : OpValue(textures[size_t(ins->resource)]->lookup(Vec2(c.in(0)), g.footprint,
                                                                                 Extension(ins->mode)));
    if (s->clamp)
      store_finite(out, &regs[ins->out]);
    else
      std::memcpy(&regs[ins->out], &out.lanes, sizeof(glm::vec4));
    ++ins, ++s;
  }
}

}  // namespace

void ShaderProgram::run(const ShaderGlobals& g, const std::vector<std::shared_ptr<const Texture>>& textures,
                        glm::vec4* regs) const {
  std::copy(constants_.begin(), constants_.end(), regs);
  // The globals at the offset hits are made only for programs that read them (a Bump's
  // heights): ShaderGlobals is large enough that making two at every run costs a noticeable share.
  if (offsets_) {
    const ShaderGlobals dx = g.offset(1, bump_filter_width_), dy = g.offset(2, bump_filter_width_);
    const ShaderGlobals* const at[3] = {&g, &dx, &dy};
    run_code(code_, steps_, data_, at, textures, regs);
  } else {
    const ShaderGlobals* const at[3] = {&g, &g, &g};
    run_code(code_, steps_, data_, at, textures, regs);
  }
}

}  // namespace torrance
