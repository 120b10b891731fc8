// The closures Cycles 3.4 makes of Torrance's materials (svm/closure.h), as the denoising
// features weigh them, and the features' step at a surface (film/denoising_passes.h).
#include "film/denoising_features.h"

#include "torrance/bsdfs/ggx_tables.h"
#include "torrance/bsdfs/metallic_bsdf.h"
#include "torrance/bsdfs/principled.h"
#include "torrance/bsdfs/principled_v2.h"
#include "torrance/util/smoothstep.h"

#include <algorithm>
#include <cmath>

namespace torrance {

namespace {

constexpr float kWeightCutoff = 1e-5f;  // CLOSURE_WEIGHT_CUTOFF
constexpr float kNotMicrofacet = 1.0f;  // bsdf_get_specular_roughness_squared of other closures

float mean(const Vec3& c) { return (c.x + c.y + c.z) / 3.0f; }

// A GGX (or Beckmann) closure's alpha_x alpha_y for the node's Roughness r (alpha = r^2).
float microfacet_roughness_squared(float r) {
  const float alpha = r * r;
  return alpha * alpha;
}

// Cycles' mean Fresnel colour of a *_FRESNEL microfacet closure (bsdf_microfacet_fresnel_color):
// its colour at the view, for the IOR `ior`.
Vec3 fresnel_color(float cos_no, float ior, const Vec3& cspec0) {
  return fresnel_interpolated(cspec0, cos_no, ior, fresnel_dielectric(1.0f, ior));
}

// The colour normalised to luminance 1 (its hue and saturation), white for black.
Vec3 tint_of(const Vec3& c, float lum) { return lum > 0.0f ? c / lum : Vec3(1.0f); }

}  // namespace

void DenoisingClosures::add_sampled(float sample_weight, bool transmits) {
  if (!(sample_weight >= kWeightCutoff) || count >= kMaxClosures) return;
  sample_weights[size_t(count)] = sample_weight;
  transmitting[size_t(count++)] = uint8_t(transmits);
}

void DenoisingClosures::add(const Vec3& albedo, float sample_weight, float roughness_squared, bool transmits,
                            bool sampled_alone) {
  if (!(sample_weight >= kWeightCutoff)) return;
  if (sampled_alone) add_sampled(sample_weight, transmits);
  sum_weight += sample_weight;
  const float diffuse_like = smooth_weights ? smooth_step(0.0f, 0.15f, std::sqrt(roughness_squared))
                                            : float(roughness_squared > 0.075f * 0.075f);
  diffuse_albedo += albedo * diffuse_like;
  specular_albedo += albedo * (1.0f - diffuse_like);
  sum_nonspecular += sample_weight * diffuse_like;
}

float DenoisingClosures::feature_weight() const {
  if (smooth_weights) return sum_weight > 0.0f ? smooth_step(0.0f, 0.5f, sum_nonspecular / sum_weight) : 0.0f;
  return sum_weight == 0.0f || sum_nonspecular * 4.0f > sum_weight ? 1.0f : 0.0f;
}

float DenoisingClosures::defensive_ratio(bool transmitted) const {
  if (cycles4_closures || count <= 1 || !(sum_weight > 0.0f)) return 1.0f;
  // The path stayed on the surface: of its closures but the Transparent one (whose sample weight
  // is in sum_weight, so in Cycles' floor, not in the side's plain probability).
  float plain = 0.0f, defended = 0.0f, defended_sum = 0.0f;
  for (int i = 0; i < count; ++i) {
    const float w = sample_weights[size_t(i)], d = std::max(w, 0.125f * sum_weight);
    defended_sum += d;
    if (bool(transmitting[size_t(i)]) == transmitted) {
      plain += w;
      defended += d;
    }
  }
  return plain > 0.0f ? (defended / defended_sum) / (plain / (sum_weight - transparent_weight)) : 1.0f;
}

void DenoisingClosures::add_transparent(float opacity, const Vec3& through) {
  diffuse_albedo *= opacity;
  specular_albedo *= opacity;
  sum_weight *= opacity;
  sum_nonspecular *= opacity;
  for (int i = 0; i < count; ++i) sample_weights[size_t(i)] *= opacity;
  const float w = std::abs(mean(through));
  if (!(w >= kWeightCutoff)) return;
  transparent_albedo = through;
  transparent_weight = w;
  if (smooth_weights) return;  // 5.3: outside the decision, carried on whole (DenoisingFeatures::surface)
  specular_albedo += through;  // 3.x/4.x: a singular closure
  sum_weight += w;
}

float DenoisingClosures::transparent_probability(bool defended) const {
  if (!(transparent_weight > 0.0f)) return 0.0f;
  float others = 0.0f;
  for (int i = 0; i < count; ++i) others += sample_weights[size_t(i)];
  if (!defended) return transparent_weight / (transparent_weight + others);
  const float floor = 0.125f * (transparent_weight + others);
  float defended_others = 0.0f;
  for (int i = 0; i < count; ++i) defended_others += std::max(sample_weights[size_t(i)], floor);
  const float t = std::max(transparent_weight, floor);
  return t / (t + defended_others);
}

void DenoisingClosures::add_glass(const Vec3& reflect, const Vec3& refract, float reflect_r2, float refract_r2) {
  add(reflect, std::abs(mean(reflect)), reflect_r2, false, !cycles4_closures);
  add(refract, std::abs(mean(refract)), refract_r2, true, !cycles4_closures);
  if (cycles4_closures) add_sampled(std::abs(mean(reflect + refract)), false);
}

void DenoisingClosures::add_principled_v2(const Material& m, float w, float cos_no, bool backfacing) {
  const float c = std::clamp(std::abs(cos_no), 0.0f, 1.0f);  // Cycles' N faces the viewer
  const PrincipledV2Bsdf bsdf(m);
  const PrincipledV2Bsdf::ClosureAlbedos a = bsdf.closure_albedos(c);
  const float r2 = sqr(bsdf.alpha());
  add(w * a.sheen, w * mean(a.sheen), kNotMicrofacet);
  add(w * a.coat, w * mean(a.coat), sqr(bsdf.coat_alpha()));
  add(w * a.metal, w * mean(a.metal), r2);
  const float metallic = std::clamp(m.metallic, 0.0f, 1.0f);
  const float glass = std::clamp(m.transmission, 0.0f, 1.0f) * (1.0f - metallic);
  if (glass > kWeightCutoff) {  // one GGX glass closure, f0 = F0(ior) x Specular Tint
    const float eta = std::max(m.ior, 1e-5f), etap = backfacing ? 1.0f / eta : eta;
    const Vec3 f0 = glm::clamp(ggx_tables::f0_from_ior(etap) * glm::max(m.specular_tint_color, Vec3(0.0f)),
                               Vec3(0.0f), Vec3(1.0f));
    const Vec3 weight = w * glass * a.layers;
    const Vec3 reflect = glm::mix(f0, Vec3(1.0f), ggx_tables::dielectric_fresnel_mix(bsdf.roughness(), c, etap));
    // Cycles 4.x: the refraction's share by the smooth Fresnel; 5.3: by the table's, the rest of
    // the reflection (bsdf_microfacet_estimate_albedo: a white glass's albedo 1 at every angle).
    const Vec3 smooth = smooth_weights ? reflect
                                       : glm::mix(f0, Vec3(1.0f), ggx_tables::dielectric_fresnel_factor(c, etap));
    const Vec3 refract = (Vec3(1.0f) - smooth) * glm::sqrt(glm::clamp(m.base_color, Vec3(0.0f), Vec3(1.0f)));
    add_glass(weight * reflect, weight * refract, r2, r2);
  }
  add(w * a.dielectric, w * mean(a.dielectric), r2);
  add(w * a.diffuse, w * mean(a.diffuse), kNotMicrofacet);
}

void DenoisingClosures::add_material(const Material& m, float w, float cos_no, bool backfacing) {
  if (cycles4_closures && !m.glass_node) {
    add_principled_v2(m, w, cos_no, backfacing);
    return;
  }
  const Vec3 base = glm::max(m.base_color, Vec3(0.0f));
  const float roughness = std::clamp(m.roughness, 0.0f, 1.0f);
  const float eta = std::max(m.ior, 1e-5f);
  const float ior = backfacing ? 1.0f / eta : eta;
  const float fresnel = fresnel_dielectric(cos_no, ior);
  if (m.glass_node) {  // the Glass BSDF: both closures of its colour, untinted by Fresnel colour
    const Vec3 weight = w * base;
    const float r2 = microfacet_roughness_squared(roughness);
    add_glass(weight * fresnel, weight * std::max(1e-4f, 1.0f - fresnel), r2, r2);
    return;
  }
  // The Principled BSDF, v1's closures (Cycles 3.x).
  const float metallic = std::clamp(m.metallic, 0.0f, 1.0f);
  const float transmission = std::clamp(m.transmission, 0.0f, 1.0f);
  const float diffuse_weight = (1.0f - metallic) * (1.0f - transmission);
  const float glass_weight = transmission * (1.0f - metallic);
  const float specular_weight = 1.0f - glass_weight;
  if (diffuse_weight > kWeightCutoff) {
    const Vec3 diffuse = w * base * diffuse_weight;
    add(diffuse, mean(diffuse), kNotMicrofacet);
    if (m.sheen_weight > kWeightCutoff) {  // its albedo: the mean of Schlick's term x cos
      const Vec3 tint = tint_of(base, luminance(base));
      const Vec3 weight = w * m.sheen_weight * diffuse_weight * (Vec3(1.0f - m.sheen_tint) + tint * m.sheen_tint);
      const float c = std::clamp(std::abs(cos_no), 0.0f, 1.0f);
      const float schlick = std::pow(1.0f - c, 5.0f);
      const float average = schlick * c;
      add(weight * average, mean(weight) * average, kNotMicrofacet);
    }
  }
  if (specular_weight > kWeightCutoff && (m.specular > kWeightCutoff || metallic > kWeightCutoff)) {
    const float specular = std::max(m.specular, 0.0f);
    const float spec_ior = 2.0f / (1.0f - std::sqrt(std::min(0.08f * specular, 0.99f))) - 1.0f;
    const Vec3 tint = tint_of(base, 0.3f * base.x + 0.6f * base.y + 0.1f * base.z);
    const Vec3 tinted = Vec3(1.0f - m.specular_tint) + tint * m.specular_tint;
    const Vec3 cspec0 = specular * 0.08f * tinted * (1.0f - metallic) + base * metallic;
    const Vec3 f = fresnel_color(cos_no, spec_ior, cspec0);
    const float weight = w * specular_weight;
    add(weight * f, weight * mean(f), microfacet_roughness_squared(roughness));
  }
  if (glass_weight > kWeightCutoff) {  // single-scatter GGX glass (3.4's GGX distribution)
    const Vec3 cspec0 = base * m.specular_tint + Vec3(1.0f - m.specular_tint);
    const Vec3 f = fresnel_color(cos_no, ior, cspec0);
    const float reflect = w * glass_weight * fresnel;
    const float refract_roughness = 1.0f - (1.0f - roughness) * (1.0f - std::clamp(m.transmission_roughness, 0.0f, 1.0f));
    const Vec3 refract = w * glass_weight * std::max(1e-4f, 1.0f - fresnel) * base;
    add_glass(reflect * f, refract, microfacet_roughness_squared(roughness),
              microfacet_roughness_squared(refract_roughness));
  }
  if (m.coat_weight > kWeightCutoff) {  // the clearcoat: F0 0.04, IOR 1.5, a quarter of its weight
    const Vec3 f = fresnel_color(cos_no, 1.5f, Vec3(0.04f)) * (0.25f * m.coat_weight);
    add(w * f, w * mean(f), microfacet_roughness_squared(std::clamp(m.coat_roughness, 0.0f, 1.0f)));
  }
}

void DenoisingClosures::add_closures(const ClosureList& list, float cos_no, bool backfacing) {
  for (int k = 0; k < list.count; ++k) {
    const ClosureList::Entry& e = list.entries[size_t(k)];
    const Material& m = e.material;
    const Vec3 weight = e.weight * glm::max(m.base_color, Vec3(0.0f));
    const float r2 = microfacet_roughness_squared(std::clamp(m.roughness, 0.0f, 1.0f));
    switch (e.type) {
      case ClosureType::Principled: add_material(m, e.weight, cos_no, backfacing); break;
      case ClosureType::Glossy:
      case ClosureType::GlossyMultiscatterV1: add(weight, mean(weight), r2); break;
      case ClosureType::Refraction: add(weight, mean(weight), r2, true); break;
      case ClosureType::MetallicF82:
      case ClosureType::MetallicConductor: {  // Cycles' albedo of a Fresnel closure: its F at wo
        const bool conductor = e.type == ClosureType::MetallicConductor;
        const MetallicBsdf metal(conductor, conductor ? m.specular_tint_color : m.base_color,
                                 conductor ? m.sheen_tint_color : m.specular_tint_color, m.roughness);
        const Vec3 f = e.weight * metal.fresnel(std::abs(cos_no));
        add(f, mean(f), r2);
        break;
      }
      case ClosureType::Diffuse:
      case ClosureType::DiffuseEnergyPreserving:
      case ClosureType::Subsurface:  // Cycles' BSSRDF counts as diffuse for the denoising albedo
      case ClosureType::Velvet:
      case ClosureType::Sheen:
      case ClosureType::ToonDiffuse:
      case ClosureType::ToonGlossy:
      case ClosureType::ToonDiffuseCycles4:
      case ClosureType::ToonGlossyCycles4: add(weight, mean(weight), kNotMicrofacet); break;
      case ClosureType::Translucent: add(weight, mean(weight), kNotMicrofacet, true); break;
      case ClosureType::PrincipledHair:
      case ClosureType::PrincipledHairHuang: add(weight, mean(weight), kNotMicrofacet, true); break;
      case ClosureType::HairReflection: add(weight, mean(weight), kNotMicrofacet); break;
      case ClosureType::HairTransmission: add(weight, mean(weight), kNotMicrofacet, true); break;
      case ClosureType::Emission:
      case ClosureType::Transparent:
      case ClosureType::RayPortal:
      case ClosureType::Holdout: break;  // no BSDF (the Transparent one: passed by the path)
    }
  }
}

void DenoisingFeatures::surface(const DenoisingClosures& c, float segment, const Vec3& normal,
                                const std::array<Vec3, 3>& camera_axes, PathRadiance& out) {
  if (!open_) return;
  auto finite = [](float v) { return std::isfinite(v) ? v : 0.0f; };
  const float share = share_ * choice_ * transparency_choice_;
  out.denoising_depth += share * finite(mean(throughput_) * segment);
  const bool first = first_;
  first_ = false;
  defended_ = first && !c.cycles4_closures;
  const float written = c.feature_weight();
  if (written > 0.0f && c.sum_weight > 0.0f) {  // 5.3 weighs the normal as the albedo
    float weight = share * written * (c.smooth_weights ? mean(throughput_) : 1.0f);
    if (c.smooth_weights && c.transparent_weight > 0.0f)  // 5.3: x the opaque closures' share
      weight *= c.sum_weight / (c.sum_weight + c.transparent_weight);
    for (int i = 0; i < 3; ++i)
      out.denoising_normal[i] += finite(weight * glm::dot(normal, camera_axes[size_t(i)]));
  }
  const Vec3 albedo = throughput_ * c.diffuse_albedo * written;
  for (int i = 0; i < 3; ++i) out.denoising_albedo[i] += share * finite(albedo[i]);
  Vec3 carried = c.specular_albedo * (1.0f - written);
  if (c.smooth_weights && c.transparent_weight > 0.0f) carried += c.transparent_albedo;  // 5.3: always on
  const bool goes_on = c.smooth_weights ? std::max({std::abs(carried.x), std::abs(carried.y), std::abs(carried.z)}) > 1e-4f : written == 0.0f;
  if (!goes_on) {
    open_ = false;
    return;
  }
  throughput_ *= carried;
  if (first) first_closures_ = c;
}

void DenoisingFeatures::left_transparent_surface(const DenoisingClosures& c, bool passed, float opacity) {
  if (!open_) return;
  const float q = c.transparent_probability(defended_);
  const float torrance = passed ? 1.0f - opacity : opacity;
  if (torrance > 0.0f) transparency_choice_ *= (passed ? q : 1.0f - q) / torrance;
}

}  // namespace torrance
