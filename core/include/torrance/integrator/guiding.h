// Path guiding learned during the render: an SD-tree in the style of Müller, Gross and Novák 2017,
// "Practical Path Guiding for Efficient Light-Transport Simulation". A binary tree over the scene's
// bounds (split at the midpoint, axes in turn) whose leaves each hold a quadtree over the sphere of
// directions, mapped to the unit square by the cylindrical (cos theta, phi) map. The quadtrees
// learn where incident radiance comes from: training passes record, at path vertices, the
// luminance of the radiance that arrived along the sampled direction divided by its pdf; between
// passes (refine) the recorded trees become the ones sampled, and fresh recording trees are built,
// subdivided where energy was found. The path tracer samples a one-sample mixture of the BSDF and
// the guide (guided_bsdf.h), so any guide -- a good, a poor or an empty one -- leaves the estimator
// unbiased; only its variance changes.
#pragma once

#include "torrance/util/fixed_point_sum.h"
#include "torrance/util/math.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace torrance {

// The cylindrical map between unit directions and [0,1)^2: (u, v) = ((cos theta + 1) / 2, phi / 2pi).
// It preserves area up to the factor 4pi, so a density on the square is 4pi x the solid-angle one.
Vec2 direction_to_square(const Vec3& dir);
Vec3 square_to_direction(const Vec2& p);

// A piecewise-constant density on [0,1)^2 as a quadtree of energies. Recording adds energy to the
// leaf cell holding a point (thread-safe, the structure fixed; in fixed point, so the sums do not
// depend on the threads' order); build_sums() then turns them into the nodes' energies, after
// which sample() and pdf() (a density on the square) may be used.
class DirectionalQuadtree {
 public:
  DirectionalQuadtree();  // the root's four quadrants, no energy
  void record(const Vec2& p, float energy);  // thread-safe; energy >= 0
  void build_sums();
  float total() const;
  // A point drawn from the density, and (pdf) its density, found on the way down. Requires total() > 0.
  Vec2 sample(Vec2 u, float* pdf = nullptr) const;
  float pdf(const Vec2& p) const;
  // The structure for the next training pass: a quadrant holding more than `fraction` of the total
  // energy is subdivided (down to max_depth levels, at most max_nodes nodes), others are leaves.
  // No energy.
  DirectionalQuadtree refined(float fraction, int max_depth, size_t max_nodes) const;
  size_t num_nodes() const { return nodes_.size(); }

 private:
  struct Node {
    std::array<float, 4> energy{};     // per quadrant: 0 = (low u, low v), 1 = (high u, low v), 2, 3
    std::array<uint32_t, 4> child{};  // 0: the quadrant is a leaf (node 0, the root, is no one's child)
  };
  uint32_t add_refined(const DirectionalQuadtree& old, uint32_t old_node, const std::array<float, 4>& energy,
                       float threshold, int depth, int max_depth, size_t max_nodes);
  // Energies: the relative-error weighted luminance over pdf is of the order of the pixel's value
  // over it, ~1 (guiding.cpp, pixel_weight); 2^24 resolves 3e-8 of it and sums up to 1e12.
  using EnergySum = FixedPointSum<24>;
  std::vector<Node> nodes_;
  std::vector<std::array<EnergySum, 4>> recorded_;  // per node while recording; empty once built
};

// The guide at one point: its learned distribution of directions, as a solid-angle density, and
// the probability with which the mixture (guided_bsdf.h) samples the BSDF instead; empty (false)
// where only the BSDF is sampled. Either way it knows its leaf of the SD-tree, so that recording
// at the point needs no second descent (GuidingField::record).
class GuideDistribution {
 public:
  GuideDistribution() = default;
  GuideDistribution(const DirectionalQuadtree* tree, float bsdf_fraction, uint32_t leaf)
      : tree_(tree), bsdf_fraction_(tree ? bsdf_fraction : 1.0f), leaf_(leaf) {}
  explicit operator bool() const { return tree_ != nullptr; }
  float bsdf_fraction() const { return bsdf_fraction_; }
  uint32_t leaf() const { return leaf_; }
  Vec3 sample(const Vec2& u) const { return square_to_direction(tree_->sample(u)); }
  // A direction, its point on the square and its solid-angle density, from one descent.
  Vec3 sample(const Vec2& u, Vec2& square, float& pdf) const {
    square = tree_->sample(u, &pdf);
    pdf *= 1.0f / (4.0f * kPi);
    return square_to_direction(square);
  }
  float pdf(const Vec3& dir) const { return pdf_of_square(direction_to_square(dir)); }
  float pdf_of_square(const Vec2& square) const { return tree_->pdf(square) * (1.0f / (4.0f * kPi)); }

 private:
  const DirectionalQuadtree* tree_ = nullptr;
  float bsdf_fraction_ = 1.0f;
  uint32_t leaf_ = 0;
};

// The BSDF fractions a leaf chooses among, after each training pass the one whose estimator would
// have had the least second moment (estimated from the pass's samples by reweighting them); 1 turns
// guiding off there. The first guided pass uses kInitialBsdfFraction: 0.7 rather than Müller et
// al.'s 0.5, which as a fixed fraction cost more where the guide is of little use (64 spp, 8
// seeds, relMSE guided / plain: suzanne 2.01 with 0.5, 1.64 with 0.7; water 0.90, 0.74) while
// keeping most of the gain where it pays (mirror 0.14, 0.17).
inline constexpr std::array<float, 5> kBsdfFractions = {0.3f, 0.5f, 0.7f, 0.9f, 1.0f};
inline constexpr float kInitialBsdfFraction = 0.7f;
static_assert(kBsdfFractions.back() == 1.0f, "the last candidate is BSDF sampling alone");

struct GuidingOptions {
  float spatial_threshold = 4000.0f;  // a leaf splits past threshold x sqrt(2^iteration) records
  float directional_fraction = 0.01f;  // a quadrant splits past this share of its leaf's energy
  int max_directional_depth = 20;
  size_t max_directional_nodes = 1024;  // per quadtree
  // Whether light reaching a vertex straight from an emitter (which next-event estimation also
  // samples) is learned too, or only light that has bounced at least once more. Learning it
  // paid on the comparison scenes (64 spp, 8 seeds, relMSE guided / plain: suzanne 1.64 -> 1.36,
  // water 0.74 -> 0.73, interior 0.92 -> 0.92): NEE of a sky or of large lights is far from ideal.
  bool learn_direct_light = true;
  size_t max_leaves = 2048;  // memory at most 2048 leaves x 2 trees x 1024 nodes x 32 B = 128 MiB
  // Guiding costs time at every vertex it touches (the tree's descent, the guide's pdf or sample
  // for the sampled direction, recording). After the training pass number decision_pass (0:
  // never) the render stops guiding and training altogether if the leaves' chosen fractions
  // promise to cut the second moment of their vertices' estimates (summed over the leaves that
  // estimated it) by less than min_predicted_saving. Earlier passes' guides are too young to
  // judge (the comparison scenes' guides that pay predict only 0.4 % after the second pass,
  // 5-67 % after the third).
  int decision_pass = 3;
  float min_predicted_saving = 0.02f;
};

// The SD-tree. During a pass sample/pdf (through at()) read the trees learned so far and record()
// writes the ones being trained, from any number of threads; refine() runs between passes.
class GuidingField {
 public:
  GuidingField(const Vec3& lo, const Vec3& hi, const GuidingOptions& options = {});
  // The learned distribution at p; empty before the first refine(), where nothing was recorded and
  // where the leaf's BSDF fraction is 1 -- except in training passes (`training`), where such a
  // leaf still samples only the BSDF but the guide's pdf is known, so its fraction can change.
  GuideDistribution at(const Vec3& p, bool training = false) const;
  // One path vertex: the luminance of the radiance that arrived along `dir`, over the pdf of `dir`,
  // and, where the guide was used (guide_pdf > 0), the vertex's estimate of its reflected light
  // (luminance) with the BSDF's and the guide's pdfs of dir, for choosing the BSDF fraction.
  void record(const Vec3& p, const Vec3& dir, float radiance_over_pdf, float estimate, float bsdf_pdf,
              float guide_pdf) {
    record(leaf_index(p), direction_to_square(dir), radiance_over_pdf, estimate, bsdf_pdf, guide_pdf);
  }
  // The same in a leaf known from at() (GuideDistribution::leaf()), dir as its point on the square.
  void record(uint32_t leaf, const Vec2& square, float radiance_over_pdf, float estimate, float bsdf_pdf,
              float guide_pdf);
  // The end of a training pass: recorded trees become sampled, new ones recorded. Returns whether
  // the guide is still worth its cost (see GuidingOptions::decision_pass); false: the render stops
  // guiding.
  bool refine();
  int iterations() const { return iterations_; }
  const GuidingOptions& options() const { return options_; }
  size_t num_leaves() const { return leaves_.size(); }

 private:
  struct SpatialNode {
    int32_t leaf = 0;             // >= 0: the index in leaves_; -1: inner node
    uint32_t first_child = 0;     // inner: children first_child, first_child + 1
    uint8_t axis = 0;             // inner: the split axis (at the midpoint)
  };
  struct Leaf {
    DirectionalQuadtree sampled, recording;
    bool trained = false;  // sampled holds a distribution
    uint32_t records = 0;  // this pass
    float bsdf_fraction = kInitialBsdfFraction;
    // This pass, per candidate fraction (squared estimates of ~1, as the energies; 2^16 resolves
    // 8e-6 and sums up to 3e14).
    std::array<FixedPointSum<16>, kBsdfFractions.size()> second_moment{};
    uint32_t moment_records = 0;
  };
  uint32_t leaf_index(const Vec3& p) const;
  void split(uint32_t node, const Vec3& lo, const Vec3& hi, uint32_t threshold);

  Vec3 lo_, hi_;
  GuidingOptions options_;
  std::vector<SpatialNode> nodes_;
  std::vector<Leaf> leaves_;
  int iterations_ = 0;
};

// What a path records is weighted by its pixel's relative-error weight: 1 / sqrt(Y^2 + 0.01), Y the
// luminance of the pixel's estimate so far (its mean over earlier passes; 0 before any), the
// weight relMSE = mean((I - R)^2 / (R^2 + 0.01)) gives the pixel's squared error. The guide then
// learns, and the BSDF fraction minimises, the relative error rather than the absolute one, which
// bright, simply lit pixels dominate (dark caustics lost their guiding to them).
inline float pixel_weight(const Vec3& pixel_mean) {
  const float y = luminance(pixel_mean);
  return 1.0f / std::sqrt(y * y + 0.01f);
}

// The vertices of one path while it is traced, for GuidingField::record: each gets every
// contribution found after it, and at the end (the destructor) records the radiance that reached it
// (contributions / the throughput after its own bounce). Unless the field learns direct light,
// what the last vertex's ray finds on an emitter (before reached_next_vertex) is left out for
// that vertex. Disabled (field null): does nothing.
// weight: the path's pixel_weight(), by which everything it records is multiplied.
class GuidePathRecorder {
 public:
  explicit GuidePathRecorder(GuidingField* field, float weight = 1.0f) : field_(field), weight_(weight) {}
  GuidePathRecorder(const GuidePathRecorder&) = delete;
  GuidePathRecorder& operator=(const GuidePathRecorder&) = delete;
  ~GuidePathRecorder() { flush(); }
  bool enabled() const { return field_ != nullptr; }
  // Before the throughput takes the bounce's weight; leaf: GuideDistribution::leaf() at the vertex,
  // square: the sampled direction on the square; pdf: the mixture's, bsdf_pdf and guide_pdf its
  // parts (guide_pdf 0 where no guide was used).
  void add_vertex(uint32_t leaf, const Vec2& square, const Vec3& throughput_before, const Vec3& weight, float pdf,
                  float bsdf_pdf, float guide_pdf) {
    if (count_ < kMaxVertices) {
      vertices_[count_++] = {throughput_before, throughput_before * weight, Vec3(0.0f), square, leaf, pdf, bsdf_pdf,
                             guide_pdf};
      direct_ = !field_->options().learn_direct_light;
    }
  }
  void reached_next_vertex() { direct_ = false; }
  void add_contribution(const Vec3& c) {
    for (int i = 0, n = direct_ ? count_ - 1 : count_; i < n; ++i) vertices_[i].radiance += c;
  }
  void flush();

 private:
  static constexpr int kMaxVertices = 16;
  struct Vertex {
    Vec3 throughput_before, throughput, radiance;
    Vec2 square;
    uint32_t leaf;
    float pdf, bsdf_pdf, guide_pdf;
  };
  GuidingField* field_;
  float weight_;
  int count_ = 0;
  bool direct_ = false;  // contributions now are emitters seen from the last vertex
  std::array<Vertex, kMaxVertices> vertices_;
};

}  // namespace torrance
