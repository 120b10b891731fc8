// The hair closures of a mixture at a hit (MixtureBsdf's shade_material): the Principled Hair
// BSDF's parameters for Chiang's and Huang's models, with their per-strand randomness, and the
// Hair BSDF node's closure.
#include "hair/hair_closures.h"

namespace torrance {
namespace {

// The Principled Hair's per-strand randomness (HairRandomness) of material m.
HairRandomness hair_randomness(const Material& m) {
  HairRandomness h;
  h.coloring = m.hair_coloring == 1   ? HairRandomness::Coloring::Melanin
               : m.hair_coloring == 2 ? HairRandomness::Coloring::DirectColor
                                      : HairRandomness::Coloring::Absorption;
  h.sigma = m.base_color;
  h.melanin = m.hair_melanin;
  h.melanin_redness = m.hair_melanin_redness;
  h.color = m.hair_color;
  h.random_roughness = m.hair_random_roughness;
  h.random_color = m.hair_random_color;
  return h;
}

// The strand's random at a hit (Cycles: the curve's Random attribute, else the node's input).
float strand_random(const Material& m, const ShaderGlobals& g) {
  return g.on_curve ? g.primitive_info.w : m.hair_random;
}

}  // namespace

PrincipledHairParams principled_hair_params(const Material& m, const ShaderGlobals& g) {
  PrincipledHairParams p;
  p.sigma = m.base_color;
  p.roughness = m.roughness;
  p.radial_roughness = m.transmission_roughness;
  p.coat = m.coat_weight;
  p.ior = m.ior;
  p.offset = m.hair_offset;
  if (const HairRandomness h = hair_randomness(m); h.varies())
    p.sigma = h.sigma_at(strand_random(m, g), p.roughness, p.radial_roughness);
  return p;
}

HuangHairParams huang_hair_params(const Material& m, const ShaderGlobals& g) {
  HuangHairParams p;
  p.sigma = m.base_color;
  p.roughness = m.roughness;
  if (const HairRandomness h = hair_randomness(m); h.varies()) {
    float radial = m.roughness;  // Huang's colour fit takes its Roughness
    p.sigma = h.sigma_at(strand_random(m, g), p.roughness, radial);
  }
  p.ior = m.ior;
  p.offset = m.hair_offset;
  p.aspect_ratio = m.hair_aspect_ratio;
  p.lobe_weights = m.hair_lobe_weights;
  return p;
}

// The Hair BSDF node's closure at a hit, its strand's direction as Cycles' svm closure node
// takes it: a linked Tangent (a world direction); else on a curve the strand's (dPdu), on a
// triangle its second edge (dPdv: corner 2 - corner 0), the Offset then 0.
HairBsdf hair_bsdf(const Material& m, bool transmission, const ShaderGlobals& g) {
  float offset = m.hair_offset;
  Vec3 tangent = m.tangent;
  if (!(glm::length(tangent) > 0.0f)) {
    if (g.on_curve) {
      tangent = g.tangent;
    } else {
      tangent = g.corners[2] - g.corners[0];
      offset = 0.0f;
    }
  }
  return HairBsdf(m.base_color, transmission, m.roughness, m.transmission_roughness, offset, tangent);
}

bool hair_may_pass(const Scene& scene, const Mixture& mixture) {
  for (const MixtureComponent& c : mixture.components)
    if (c.type == ClosureType::PrincipledHairHuang && scene.material(c.material).hair_aspect_ratio != 1.0f) return true;
  return false;
}

}  // namespace torrance
