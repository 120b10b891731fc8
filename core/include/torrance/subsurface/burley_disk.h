// Cycles' Christensen-Burley subsurface scattering (closure/bssrdf.h's profile, integrator/
// subsurface_disk.h's disk sampling), for the closures whose method is Christensen-Burley:
//
//   profile  per channel of d = radius / (4 pi) (Cycles scales Burley's radius so):
//            R(r) = (exp(-r / d) + exp(-r / (3 d))) / (4 d) for r < 16 d, else 0; the "pdf" is
//            R / cdf(16) (0 at r = 0), the sample r solves cdf(r / d) = xi cdf(16) by Newton
//            (cdf(x) = 1 - exp(-x) / 4 - 3 exp(-x / 3) / 4), with the probe's half height
//            h = sqrt((16 d)^2 - r^2); a channel (of those with a radius) is chosen uniformly.
//   disk     one of three axes (the entry's geometric normal with probability 1/2, the two
//            tangents 1/4 each) is the probe's direction; a point at the sampled r and a uniform
//            angle on the disk about the others; a ray through it along -axis from height h
//            to -h finds the object's surfaces (all of them; at most 4, a uniform subset, are
//            weighed, x hits / 4), each weighed by R(|p - entry|) / pdf(r) and the axes' power
//            heuristic pdf_axis / sum pdf_k^2, pdf_k = P(k) |axis_k . n_hit|; one is chosen in
//            proportion to its mean weight, the path's throughput x its weight x the sum / its
//            mean weight. No colour is divided out: the closure's weight carries it.
// The exit is then shaded as the random walk's (exit_bsdf.h), seen along its geometric normal.
#pragma once

#include "torrance/subsurface/random_walk.h"

namespace torrance {

inline constexpr float kBurleyTruncate = 16.0f;  // Cycles' BURLEY_TRUNCATE
inline constexpr int kBurleyMaxHits = 4;         // BSSRDF_MAX_HITS

// The profile of one channel (d = radius / (4 pi)): eval, pdf and sample side by side.
float burley_eval(float d, float r);
float burley_pdf(float d, float r);
void burley_sample(float d, float xi, float& r, float& h);

// Christensen-Burley from the entry `position` of geometric normal `normal` (either side) for a
// path of `throughput` (the closure's weight included); the exit's direction is the chosen hit's
// geometric normal, flipped when `backfacing` (the entry was on the mesh's back). The boundary's
// probe() finds the hits; keep() is told the one chosen.
WalkExit burley_disk(WalkBoundary& boundary, const SubsurfaceLobe& lobe, const Vec3& position, const Vec3& normal,
                     bool backfacing, const Vec3& throughput, Rng& rng);

}  // namespace torrance
