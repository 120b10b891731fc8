// Cycles 3.4's Random Walk subsurface scattering (integrator/subsurface_random_walk.h; Chiang,
// Kutz and Burley 2016): the path enters the mesh through a Lambertian transmission (a cosine
// direction about the inward shading normal, weight 1; none if it points out of the geometric
// surface) or, as Cycles 4.x, a rough refraction (the direction of a GGX visible normal's
// refraction through the IOR, weight 1: Cycles leaves out its shadowing), then walks through the volume albedo_inversion.h makes of the closure until it meets
// the mesh's own surface again (other objects are not seen: Cycles' local intersection):
//
//   - the colour is divided out of the throughput (the walk's scattering brings it back); a
//     channel whose single-scattering albedo is below 0.2 is walked with 0.2 and its throughput
//     scaled by albedo / 0.2 (Cycles' min_alpha);
//   - each step picks a channel with probability proportional to |throughput x albedo| and draws
//     an exponential free flight with that channel's extinction; the throughput of every channel
//     is multiplied by its own transmittance (x its scattering coefficient where the flight ends
//     inside) over the mixture of the densities of every channel and strategy (one-sample MIS,
//     balance heuristic);
//   - directions after the first follow Henyey-Greenstein of the anisotropy about the direction
//     travelled, or, as often as Cycles' heuristic says, Dwivedi's guide (dwivedi_guide.h) about
//     the entry normal, backwards too where the first flight saw the opposite side within 10
//     mean free paths; past the 10th step the walk is isotropic with the reduced scattering
//     coefficient sigma_s (1 - g) (Cycles' similarity relation);
//   - at most 256 steps (Cycles' BSSRDF_MAX_BOUNCES); a throughput below 1e-6 ends it. The
//     strategies keep the expectation but for the walks this limit cuts off, which is why they
//     are Cycles' (the guide's walks are shorter).
// The exit's direction is the last flight's; the path then shades the exit point as if reached
// from outside (exit_bsdf.h).
#pragma once

#include "torrance/subsurface/subsurface_lobe.h"
#include "torrance/util/sampling.h"

namespace torrance {

inline constexpr int kMaxWalkSteps = 256;

inline constexpr int kMaxProbeHits = 32;  // the surfaces a Christensen-Burley probe collects at most

// A surface a probe met (burley_disk.h): its distance and geometric normal (world, the mesh's).
struct ProbeHit {
  float t = 0.0f;
  Vec3 normal{0.0f, 0.0f, 1.0f};
};

// The mesh a walk is inside, as the walk sees it.
class WalkBoundary {
 public:
  virtual ~WalkBoundary() = default;
  // The distance to the mesh's nearest surface along origin + t dir for t in (0, t_max]; false
  // if none.
  virtual bool nearest(const Vec3& origin, const Vec3& dir, float t_max, float& t) = 0;
  // Every surface of the mesh along origin + t dir for t in [0, t_max] (at most `capacity`, the
  // nearest first); their number. None by default.
  virtual int probe(const Vec3&, const Vec3&, float, ProbeHit*, int) { return 0; }
  // The probe's hit `index` is the exit.
  virtual void keep(int) {}
};

struct WalkExit {
  bool exited = false;
  Vec3 position{0.0f};   // on the mesh's surface
  Vec3 direction{0.0f};  // of the last flight, leaving through the surface
  Vec3 throughput{0.0f};  // the path's, the closure's weight and the walk's included
  int steps = 0;
};

// The walk of `lobe` entering at `position`, whose shading and geometric normals face the side
// the path came from (`normal`, `geometric_normal`; `incoming`: towards where the path came
// from, for a refractive entry), for a path of `throughput` (the closure's
// weight already included: Cycles' throughput at the subsurface bounce). `origin_offset`: how far
// the first flight starts below the surface (off the entry triangle).
WalkExit random_walk(WalkBoundary& boundary, const SubsurfaceLobe& lobe, const Vec3& position, const Vec3& normal,
                     const Vec3& geometric_normal, const Vec3& incoming, float origin_offset,
                     const Vec3& throughput, Rng& rng);

}  // namespace torrance
