#include "torrance/bsdfs/mixture.h"

#include "torrance/shader/shader_textures.h"

#include <stdexcept>
#include <string>

namespace torrance {

void check_mixture(const Mixture& mixture, size_t num_materials, size_t num_textures) {
  const size_t n = mixture.components.size();
  if (n < 1 || n > size_t(kMaxMixtureComponents))
    throw std::invalid_argument("a mixture needs 1 to " + std::to_string(kMaxMixtureComponents) + " closures, got " +
                                std::to_string(n));
  if (mixture.factors.size() > size_t(kMaxMixFactors))
    throw std::invalid_argument("a mixture has at most " + std::to_string(kMaxMixFactors) + " mix factors, got " +
                                std::to_string(mixture.factors.size()));
  for (const MixFactor& f : mixture.factors) {
    if (!std::isfinite(f.value) || !std::isfinite(f.checker_scale) || !std::isfinite(f.checker_color1) ||
        !std::isfinite(f.checker_color2))
      throw std::invalid_argument("mix factor values must be finite (no NaN or Inf)");
    if (f.kind == MixFactor::Kind::Image && (f.texture < 0 || size_t(f.texture) >= num_textures))
      throw std::invalid_argument("mix factor uses texture " + std::to_string(f.texture) + " but the scene has " +
                                  std::to_string(num_textures) + " textures");
  }
  const int num_factors = int(mixture.factors.size());
  for (const MixtureComponent& c : mixture.components) {
    if (c.material >= num_materials)
      throw std::invalid_argument("mixture closure uses material " + std::to_string(c.material) +
                                  " but the scene has " + std::to_string(num_materials) + " materials");
    if (c.terms.size() > size_t(kMaxMixFactors))
      throw std::invalid_argument("a mixture closure has at most " + std::to_string(kMaxMixFactors) + " weight terms");
    for (int t : c.terms)
      if (t >= num_factors || -t - 1 >= num_factors)
        throw std::invalid_argument("mixture weight term " + std::to_string(t) +
                                    " names no mix factor (the mixture has " + std::to_string(num_factors) + ")");
  }
}

MixtureWeights mixture_weights(const Mixture& mixture, const std::vector<std::shared_ptr<const Texture>>& textures,
                               const Vec2& uv, float footprint, const glm::vec4* registers) {
  std::array<float, kMaxMixFactors> fac{};
  for (size_t i = 0; i < mixture.factors.size(); ++i) {
    const MixFactor& f = mixture.factors[i];
    float v = f.value;
    if (f.kind == MixFactor::Kind::Image) {
      v = blender_luminance(Vec3(textures[f.texture]->lookup(uv, footprint)));
    } else if (f.kind == MixFactor::Kind::Program) {
      v = registers ? registers[f.register_index].x : 0.0f;
    } else if (f.kind == MixFactor::Kind::Checker) {
      v = shader::checker(Vec3(uv.x, uv.y, 0.0f) * f.checker_scale) > 0.5f ? f.checker_color1 : f.checker_color2;
    }
    fac[i] = std::isfinite(v) ? clamp01(v) : 0.0f;  // Cycles clamps the Mix Shader's Fac
  }
  MixtureWeights w;
  w.count = int(mixture.components.size());
  for (int c = 0; c < w.count; ++c) {
    float weight = 1.0f;
    for (int t : mixture.components[c].terms) weight *= t >= 0 ? fac[t] : 1.0f - fac[-t - 1];
    w.weight[c] = weight;
  }
  return w;
}

float mixture_opacity(const Mixture& mixture, const MixtureWeights& w) {
  float through = 0.0f;
  for (int c = 0; c < w.count; ++c)
    if (passes_rays(mixture.components[size_t(c)].type)) through += w.weight[c];
  return clamp01(1.0f - through);
}

void weights_when_opaque(const Mixture& mixture, MixtureWeights& w) {
  if (!mixture.passes()) return;
  const float opacity = mixture_opacity(mixture, w);
  for (int c = 0; c < w.count; ++c) {
    const bool through = passes_rays(mixture.components[size_t(c)].type);
    w.weight[c] = through || !(opacity > 0.0f) ? 0.0f : w.weight[c] / opacity;
  }
}

}  // namespace torrance
