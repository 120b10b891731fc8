// The Hosek / Wilkie sky model's published CIE XYZ coefficients (sky_hosek_data.cpp).
#pragma once

namespace torrance::shader {

// Per channel: 2 albedos x 10 turbidities x 6 control points x 9 parameters.
constexpr int kHosekConfigCount = 2 * 10 * 6 * 9;
// Per channel: 2 albedos x 10 turbidities x 6 control points.
constexpr int kHosekRadianceCount = 2 * 10 * 6;
extern const double kHosekConfigs[3][kHosekConfigCount];
extern const double kHosekRadiances[3][kHosekRadianceCount];

}  // namespace torrance::shader
