// libFuzzer harness: a byte stream decoded into scene-building calls (materials, textures, meshes
// with arbitrary indices and float bit patterns, prototypes and instances with arbitrary matrices,
// lights, world, camera), then a tiny render.
// Every call must return or throw std::invalid_argument / std::runtime_error; the render of what
// was accepted must give a finite image. ASan/UBSan report the rest.
#include "fuzz_common.h"

#include "torrance/integrator/integrator.h"
#include "torrance/scene/scene.h"

#include <fuzzer/FuzzedDataProvider.h>

#include <cmath>
#include <cstring>
#include <vector>

using namespace torrance;
using torrance_fuzz::clearly;

namespace {

// Any float bit pattern (NaN, Inf, denormals) a third of the time, else a plain value.
float any_float(FuzzedDataProvider& in) {
  switch (in.ConsumeIntegralInRange<int>(0, 2)) {
    case 0: {
      const uint32_t bits = in.ConsumeIntegral<uint32_t>();
      float f;
      std::memcpy(&f, &bits, sizeof f);
      return f;
    }
    case 1: return in.ConsumeFloatingPointInRange<float>(-4.0f, 4.0f);
    default: return float(in.ConsumeIntegralInRange<int>(-2, 2)) * 0.5f;
  }
}
Vec3 any_vec3(FuzzedDataProvider& in) {
  const float x = any_float(in), y = any_float(in), z = any_float(in);
  return Vec3(x, y, z);
}

void add_mesh(FuzzedDataProvider& in, Scene& scene) {
  const size_t nv = in.ConsumeIntegralInRange<size_t>(0, 12), nt = in.ConsumeIntegralInRange<size_t>(0, 12);
  std::vector<float> positions(3 * nv);
  for (float& p : positions) p = any_float(in);
  std::vector<int64_t> triangles(3 * nt);
  for (int64_t& t : triangles)
    t = in.ConsumeBool() ? in.ConsumeIntegral<int64_t>() : in.ConsumeIntegralInRange<int64_t>(-1, int64_t(nv));
  std::vector<float> normals, uvs;
  std::vector<int64_t> materials;
  if (in.ConsumeBool()) {
    normals.resize(9 * nt);
    for (float& n : normals) n = any_float(in);
  }
  if (in.ConsumeBool()) {
    uvs.resize(6 * nt);
    for (float& u : uvs) u = any_float(in);
  }
  if (in.ConsumeBool()) {
    materials.resize(nt);
    for (int64_t& m : materials) m = in.ConsumeIntegralInRange<int64_t>(-1, int64_t(scene.num_materials()));
  }
  clearly([&] {
    scene.add_mesh(positions.data(), nv, triangles.data(), nt, normals.empty() ? nullptr : normals.data(),
                   materials.empty() ? nullptr : materials.data(), uvs.empty() ? nullptr : uvs.data());
  });
}

// A prototype (arbitrary vertices and slots), then a few instances of some prototype with
// arbitrary matrices (any bit patterns, huge translations and scales), moved and removed.
void add_instances(FuzzedDataProvider& in, Scene& scene) {
  if (scene.num_prototypes() == 0 || in.ConsumeBool()) {
    const size_t nv = in.ConsumeIntegralInRange<size_t>(0, 8), nt = in.ConsumeIntegralInRange<size_t>(0, 8);
    std::vector<float> positions(3 * nv);
    for (float& p : positions) p = any_float(in);
    std::vector<int64_t> triangles(3 * nt), slots(nt);
    for (int64_t& t : triangles) t = in.ConsumeIntegralInRange<int64_t>(-1, int64_t(nv));
    for (int64_t& m : slots) m = in.ConsumeIntegralInRange<int64_t>(-1, 3);
    clearly([&] { scene.add_prototype(positions.data(), nv, triangles.data(), nt, nullptr, slots.data()); });
  }
  const size_t count = in.ConsumeIntegralInRange<size_t>(0, 4);
  std::vector<float> transforms(12 * count);
  for (size_t i = 0; i < count; ++i) {
    float* m = &transforms[12 * i];
    for (int k = 0; k < 12; ++k) m[k] = (k % 5 == 0) ? 1.0f : 0.0f;  // identity
    for (int j = in.ConsumeIntegralInRange<int>(0, 4); j > 0; --j) {
      const int k = in.ConsumeIntegralInRange<int>(0, 11);
      m[k] = in.ConsumeBool() ? any_float(in) : std::ldexp(1.0f, in.ConsumeIntegralInRange<int>(-140, 127)) *
                                                    (in.ConsumeBool() ? -1.0f : 1.0f);
    }
  }
  const bool per_instance = in.ConsumeBool();
  const size_t table_size = in.ConsumeIntegralInRange<size_t>(0, 3);
  std::vector<int64_t> table((per_instance ? count : 1) * table_size);
  for (int64_t& t : table) t = in.ConsumeIntegralInRange<int64_t>(-1, int64_t(scene.num_materials()));
  const uint32_t prototype = in.ConsumeIntegralInRange<uint32_t>(0, uint32_t(scene.num_prototypes()));
  uint32_t first = 0;
  if (!clearly([&] {
        first = scene.add_instances(prototype, transforms.data(), count, table.data(), table_size, per_instance);
      }))
    return;
  if (count > 0 && in.ConsumeBool()) {  // move or remove some, with ids that may not exist
    std::vector<int64_t> ids(in.ConsumeIntegralInRange<size_t>(1, count));
    for (int64_t& id : ids) id = int64_t(first) + in.ConsumeIntegralInRange<int64_t>(-1, int64_t(count));
    if (in.ConsumeBool()) {
      std::vector<float> moved(12 * ids.size());
      for (float& v : moved) v = in.ConsumeBool() ? any_float(in) : float(in.ConsumeIntegralInRange<int>(-1, 1));
      clearly([&] { scene.set_instance_transforms(ids.data(), moved.data(), ids.size()); });
    } else {
      clearly([&] { scene.remove_instances(ids.data(), ids.size()); });
    }
  }
}

void add_texture(FuzzedDataProvider& in, Scene& scene) {
  int w = in.ConsumeIntegralInRange<int>(-1, 9), h = in.ConsumeIntegralInRange<int>(-1, 9);
  const int c = in.ConsumeIntegralInRange<int>(0, 5);
  if (in.ConsumeIntegralInRange<int>(0, 15) == 0) {  // sizes the checks must refuse before reading pixels
    w = in.ConsumeIntegralInRange<int>(1 << 14, 1 << 30);
    h = in.ConsumeIntegralInRange<int>(1 << 14, 1 << 30);
    clearly([&] { scene.add_texture(Texture(w, h, 4, nullptr, ColorSpace::Linear, Interpolation::Linear)); });
    return;
  }
  std::vector<float> pixels(size_t(std::max(w, 0)) * size_t(std::max(h, 0)) * size_t(std::max(c, 0)));
  for (float& p : pixels) p = any_float(in);
  const ColorSpace space = in.ConsumeBool() ? ColorSpace::SRGB : ColorSpace::Linear;
  const Interpolation interp = in.ConsumeBool() ? Interpolation::Closest : Interpolation::Linear;
  clearly([&] { scene.add_texture(Texture(w, h, c, pixels.data(), space, interp)); });
}

void set_camera(FuzzedDataProvider& in, Scene& scene) {
  CameraParams c;
  if (in.ConsumeBool()) {
    for (float& m : c.camera_to_world) m = any_float(in);
  } else {  // a plausible camera, placed somewhere
    c.camera_to_world[3] = any_float(in);
    c.camera_to_world[7] = any_float(in);
    c.camera_to_world[11] = any_float(in) + 4.0f;
  }
  if (in.ConsumeBool()) {
    c.lens_mm = any_float(in);
    c.sensor_width_mm = any_float(in);
    c.sensor_height_mm = any_float(in);
    c.shift_x = any_float(in);
    c.shift_y = any_float(in);
    c.clip_start = any_float(in);
    c.clip_end = any_float(in);
  }
  c.sensor_fit = SensorFit(in.ConsumeIntegralInRange<int>(0, 2));
  clearly([&] {
    Camera(c, 2, 2, 1.0f, 1.0f);  // as the bindings validate it
    scene.set_camera(c);
  });
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  torrance_fuzz::set_small_budget();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  Scene scene;
  for (int op = 0; op < 24 && in.remaining_bytes() > 0; ++op) {
    switch (in.ConsumeIntegralInRange<int>(0, 11)) {
      case 0: {
        Material m;
        if (in.ConsumeBool()) {  // wild values
          m.base_color = any_vec3(in);
          m.metallic = any_float(in);
          m.roughness = any_float(in);
          m.specular = any_float(in);
          m.emission = any_vec3(in);
          m.specular_tint = any_float(in);
          m.transmission = any_float(in);
          m.transmission_roughness = any_float(in);
          m.ior = any_float(in);
          m.alpha = any_float(in);
          m.transparent_color = any_vec3(in);
        } else {  // valid values, so that what follows (textures, rendering) is reached
          m.roughness = in.ConsumeFloatingPointInRange<float>(0.0f, 1.0f);
          m.metallic = in.ConsumeFloatingPointInRange<float>(0.0f, 1.0f);
          m.emission = Vec3(in.ConsumeFloatingPointInRange<float>(0.0f, 2.0f));
          m.transmission = in.ConsumeFloatingPointInRange<float>(0.0f, 1.0f);
          m.ior = in.ConsumeFloatingPointInRange<float>(0.5f, 3.0f);
          m.glass_node = in.ConsumeBool();
          m.alpha = in.ConsumeFloatingPointInRange<float>(0.0f, 1.0f);
        }
        MaterialTextures t;
        const int n = int(scene.num_textures());
        t.base_color = in.ConsumeIntegralInRange<int>(-2, n);
        t.roughness = in.ConsumeIntegralInRange<int>(-2, n);
        t.emission = in.ConsumeIntegralInRange<int>(-2, n);
        t.normal = in.ConsumeIntegralInRange<int>(-2, n);
        t.alpha = in.ConsumeIntegralInRange<int>(-2, n);
        t.emission_strength = in.ConsumeBool() ? any_float(in) : 1.0f;
        t.normal_strength = in.ConsumeBool() ? any_float(in) : 1.0f;
        clearly([&] { scene.add_material(m, t); });
        break;
      }
      case 1:
      case 2: add_mesh(in, scene); break;
      case 3: add_texture(in, scene); break;
      case 4: {
        const Vec3 d = any_vec3(in), c = any_vec3(in);
        const float s = any_float(in), a = any_float(in);
        clearly([&] { scene.edit_lights([&](Lights& l) { l.add_sun(d, s, c, a); }); });
        break;
      }
      case 5: {
        const Vec3 p = any_vec3(in), c = any_vec3(in);
        const float w = any_float(in), r = any_float(in);
        clearly([&] { scene.edit_lights([&](Lights& l) { l.add_point(p, w, c, r); }); });
        break;
      }
      case 6: {
        const Vec3 p = any_vec3(in), d = any_vec3(in), c = any_vec3(in);
        const float w = any_float(in), r = any_float(in), size = any_float(in), blend = any_float(in);
        clearly([&] { scene.edit_lights([&](Lights& l) { l.add_spot(p, d, w, c, r, size, blend); }); });
        break;
      }
      case 7: {
        const Vec3 p = any_vec3(in), u = any_vec3(in), v = any_vec3(in), d = any_vec3(in), c = any_vec3(in);
        const bool ellipse = in.ConsumeBool();
        const float w = any_float(in), spread = any_float(in);
        clearly([&] { scene.edit_lights([&](Lights& l) { l.add_area(p, u, v, d, ellipse, w, c, spread); }); });
        break;
      }
      case 8: {
        const Vec3 c = any_vec3(in);
        const float s = any_float(in);
        if (in.ConsumeBool()) clearly([&] { scene.edit_lights([&](Lights& l) { l.set_world(c, s); }); });
        else clearly([&] { scene.set_world_texture(in.ConsumeIntegralInRange<uint32_t>(0, 3), s); });
        break;
      }
      case 9: set_camera(in, scene); break;
      case 10: add_instances(in, scene); break;
      default: {
        RenderSettings s;
        s.width = in.ConsumeIntegralInRange<int>(1, 4);
        s.height = in.ConsumeIntegralInRange<int>(1, 4);
        // Mostly 1-2 samples; sometimes enough for adaptive checks and guiding's training passes.
        s.samples = in.ConsumeIntegralInRange<int>(0, 7) == 0 ? in.ConsumeIntegralInRange<int>(3, 40)
                                                               : in.ConsumeIntegralInRange<int>(1, 2);
        s.max_bounces = in.ConsumeIntegralInRange<int>(0, 4);
        s.passes = in.ConsumeIntegral<uint32_t>() & 0x1ff;
        s.brdf_model = in.ConsumeBool() ? BrdfModel::Principled : BrdfModel::Paper;
        s.light_selection = in.ConsumeBool() ? LightSelection::Uniform : LightSelection::Contribution;
        s.sobol = in.ConsumeBool();
        s.specialize = in.ConsumeBool();
        s.camera_packets = in.ConsumeBool();
        s.guiding = in.ConsumeBool();
        if (in.ConsumeBool()) s.guiding_training_fraction = any_float(in);
        if (in.ConsumeBool()) s.adaptive_threshold = any_float(in);
        if (in.ConsumeBool()) s.adaptive_min_samples = in.ConsumeIntegralInRange<int>(-1, 20);
        if (in.ConsumeBool()) s.clamp_direct = any_float(in);
        if (in.ConsumeBool()) s.clamp_indirect = any_float(in);
        s.efficiency_roulette = in.ConsumeBool();
        if (in.ConsumeBool()) s.roulette_min_survival = any_float(in);
        s.threads = 1;
        RenderResult r;
        if (clearly([&] { r = render(scene, s); })) {
          for (float v : r.image.rgba)
            if (!std::isfinite(v)) torrance_fuzz::fail("render gave a non-finite pixel");
        }
      }
    }
  }
  // Shade every material once, as a hit would (textures, normal map, mesh light on commit).
  clearly([&] {
    scene.commit();
    SurfaceHit hit;
    hit.tangent = Vec3(1.0f, 0.0f, 0.0f);
    hit.uv = Vec2(0.3f, 0.7f);
    for (uint32_t i = 0; i < scene.num_materials(); ++i) {
      const Material m = scene.textured_material(i, hit.uv, 0.01f);
      const Vec3 n = scene.normal_mapped(i, hit, Vec3(0.0f, 0.0f, 1.0f), 0.01f);
      if (!is_finite(m.base_color) || !is_finite(n)) torrance_fuzz::fail("shading gave a non-finite colour or normal");
    }
  });
  return 0;
}
