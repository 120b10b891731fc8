// Heterogeneous media (torrance/media/varying_medium.h) sampled without bias, so that a render
// converges to what Cycles' ray marching converges to as its step shrinks: free flights by
// spectral tracking (Kutz et al. 2017: tentative collisions at the mix's majorant rate, each a
// real scattering or a null collision chosen in proportion to the path's throughput times the
// coefficients, the weights correcting every channel), emission estimated at every tentative
// collision, shadow transmittance by ratio tracking. A point whose extinction exceeds the
// majorant (a feature the majorant's grid missed) gives a negative null coefficient: the choice
// takes |p_scatter| / (|p_scatter| + |p_null|) and the path carries the signed weight (weighted
// delta tracking), so the estimate stays unbiased; the path tracer's checks take |weight|.
// A heterogeneous medium exists only inside its bounds: tracking covers the hull of the ray's
// spans through them, the stretches before and after take the mix's constant part alone.
#pragma once

#include "torrance/media/homogeneous_medium.h"
#include "torrance/util/sampling.h"

namespace torrance {

class Scene;
struct VaryingMedium;

// The coefficients of a heterogeneous medium at p, seen along dir.
HomogeneousMedium varying_coefficients(const Scene& scene, const VaryingMedium& medium, const Vec3& p,
                                       const Vec3& dir);

// mix at p: its constant part plus its heterogeneous media's values there (a mix without them).
MediumMix mix_at(const Scene& scene, const MediumMix& mix, const Vec3& p, const Vec3& dir);

// A bound of max_component(sigma_a + sigma_s) of medium over its bounds: the largest value on a
// grid of points through them, with a margin for what lies between (never below a rate that
// gives emission-only media a few collisions across their bounds).
float varying_majorant(const Scene& scene, const VaryingMedium& medium);

// A free flight from origin along dir over [0, t_max) through a mix with heterogeneous media, as
// sample_free_flight's (homogeneous_medium.h); local: the mix at the scattering point.
FreeFlight track_free_flight(const Scene& scene, const MediumMix& mix, const Vec3& origin, const Vec3& dir,
                             float t_max, const Vec3& throughput, Rng& rng, bool may_scatter, MediumMix& local);

// The transmittance of such a mix from origin along dir over [0, t_max) (ratio tracking).
Vec3 ratio_tracking(const Scene& scene, const MediumMix& mix, const Vec3& origin, const Vec3& dir, float t_max,
                    Rng& rng);

// A generator for one stretch, from sampler values or a ray's floats (their bits).
Rng tracking_rng(float a, float b, float c = 0.0f);

}  // namespace torrance
