#include "torrance/bsdfs/multiscatter_glossy_bsdf.h"

namespace torrance {

MultiscatterGlossyBsdf::MultiscatterGlossyBsdf(const Vec3& color, float roughness, float anisotropy,
                                               const Vec3& tangent, float rotation, microsurface::HeightStep step)
    : color_(glm::clamp(color, Vec3(0.0f), Vec3(1.0f))) {
  microsurface::Reflectance r;
  r.color = color_;
  walk_ = microsurface::Walk(GlossyBsdf::lobe_shape(roughness, anisotropy, tangent, rotation), r, step);
}

}  // namespace torrance
