// The hair closures of a mixture at a hit: what MixtureBsdf builds for the Principled Hair BSDF
// (Chiang's and Huang's models, with Random Roughness and Random Color per strand) and the Hair
// BSDF node from a material and the hit's shader globals.
#pragma once

#include "torrance/hair/hair_bsdf.h"
#include "torrance/hair/huang_hair_bsdf.h"
#include "torrance/hair/principled_hair_bsdf.h"
#include "torrance/bsdfs/bsdf.h"
#include "torrance/bsdfs/mixture.h"
#include "torrance/scene/scene.h"
#include "torrance/shader/shader_program.h"

namespace torrance {

PrincipledHairParams principled_hair_params(const Material& m, const ShaderGlobals& g);
HuangHairParams huang_hair_params(const Material& m, const ShaderGlobals& g);
// transmission: the Hair BSDF node's Transmission component (else Reflection).
HairBsdf hair_bsdf(const Material& m, bool transmission, const ShaderGlobals& g);

// Whether some closure of mixture `mixture` may let rays through at a strand's hit: a Huang
// closure whose Aspect Ratio is not 1 (Cycles' node then has surface transparency; the path
// tracer passes such a hit as a transparent surface, pass_sheet).
bool hair_may_pass(const Scene& scene, const Mixture& mixture);

}  // namespace torrance
