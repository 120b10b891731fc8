// The render's ray counts, the ray log and its replay through raw Embree (ray_log.h, ray_replay.h).
#include "scene_helpers.h"

#include "torrance/integrator/first_bounce_splits.h"
#include "torrance/integrator/ray_replay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

namespace torrance {
namespace {

Material grey() {
  Material m;
  m.base_color = Vec3(0.5f);
  m.specular = 0.0f;
  m.roughness = 1.0f;
  return m;
}

RenderSettings tiny(int samples, int max_bounces) {
  RenderSettings s;
  s.width = 8;
  s.height = 6;
  s.samples = samples;
  s.max_bounces = max_bounces;
  return s;
}

// The cluttered room's renders: 24 x 16 pixels (a 16-pixel tile and an 8-pixel one per row), 3 bounces.
RenderSettings room_frame(int samples) {
  RenderSettings s = tiny(samples, 3);
  s.width = 24;
  s.height = 16;
  return s;
}

// A plane at z = 0 filling the view of a camera above it, lit by a sun straight down.
void sunlit_plane(Scene& scene) {
  const int64_t m = scene.add_material(grey());
  test::add_quad(scene, Vec3(-50, -50, 0), Vec3(50, -50, 0), Vec3(50, 50, 0), Vec3(-50, 50, 0), m);
  test::look_down(scene, 5.0f, 2000.0f);
  scene.lights().add_sun(Vec3(0, 0, -1), 3.0f, Vec3(1.0f), 0.0f);
}

TEST(Rays, RenderCountsEveryQuery) {
  {  // Each sample: the camera ray hits the plane, one shadow ray to the sun, and unless the
     // diffuse sample is degenerate (a few of the 144) a bounce ray upward that misses.
    Scene scene;
    sunlit_plane(scene);
    const RenderResult r = render(scene, tiny(3, 0));
    const uint64_t samples = (8 + 2) * (6 + 2) * 3;  // the image and its 1-pixel splatting ring
    EXPECT_EQ(r.samples_spent, samples);
    EXPECT_EQ(r.occlusion_rays, samples);
    EXPECT_GT(r.closest_rays, samples + samples * 9 / 10);
    EXPECT_LE(r.closest_rays, 2 * samples);
    EXPECT_EQ(r.rays_traced(), r.closest_rays + r.occlusion_rays);
  }
  {  // Looking away from the plane: one camera ray per sample, nothing else.
    Scene scene;
    sunlit_plane(scene);
    CameraParams up = scene.camera();
    up.camera_to_world = {1, 0, 0, 0, 0, -1, 0, 0, 0, 0, -1, 5, 0, 0, 0, 1};  // looking up (+z)
    scene.set_camera(up);
    const RenderResult r = render(scene, tiny(5, 4));
    EXPECT_EQ(r.closest_rays, uint64_t(10 * 8 * 5));
    // With the automatic splitting's pilot (first_bounce_splits.h: its 2 x 1 pixels, 4 samples
    // each), its camera rays are counted too.
    RenderSettings piloted_settings = tiny(5, 4);
    piloted_settings.first_bounce_splits = 0;
    const RenderResult piloted = render(scene, piloted_settings);
    EXPECT_EQ(piloted.closest_rays, uint64_t(10 * 8 * 5 + 2 * 1 * FirstBounceSplits::kSamples));
    EXPECT_EQ(r.occlusion_rays, 0u);
  }
}

// A box room with a few tilted panels inside: hits at many triangles, shadows partly blocked.
void cluttered_room(Scene& scene) {
  const int64_t m = scene.add_material(grey());
  const float s = 4.0f;
  test::add_quad(scene, Vec3(-s, -s, 0), Vec3(s, -s, 0), Vec3(s, s, 0), Vec3(-s, s, 0), m);        // floor
  test::add_quad(scene, Vec3(-s, s, 0), Vec3(s, s, 0), Vec3(s, s, 2 * s), Vec3(-s, s, 2 * s), m);  // back wall
  // A panel above the point light: a shadow ray running past the light would hit it.
  test::add_quad(scene, Vec3(-2, -2, 8), Vec3(-2, 2, 8), Vec3(2, 2, 8), Vec3(2, -2, 8), m);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-3.0f, 3.0f);
  for (int i = 0; i < 20; ++i) {
    const Vec3 c(u(rng), u(rng), 1.5f + 0.3f * u(rng));
    test::add_quad(scene, c, c + Vec3(0.8f, 0.1f, 0.2f), c + Vec3(0.7f, 0.9f, 0.5f), c + Vec3(-0.1f, 0.8f, 0.3f), m);
  }
  // Two instances of a prototype panel with UVs, one mirrored (instance hits, swapped corners).
  const float p[] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
  const int64_t tris[] = {0, 1, 2, 0, 2, 3};
  const float uvs[] = {0, 0, 1, 0, 1, 1, 0, 0, 1, 1, 0, 1};
  const uint32_t proto = scene.add_prototype(p, 4, tris, 2, nullptr, nullptr, uvs);
  const float placed[] = {1, 0, 0, -3, 0, 1, 0, -2, 0, 0, 1, 0.2f, -1, 0, 0, 3, 0, 1, 0, -2.5f, 0, 0, 1.5f, 0.1f};
  const int64_t table[] = {m};
  scene.add_instances(proto, placed, 2, table, 1);
  CameraParams cam;
  cam.camera_to_world = {1, 0, 0, 0, 0, 0, -1, -12, 0, 1, 0, 3, 0, 0, 0, 1};  // at y = -12 looking +y
  cam.lens_mm = 35.0f;
  scene.set_camera(cam);
  scene.lights().add_sun(glm::normalize(Vec3(0.3f, 0.5f, -1.0f)), 3.0f, Vec3(1.0f), 0.02f);
  scene.lights().add_point(Vec3(0, 0, 6), 500.0f, Vec3(1.0f), 0.1f);
}

TEST(Rays, LogHoldsTheRenderedRaysAndRawEmbreeGivesTheSameAnswers) {
  Scene scene;
  cluttered_room(scene);
  RenderSettings settings = room_frame(4);
  const RenderResult counted = render(scene, settings);
  const std::vector<LoggedRay> logged = record_render_rays(scene, settings);
  ASSERT_EQ(logged.size(), counted.rays_traced());  // the same render, the same rays
  size_t camera = 0, occluded = 0;
  for (const LoggedRay& r : logged) {
    camera += r.kind == RayKind::Camera;
    occluded += r.kind == RayKind::Occlusion && r.occluded;
  }
  EXPECT_EQ(camera, size_t(26 * 18 * 4));  // the image and its 1-pixel splatting ring
  EXPECT_GT(occluded, 0u);
  // The log's order (runs of one kind are short: mostly partial packets), then the camera rays
  // alone (full, coherent packets).
  const std::vector<LoggedRay> camera_rays = select_rays(logged, RayKind::Camera);
  for (const std::vector<LoggedRay>* expected : {&logged, &camera_rays})
    for (int width : {1, 8}) {
      std::vector<LoggedRay> replayed = *expected;
      for (LoggedRay& r : replayed) r.geom_id = r.prim_id = r.inst_id = 12345, r.hit_t = -1.0f, r.occluded = !r.occluded;
      replay_rays(scene, replayed, width);
      size_t differ = 0;
      for (size_t i = 0; i < replayed.size(); ++i) differ += !(*expected)[i].same_answer(replayed[i]);
      EXPECT_EQ(differ, 0u) << "packet width " << width << " of " << replayed.size() << " rays";
    }
}

TEST(Rays, PacketsAnswerAsSingleRaysOnRandomRays) {
  Scene scene;
  cluttered_room(scene);
  scene.commit();
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<LoggedRay> rays(5000);
  for (size_t i = 0; i < rays.size(); ++i) {
    LoggedRay& r = rays[i];
    r.origin = Vec3(3.5f * u(rng), 3.5f * u(rng), 3.0f + 2.5f * u(rng));
    Vec3 d(u(rng), u(rng), u(rng));
    r.dir = glm::length(d) > 1e-3f ? glm::normalize(d) : Vec3(0, 0, -1);
    // In three blocks of one kind each (of 1667 or 1666 rays: full packets and a partial one).
    const size_t block = 3 * i / rays.size();
    r.kind = block == 0 ? RayKind::Occlusion : (block == 1 ? RayKind::Camera : RayKind::Closest);
    r.tmin = r.kind == RayKind::Camera ? 0.1f : 0.0f;
    r.tmax = i % 5 == 0 ? INFINITY : 1.0f + 4.0f * (u(rng) + 1.0f);
  }
  std::vector<LoggedRay> single = rays;
  replay_rays(scene, single, 1);
  size_t hits = 0;
  for (const LoggedRay& r : single) hits += r.kind == RayKind::Occlusion ? r.occluded : r.geom_id != 0xFFFFFFFFu;
  EXPECT_GT(hits, rays.size() / 4);
  EXPECT_LT(hits, rays.size());
  for (int width : {8}) {
    std::vector<LoggedRay> packets = rays;
    replay_rays(scene, packets, width);
    size_t differ = 0;
    for (size_t i = 0; i < rays.size(); ++i) differ += !single[i].same_answer(packets[i]);
    EXPECT_EQ(differ, 0u) << "packet width " << width;
  }
}

bool same_bits(const SurfaceHit& a, const SurfaceHit& b) {
  auto eq = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof(x)) == 0; };
  return eq(a.t, b.t) && eq(a.position, b.position) && eq(a.geometric_normal, b.geometric_normal) &&
         eq(a.shading_normal, b.shading_normal) && a.material == b.material && a.emitter == b.emitter &&
         eq(a.uv, b.uv) && eq(a.tangent, b.tangent) && eq(a.uv_per_metre, b.uv_per_metre) &&
         eq(a.bitangent_sign, b.bitangent_sign) && eq(a.dpdu, b.dpdu) && eq(a.dpdv, b.dpdv);
}

TEST(Rays, PacketHitsAreSingleHitsBitForBit) {
  Scene scene;
  cluttered_room(scene);
  scene.commit();
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  size_t hits = 0, differ = 0, total = 0;
  for (int group = 0; group < 600; ++group) {
    const int n = group % 8 + 1;  // every packet fill, 1 to 8 lanes
    Ray rays[Scene::kPacketSize];
    const Vec3 origin(3.0f * u(rng), -11.0f + u(rng), 3.0f + u(rng));  // near the camera, aiming at the room
    for (int i = 0; i < n; ++i) {
      rays[i].origin = origin;
      rays[i].dir = glm::normalize(Vec3(0.4f * u(rng), 1.0f, 0.3f * u(rng)));
      rays[i].tmin = 0.1f;
      rays[i].tmax = i == 3 ? 9.0f : 1000.0f;  // one lane stops short of the wall
    }
    SurfaceHit packet_hits[Scene::kPacketSize];
    bool found[Scene::kPacketSize];
    scene.intersect_packet(rays, n, packet_hits, found);
    for (int i = 0; i < n; ++i) {
      SurfaceHit single;
      const bool single_found = scene.intersect(rays[i], single);
      hits += single_found;
      ++total;
      differ += single_found != found[i] || (single_found && !same_bits(single, packet_hits[i]));
    }
  }
  EXPECT_EQ(differ, 0u) << "of " << total << " rays";
  EXPECT_GT(hits, total / 2);
  EXPECT_LT(hits, total);
}

TEST(Rays, CameraPacketsRenderTheSameImageBitForBit) {
  Scene scene;
  cluttered_room(scene);
  RenderSettings settings = room_frame(13);  // 13: a full packet and a partial one per pixel and pass
  settings.passes = kPassNormal | kPassDiffuseDirect;
  settings.camera_packets = false;
  const RenderResult single = render(scene, settings);
  settings.camera_packets = true;
  const RenderResult packets = render(scene, settings);
  ASSERT_EQ(single.image.rgba.size(), packets.image.rgba.size());
  EXPECT_EQ(std::memcmp(single.image.rgba.data(), packets.image.rgba.data(), single.image.rgba.size() * 4), 0);
  for (size_t p = 0; p < single.passes.size(); ++p)
    EXPECT_EQ(std::memcmp(single.passes[p].second.rgba.data(), packets.passes[p].second.rgba.data(),
                          single.passes[p].second.rgba.size() * 4), 0) << single.passes[p].first;
  EXPECT_EQ(single.closest_rays, packets.closest_rays);
  EXPECT_EQ(single.occlusion_rays, packets.occlusion_rays);
}

// Passes of fewer than 8 samples per pixel (the first passes of every render: 1, 2, 4, ...
// samples) fill their camera packets with the next pixels' samples: a 1-sample render of a
// 24 x 16 image (tiles 16 and 8 pixels wide) traces each tile row as full packets, 3 per image
// row, and the same image as ray by ray (CameraPacketsRenderTheSameImageBitForBit's 13 samples
// run passes of 1, 2, 4 and 6).
TEST(Rays, OneSamplePassesTraceCameraRaysInFullPackets) {
  Scene scene;
  cluttered_room(scene);
  RenderSettings settings = room_frame(1);
  settings.filter_splatting = false;  // the tiles of the image alone (splatting adds a ring)
  const RenderResult packets = render(scene, settings);
  EXPECT_EQ(packets.camera_packets, 3u * 16u);
  settings.camera_packets = false;
  const RenderResult single = render(scene, settings);
  EXPECT_EQ(single.camera_packets, 0u);
  EXPECT_EQ(std::memcmp(single.image.rgba.data(), packets.image.rgba.data(), single.image.rgba.size() * 4), 0);
}

}  // namespace
}  // namespace torrance
