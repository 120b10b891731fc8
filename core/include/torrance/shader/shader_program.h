// A shader program: the part of a Blender node graph that computes the values feeding a
// closure's sockets (textures, colour and converter nodes, maths), compiled by the add-on
// (python_addon/torrance/shader_graph/) into straight-line code over registers of four floats
// and run by the core at each hit whose material needs it.
//
// Registers 0 .. constants-1 hold the graph's folded constants; every instruction reads up to
// kShaderInputs registers written before it and writes one; ops with tables (ramps, curves) read
// them from the program's data: at the instruction's resource, a length n and then n floats. A float lives in a register's x, a colour in xyz (w
// is an image's alpha), a vector in xyz. The ops are Cycles' (shader_math.h, shader_color.h); the
// add-on inserts Blender's implicit conversions (colour -> float: luminance, vector -> float:
// average) as instructions, so every op reads exactly the kind it expects.
#pragma once

#include "torrance/util/math.h"
#include "torrance/integrator/path_state.h"
#include "torrance/shader/texture.h"

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace torrance {

class VolumeGrid;

enum class ShaderOpcode : uint8_t {
  TexCoordUV,      // out = (u, v, 0, 0): the mesh's UVs (Texture Coordinate > UV, UV Map, unlinked Vector)
  Image,           // out = texture(in0.xy) RGBA; resource = its id; mode: the Extension (texture.h)
  Channel,         // out = (in0[mode], 0, 0, 0): Separate RGB/XYZ/Color (RGB), an image's Alpha
  Combine,         // out = (in0.x, in1.x, in2.x, 1): Combine RGB/XYZ/Color (RGB)
  Math,            // out.x = math(mode, in0.x, in1.x, in2.x); flags & 1: clamp to [0, 1]
  VectorMath,      // vector_math(mode, in0, in1, in2, in3.x): flags & 1 ? (value, 0, 0, 0) : vector
  MixColor,        // mix_color(mode, factor(in0.x, flags & 2), in1, in2, flags & 1)
  MixFloat,        // out.x = mix_float(factor(in0.x, flags & 2), in1.x, in2.x)
  MixVector,       // mix_vector(flags & 4 ? in0 : in0.x, in1, in2); flags & 2: clamp the factor
  ColorModel,      // mode 0: RGB -> HSV, 1: HSV -> RGB, 2: RGB -> HSL, 3: HSL -> RGB (of in0.xyz)
  Invert,          // invert(in0.x, in1)
  Gamma,           // gamma(in0, in1.x)
  BrightContrast,  // bright_contrast(in0, in1.x, in2.x)
  HueSaturation,   // hue_saturation_value(in0.x, in1.x, in2.x, in3.x, in4)
  Luminance,       // out.x = rgb_to_bw(in0): colour -> float
  Average,         // out.x = (in0.x + in0.y + in0.z) / 3: vector -> float
  Bump = 16,       // the Bump node (shader_bump.h): a normal from heights at the hit and its offsets
  NormalMap = 17,  // the Normal Map node (shader_bump.h)
  Displacement = 18,        // the Displacement and Vector Displacement nodes (shader_bump.h)
  VectorDisplacement = 19,
  // The node families' ops, each family a range of numbers (its header says what each op reads;
  // shader_op_info lists their shapes; python_addon/torrance/shader_graph/ the same numbers):
  //   32-47 noise (shader_noise.h), 48-55 Voronoi (shader_voronoi.h), 56-71 textures
  //   (shader_textures.h), 72-95 converters (shader_convert.h), 96-127 geometry and vectors.
  // [noise ops]
  Noise = 32,       // Noise Texture (shader_noise.h): mode = dimensions - 1; flags & 1: Color, else Fac
  WhiteNoise = 33,  // White Noise Texture: mode = dimensions - 1; flags & 1: Color, else Value
  Musgrave = 34,    // Musgrave Texture: mode = type * 4 + dimensions - 1
  Wave = 35,        // Wave Texture: mode = (type * 4 + direction) * 3 + profile; flags & 1: Color
  NoiseV4 = 36,     // Blender 4.x's Noise Texture (shader_noise4.h): mode = type * 4 + dimensions - 1
  TexGabor = 37,    // Blender 4.3+'s Gabor Texture (shader_gabor.h): mode 2D/3D; out (Value, Phase, Intensity)
  // [voronoi ops]
  Voronoi = 48,    // the Voronoi Texture node (shader_voronoi.h): mode, flags and inputs as voronoi_op says
  VoronoiV4 = 49,  // Blender 4.x's Voronoi Texture (fractal; shader_voronoi.h): as voronoi4_op says
  // [texture ops]
  TexChecker = 56,   // shader_textures.h (flags & 1: the Fac, else the Color)
  TexGradient = 57,
  TexBrick = 58,
  TexMagic = 59,
  ImageProjection = 60,  // shader_image.h
  TexSky = 61,           // shader_sky.h: the Sky Texture node; mode: SkyModel, a table
  RadialTiling = 62,     // shader_radial_tiling.h: Blender 5's Radial Tiling; mode: its outputs
  TexIES = 63,           // shader_ies.h: the IES Texture node (Fac); a table
  TexPointDensity = 64,  // shader_voxel.h: the Point Density node (Color xyz, Density w); a table
  // [converter ops]
  ColorRamp = 72,       // shader_convert.h: RGBA = ramp(in0.x), table RGBA; flags & 1: interpolate
  RGBCurves = 73,       // curves(fac in0.x, colour in1), table (min_x, max_x, RGB); flags & 1: extrapolate
  VectorCurves = 74,    // as RGBCurves on a vector (w 0)
  FloatCurve = 75,      // float_curve(fac in0.x, value in1.x), table (min_x, max_x, values); flags & 1 as above
  MapRange = 76,        // map_range(mode, in0-in5 .x: value, from min/max, to min/max, steps); flags & 1: clamp
  VectorMapRange = 77,  // vector_map_range(mode, in0-in5 as vectors); flags & 1: clamp
  Clamp = 78,           // clamp(mode, in0.x, min in1.x, max in2.x)
  Blackbody = 79,       // blackbody(in0.x kelvin)
  Wavelength = 80,      // wavelength(in0.x nanometres)
  // [geometry ops]
  Geometry = 96,     // shader_geometry.h
  Reflection = 97,
  Fresnel = 98,
  LayerWeight = 99,
  Attribute = 100,
  Tangent = 101,
  AmbientOcclusion = 102,  // shader_geometry.h
  Bevel = 103,             // shader_bevel.h
  Mapping = 104,       // shader_vector.h
  VectorRotate = 105,
  LightPath = 106,     // shader_geometry.h
  CameraTransform = 107,
  VectorTransform = 108,  // shader_vector.h
  LightFalloff = 109,     // shader_geometry.h
  Wireframe = 110,
  VolumeGrid = 111,       // media/volume_grid.h: a grid (resource) at in0 (a world point), RGBA
  CurvesInfo = 112,       // shader_curves_info.h
  Raycast = 113,          // shader_raycast.h
  PointInfo = 114,        // shader_curves_info.h
};
constexpr int kShaderOpcodes = 128;

constexpr int kShaderInputs = 12;

struct ShaderInstruction {
  ShaderOpcode op = ShaderOpcode::TexCoordUV;
  uint8_t mode = 0, flags = 0;
  int32_t resource = -1;  // Image: the texture id; ops with tables: the offset of their data
  int16_t out = 0;
  std::array<int16_t, kShaderInputs> in{};
  // Where the op reads the hit: 0 at the hit, 1 and 2 at the hit moved by the ray differentials
  // dx and dy (ShaderGlobals::offset; a Bump node's height graph, compiled three times, as
  // Cycles does). Python code rows carry it in flags bits 6-7.
  uint8_t offset = 0;
};

// A hit of a local ray query (ShaderTracer::local_hits): world space, the normals as wound.
struct LocalHit {
  Vec3 position{0.0f};
  Vec3 true_normal{0.0f};  // unit
  Vec3 normal{0.0f};       // the interpolated (smooth) normal, unit
};

// The surface a Raycast node's ray meets first (ShaderTracer::raycast).
struct RaycastHit {
  float t = 0.0f;       // along the ray, in lengths of its direction
  Vec3 normal{0.0f};    // the smooth normal, turned toward the ray's origin (unit)
  uint32_t object = 0;  // as ShaderGlobals::object names it (kNoObject on a hair strand)
};

// What a program may trace (the Ambient Occlusion, Bevel and Raycast nodes): the scene (Scene
// implements it).
class ShaderTracer {
 public:
  // Whether anything lies along origin + t dir for t in (tmin, tmax).
  virtual bool occluded(const Vec3& origin, const Vec3& dir, float tmin, float tmax) const = 0;
  // Local queries (Cycles' scene_intersect_local): against object `object`'s own triangles only
  // (ShaderGlobals::object; an instance's its prototype's, placed), nothing else in the scene.
  // Whether any of them lies along origin + t dir for t in (tmin, tmax); false for no object.
  virtual bool local_occluded(uint32_t object, const Vec3& origin, const Vec3& dir, float tmin, float tmax) const {
    (void)object, (void)origin, (void)dir, (void)tmin, (void)tmax;
    return false;
  }
  // All hits on origin + t dir, t in [0, tmax]: how many there are, of which up to max_hits chosen
  // uniformly at random (a reservoir drawn by `seed`, as Cycles keeps LOCAL_MAX_HITS) go to hits.
  virtual int local_hits(uint32_t object, const Vec3& origin, const Vec3& dir, float tmax, uint32_t seed,
                         LocalHit* hits, int max_hits) const {
    (void)object, (void)origin, (void)dir, (void)tmax, (void)seed, (void)hits, (void)max_hits;
    return 0;
  }
  // The first surface along origin + t dir, t in [tmin, tmax] (Cycles' scene_intersect of the
  // Raycast node, whatever the surface's material: transparent ones stop it too): in the whole
  // scene when only_object is kNoObject, else against that object's own triangles (a local
  // query; none for no such object). A hit on triangle skip_prim of object skip_object is passed
  // by (the surface the ray leaves: Cycles' self-intersection skip; kNoObject skips none).
  virtual bool raycast(const Vec3& origin, const Vec3& dir, float tmin, float tmax, uint32_t only_object,
                       uint32_t skip_object, uint32_t skip_prim, RaycastHit& hit) const {
    (void)origin, (void)dir, (void)tmin, (void)tmax, (void)only_object, (void)skip_object, (void)skip_prim, (void)hit;
    return false;
  }

 protected:
  ~ShaderTracer() = default;
};

// What a program may read at a hit, as Cycles' ShaderData: world-space position, the shading and
// true normals facing the viewer (flipped on a back face), the direction toward the viewer.
struct ShaderGlobals {
  Vec2 uv{0.0f};
  float footprint = 0.0f;  // the texture lookups' footprint, in UV units
  Vec3 position{0.0f};
  Vec3 normal{0.0f, 0.0f, 1.0f};
  Vec3 true_normal{0.0f, 0.0f, 1.0f};
  Vec3 incoming{0.0f, 0.0f, 1.0f};
  bool backfacing = false;
  // A hair strand's hit (SurfaceHit::on_curve; the Curves Info node): its Intercept (0 at the
  // root, 1 at the tip), its strand's Length, its Thickness and the strand's Random.
  bool on_curve = false;
  // A point's hit (SurfaceHit::on_point; the Point Info node): primitive_info holds its centre
  // (xyz) and radius there.
  bool on_point = false;
  glm::vec4 primitive_info{0.0f};
  Vec3 curve_normal{0.0f};  // a strand's normal attribute (SurfaceHit::curve_normal), else 0
  // The hit triangle's corner attributes (corner k's layer a at k * num_attributes + a), the
  // layers' ids and the corners' interpolation weights.
  const Vec3* corner_attributes = nullptr;
  const int32_t* attribute_ids = nullptr;
  int num_attributes = 0;
  Vec3 corner_weights{0.0f};
  // The hit instance's constant attributes (Object Info of an instanced object): layer a's value
  // at instance_constants[a], its id instance_constant_ids[a].
  const Vec3* instance_constants = nullptr;
  const int32_t* instance_constant_ids = nullptr;
  int num_instance_constants = 0;
  PathState path;  // the path's state where the program runs (the Light Path node)
  // The scene a program may trace (Ambient Occlusion); null where there is none (a world, a
  // light: as Cycles' for no object, the node then sees no occluder).
  const ShaderTracer* tracer = nullptr;
  // The hit's object for the tracer's local queries (SurfaceHit::object; kNoObject: none) and
  // its triangle.
  static constexpr uint32_t kNoObject = 0xFFFFFFFFu;
  uint32_t object = kNoObject, prim = 0;
  // A 2-D point of the path's sampler for this hit, stratified over the pixel's samples (the
  // path tracer's, where kReadsSampleShift asks for it): ops that trace several rays rotate
  // their points by it, as Cycles' branched sampling spreads them over the pixel's samples.
  Vec2 sample_shift{0.0f};
  bool has_sample_shift = false;
  // Cycles' ray differentials at the hit: dP/dx and dP/dy (the footprint's width along its
  // tangent pair around the true normal), and what they move the UVs and corner weights by.
  Vec3 dpdx{0.0f}, dpdy{0.0f};
  Vec2 duvdx{0.0f}, duvdy{0.0f};
  Vec3 dweights_dx{0.0f}, dweights_dy{0.0f};
  // The UV map's tangent (unit dP/du, as wound; 0 without UVs) and the bitangent's sign.
  Vec3 tangent{0.0f};
  float bitangent_sign = 1.0f;
  Vec3 corners[3] = {Vec3(0.0f), Vec3(0.0f), Vec3(0.0f)};  // the hit triangle's, world space (0: none)
  // The scene's volume grids a heterogeneous volume's program reads (VolumeGrid ops; null
  // elsewhere: they read 0), and whether those ops give their bricks' bounds instead of values
  // (VolumeGrid::brick_max: the majorant's search).
  const std::vector<std::shared_ptr<const VolumeGrid>>* grids = nullptr;
  bool grid_bounds = false;
  // These globals at the hit moved by width times dx (which 1) or dy (which 2): position, UVs
  // and corner weights (normals, the view and footprint stay, as in Cycles' bump evaluation;
  // width: the Bump's Filter Width, 1 before Cycles 4.3).
  ShaderGlobals offset(int which, float width = 1.0f) const {
    ShaderGlobals g = *this;
    const bool x = which == 1;
    g.position += width * (x ? dpdx : dpdy);
    g.uv += width * (x ? duvdx : duvdy);
    g.corner_weights += width * (x ? dweights_dx : dweights_dy);
    return g;
  }
};

#if defined(__has_builtin)
#if __has_builtin(__builtin_shufflevector)
#define TORRANCE_HAS_SHUFFLEVECTOR 1
#endif
#endif

// An op's output: a register's four values, returned in one vector register. (A glm::vec4 comes
// back split over two, which the program's loop joined again through memory: a load that waits
// for the two stores before it, after every instruction, ~40 % of the loop's own time in a
// profile of a procedural material.)
struct OpValue {
  typedef float Lanes __attribute__((vector_size(16)));
  Lanes lanes;
  // From the two halves a glm::vec4 is returned in, joined in registers (a shuffle: written as
  // {x, y, z, w} GCC joins them through memory, the same stall again, at every op's return).
  OpValue(const glm::vec4& v) {  // NOLINT: ops return glm::vec4s
#if TORRANCE_HAS_SHUFFLEVECTOR
    typedef float Half __attribute__((vector_size(8)));
    const Half low = {v.x, v.y}, high = {v.z, v.w};
    lanes = __builtin_shufflevector(low, high, 0, 1, 2, 3);
#else
    lanes = Lanes{v.x, v.y, v.z, v.w};
#endif
  }
  OpValue(float x, float y, float z, float w) : lanes{x, y, z, w} {}
  operator glm::vec4() const { return glm::vec4(lanes[0], lanes[1], lanes[2], lanes[3]); }  // NOLINT
};

// What an op sees when it runs: its instruction, the registers and the program's data.
struct ShaderOpContext {
  const ShaderInstruction& ins;
  const glm::vec4* regs;
  const ShaderGlobals& globals;
  const float* data;  // the op's table (after its length), when it has one
  int data_size;      // its length
  const glm::vec4& in(int k) const { return regs[ins.in[size_t(k)]]; }
  float value(int k) const { return in(k).x; }
  Vec3 vector(int k) const { return Vec3(in(k)); }
};

// An opcode's shape: the inputs it reads, how many modes it has (0: not an opcode), whether it
// reads data, and how it runs (Image needs the textures and runs in ShaderProgram::run itself).
struct ShaderOpInfo {
  int inputs = 0;
  int modes = 0;
  bool data = false;
  OpValue (*run)(const ShaderOpContext&) = nullptr;
  // Whether its outputs are its input registers' values moved around (Channel, Combine): finite
  // already, so run() need not clamp them.
  bool copies = false;
};
ShaderOpInfo shader_op_info(ShaderOpcode op);

// What of ShaderGlobals beyond the hit's basics (UV, position, normals, view, path) a program
// reads (ShaderProgram::globals_read): shader_globals fills only these.
enum GlobalsRead : uint8_t {
  kReadsAttributes = 1,     // the corner attributes and instance constants (Attribute)
  kReadsTangent = 2,        // the UV tangent and bitangent sign (Tangent, Normal Map, Vector Displacement)
  kReadsCorners = 4,        // the triangle's corners (Wireframe)
  kReadsDifferentials = 8,  // the ray differentials (reads_differentials)
  kReadsSampleShift = 16,   // the path's sample shift (ops that trace several rays: Bevel)
  kReadsAll = 31,
};

class ShaderProgram {
 public:
  static constexpr int kMaxRegisters = 128;

  // Throws std::invalid_argument naming the problem unless every instruction's opcode, mode,
  // registers (inputs written before they are read, outputs past the constants), texture (below
  // num_textures) and table (within data) are valid and the constants and data are finite.
  ShaderProgram(std::vector<glm::vec4> constants, std::vector<ShaderInstruction> code, int registers,
                size_t num_textures, std::vector<float> data = {});

  int registers() const { return registers_; }
  // Whether register r holds a value after run() (a constant or an instruction's output).
  bool written(int r) const { return r >= 0 && r < registers_ && written_[size_t(r)]; }
  // Whether some instruction is of op.
  bool reads(ShaderOpcode op) const {
    for (const ShaderInstruction& ins : code_)
      if (ins.op == op) return true;
    return false;
  }
  // The resources (texture, grid ids) of op's instructions, in order.
  std::vector<int32_t> resources(ShaderOpcode op) const {
    std::vector<int32_t> out;
    for (const ShaderInstruction& ins : code_)
      if (ins.op == op) out.push_back(ins.resource);
    return out;
  }
  // Throws std::invalid_argument unless every VolumeGrid instruction names one of num_grids grids.
  void check_grids(size_t num_grids) const;
  // Whether some instruction traces local rays (Bevel, Ambient Occlusion's and Raycast's Only Local): the
  // scene then builds a BVH per object for ShaderTracer's local queries.
  bool local_queries() const { return local_queries_; }
  // Whether run() reads ShaderGlobals' ray differentials (dpdx, dpdy and what they move: a Bump
  // op, or instructions at the offset hits); without them the caller need not compute those.
  bool reads_differentials() const { return differentials_; }
  // GlobalsRead flags of what run() reads, found once from the code.
  uint8_t globals_read() const { return globals_read_; }
  // Runs the program; regs must hold registers() entries. Every value written is finite.
  void run(const ShaderGlobals& g, const std::vector<std::shared_ptr<const Texture>>& textures,
           glm::vec4* regs) const;

 private:
  // Checks a Bump instruction's Filter Width (after `earlier` Bumps) and keeps it.
  void check_bump_filter_width(const ShaderInstruction& ins, const std::string& where, int earlier);

  std::vector<glm::vec4> constants_;
  std::vector<ShaderInstruction> code_;
  std::vector<float> data_;
  int registers_;
  std::vector<bool> written_;
  bool offsets_ = false;  // some instruction reads the hit at an offset
  // How far the offset hits lie, in ray differentials: the Bump ops' Filter Width (their in6, a
  // constant, one for the program), 1 without Bumps.
  float bump_filter_width_ = 1.0f;
  bool differentials_ = false;
  bool local_queries_ = false;
  uint8_t globals_read_ = 0;

 public:
  // An instruction as run() runs it, found once at construction: how (Kind), its op's function
  // (kCall; nullptr for Image), its table (offset into data_ after the length, and the length) and
  // whether its output needs clamping to finite values.
  struct Step {
    // kCall: through run (an Image through its texture); kChannel, kCombine: moves of register
    // lanes (a Separate's channel, a Combine's three floats) done in run()'s loop itself, their
    // values their inputs' bits (finite already); kSeparateCombine: this Channel, the two
    // Channels after it and the Combine after those (a Separate feeding a Combine, as the
    // add-on compiles it) run as one step, the same four moves in the same order.
    enum Kind : uint8_t { kCall, kChannel, kCombine, kSeparateCombine };
    OpValue (*run)(const ShaderOpContext&) = nullptr;
    int32_t table = 0, table_size = 0;
    bool clamp = true;
    Kind kind = kCall;
  };

 private:
  std::vector<Step> steps_;
};

// Which registers of a material's program feed its inputs (-1: the material's own value). A
// float input reads the register's x.
struct ShaderOutputs {
  int program = -1;  // index from Scene::add_shader_program
  int16_t base_color = -1, metallic = -1, roughness = -1, emission = -1;
  int16_t normal = -1;  // the closure's Normal (facing the viewer, as Cycles' N): Bump, Normal Map
  int16_t alpha = -1;   // the material's alpha (x, clamped to [0, 1]): Scene::opacity
  // The surface's normal after the Material Output's Displacement (as bump: Cycles' sd->N, facing
  // the viewer), what the shadow terminator's smoothing compares the closure's Normal with.
  int16_t surface_normal = -1;
  // Principled v2's Transmission Weight (Material::transmission, x).
  int16_t transmission = -1;
  // The Principled BSDF's coat inputs (Material::coat_*): weight, roughness, IOR (x) and tint.
  int16_t coat_weight = -1, coat_roughness = -1, coat_ior = -1, coat_tint = -1;
  // The Principled BSDF's Clearcoat / Coat Normal where linked (facing the viewer, as normal).
  int16_t coat_normal = -1;
  // The Principled BSDF's sheen inputs (Material::sheen_*): weight, roughness (x) and tint (v1's
  // factor the x, v2's colour).
  int16_t sheen_weight = -1, sheen_roughness = -1, sheen_tint = -1;
  // Anisotropy (Material::anisotropy, anisotropic_rotation: x; tangent: a world direction).
  int16_t anisotropy = -1, anisotropic_rotation = -1, tangent = -1;
  // The subsurface inputs (Material::subsurface x, subsurface_radius and subsurface_color).
  int16_t subsurface = -1, subsurface_radius = -1, subsurface_color = -1;
  // Thin Film (Material::thin_film_thickness, thin_film_ior: x).
  int16_t thin_film_thickness = -1, thin_film_ior = -1;
  // Principled v2's dispersion, the inverse Abbe number (Material::dispersion: x, at least 0).
  int16_t dispersion = -1;
  // A colour read as Material::specular_tint_color (at least 0): Principled v2's Specular Tint, the
  // Metallic BSDF's Edge Tint (F82) or IOR (Physical Conductor).
  int16_t specular_tint_color = -1;
  // The Principled BSDF's specular (Material::specular, v1's units: at least 0; v2's computed from
  // its Specular IOR Level and IOR) and an IOR (Material::ior, clamped to [1e-5, 1000] as Cycles'
  // max(IOR, 1e-5)): the Principled's, the Glass and Refraction BSDFs'.
  int16_t specular = -1, ior = -1;
  // Principled v1's Specular Tint (Material::specular_tint: x, clamped to [0, 1]).
  int16_t specular_tint = -1;
  // Principled v2's Diffuse Roughness and the Toon BSDF's Smooth (Material::diffuse_roughness,
  // transmission_roughness: x, clamped to [0, 1]).
  int16_t diffuse_roughness = -1, transmission_roughness = -1;
  // The Ray Portal BSDF's linked Position and Direction (Material::portal_position, portal_direction).
  int16_t portal_position = -1, portal_direction = -1;
  bool any() const { return program >= 0; }
  // Every register above (-1: not read), for the checks of Scene::check_program_outputs.
  auto registers() const {
    return std::array{base_color, metallic, roughness, emission, normal, alpha, surface_normal, transmission,
                      coat_weight, coat_roughness, coat_ior, coat_tint, coat_normal, sheen_weight, sheen_roughness,
                      sheen_tint, anisotropy, anisotropic_rotation, tangent, subsurface, subsurface_radius,
                      subsurface_color, thin_film_thickness, thin_film_ior, dispersion, specular_tint_color, specular,
                      ior, specular_tint, diffuse_roughness, transmission_roughness, portal_position, portal_direction};
  }
};

}  // namespace torrance
