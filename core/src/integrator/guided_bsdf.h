// Path guiding's sampling at a path vertex (guiding.h): a one-sample mixture of the BSDF's own
// sampling (probability guide.bsdf_fraction()) and the learned guide, whose density -- used for the
// sample's weight -- is the same mixture of both pdfs, so the estimator stays unbiased whatever
// the guide. MIS against next-event estimation uses the BSDF's part alone (path_tracer.cpp).
#pragma once

#include "torrance/bsdfs/bsdf.h"
#include "torrance/integrator/guiding.h"

#include <glm/vec4.hpp>

#include <algorithm>

namespace torrance {

// Samples the mixture with the numbers of Bsdf::sample: u.x chooses the strategy (and, rescaled,
// the BSDF's lobe), u.yz the direction of either, so both keep the sampler's stratification of
// the direction. A delta lobe (only BSDF sampling produces it) gets its weight over the
// probability of choosing the BSDF; continuous directions get eval / mixture pdf. bsdf_pdf and
// guide_pdf: the parts of that pdf, square: the direction on the guide's square (for
// GuidingField::record), each found once. view: the BSDF's prepared at the vertex (its lobes' own
// normals included).
template <bool kGlass, typename Bsdf>
BsdfSample sample_guided(const Bsdf& bsdf, const GuideDistribution& guide, const Frame& frame,
                         const typename Bsdf::View& view, const glm::vec4& u, float& bsdf_pdf, float& guide_pdf,
                         Vec2& square) {
  const float a = guide.bsdf_fraction();
  if (u.x < a) {
    BsdfSample s = bsdf.template sample<kGlass>(view, std::min(u.x / a, 0.99999994f), Vec2(u.y, u.z));
    if (!s.valid()) return s;
    if (s.is_delta) {
      s.weight /= a;
      return s;
    }
    const Vec3 f = s.weight * s.pdf;
    bsdf_pdf = s.pdf;
    square = direction_to_square(frame.to_world(s.wi));
    guide_pdf = guide.pdf_of_square(square);
    s.pdf = a * bsdf_pdf + (1.0f - a) * guide_pdf;
    s.weight = f / s.pdf;
    return s;
  }
  const Vec3 wi_world = guide.sample(Vec2(u.y, u.z), square, guide_pdf);
  BsdfSample s;
  s.wi = frame.to_local(wi_world);
  s.diffuse = true;  // the Light Path node's label of a guide-drawn direction (Cycles has no guiding)
  bsdf_pdf = bsdf.template pdf<kGlass>(view, s.wi);
  s.pdf = a * bsdf_pdf + (1.0f - a) * guide_pdf;
  if (!(s.pdf > 0.0f)) return BsdfSample{};
  s.weight = bsdf.template eval_lobes<kGlass>(view, s.wi).total() / s.pdf;
  return s;
}

}  // namespace torrance
