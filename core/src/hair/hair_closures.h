// The hair closures of a mixture at a hit: what MixtureBsdf builds for the Principled Hair BSDF
// (Chiang's and Huang's models, with Random Roughness and Random Color per strand) and the Hair
// BSDF node from a material and the hit's shader globals.
#pragma once

#include "torrance/hair/hair_bsdf.h"
#include "torrance/hair/huang_hair_bsdf.h"
#include "torrance/hair/principled_hair_bsdf.h"
#include "torrance/bsdfs/bsdf.h"
#include "torrance/shader/shader_program.h"

namespace torrance {

PrincipledHairParams principled_hair_params(const Material& m, const ShaderGlobals& g);
HuangHairParams huang_hair_params(const Material& m, const ShaderGlobals& g);
// transmission: the Hair BSDF node's Transmission component (else Reflection).
HairBsdf hair_bsdf(const Material& m, bool transmission, const ShaderGlobals& g);

}  // namespace torrance
