// Efficiency-aware Russian roulette: a path continues from a vertex with the probability that
// makes the image's error x time smallest, learned during the render -- the roulette half of
// Rath et al. 2022, "EARS: Efficiency-Aware Russian Roulette and Splitting".
//
// Why: a sample's error and cost split by vertex. Continuing from vertex i (throughput T, its
// luminance t) brings a contribution t Y to the pixel and costs C rays. Continuing with
// probability q (weight 1/q) changes the pixel's variance per sample by t^2 E[Y^2] (1/q - 1) and
// its cost by C (q - 1). The image's relative error (mean over pixels of Var_p / (I_p^2 + eps))
// times its cost is smallest, to first order, for
//
//     q = t sqrt(E[Y^2] / E[C]) / sqrt(I_p^2 + eps) x sqrt(c / v),
//
// where I_p is the pixel's value, v the image's relative variance per sample and c its cost per
// sample (rays). Where the continuation carries little light for its cost (a sun-lit diffuse
// scene: its indirect light is a few per cent of the image and of its error) q is small and most
// paths stop after their first vertex; where it carries the error (caustics, a room lit
// indirectly) q reaches 1 and nothing changes. Any q > 0 keeps the estimator unbiased: only the
// variance and the time change. The path tracer uses it as a cap on the classic rule's
// probability (1 before the fifth vertex): it only ever stops more paths.
//
// What is learned, from every sample of the passes so far: per block of kBlock x kBlock pixels
// and depth slot (0, 1, 2, and 3 or more), E[Y^2] (at least the image's at that depth: a block's
// few samples of a heavy tail often hold none of it) and E[C] of continuations, Y measured as the
// luminance the continuation brought divided by t and multiplied by the q it survived (the
// un-rouletted value); per pixel, the sum and sum of squares of its samples' luminance and their
// cost (rays). update() turns them into the survival factors of the next samples, once pixels have
// kFirstSamples samples (the relative variance of fewer, divided by their own noisy mean, is far
// too high, and would make the roulette kill paths whose extra variance then confirms it). It
// runs when every pixel has the same number of samples (the integrator calls it at sample counts
// 1, 3, 7, 15, ..., where its first passes end), so the decisions depend on the sample index,
// never on timing or threads.
#pragma once

#include "torrance/util/math.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace torrance {

class RouletteField {
 public:
  static constexpr int kBlock = 4;   // pixels per side of a block of statistics
  static constexpr int kDepths = 4;  // depth slots 0, 1, 2 and 3+
  static constexpr float kEpsilon = 0.01f;  // of the relative error, as relMSE's (I^2 + 0.01)
  static constexpr uint32_t kFirstSamples = 4;  // per pixel, before anything is decided
  // The learned q is doubled: second moments of heavy-tailed contributions learned from finite
  // samples come out low, and stopping too many paths costs more than stopping too few (on the
  // comparison scenes, factor 1 lost 34-39 % of efficiency on glossy_chain and many_lights,
  // factor 2 nothing measurable, keeping most of the gains).
  static constexpr float kSafety = 2.0f;

  // width x height: the rendered window; min_survival: the smallest q ever used (a bound on the
  // 1/q a contribution can be scaled by, should the learned statistics underrate it).
  RouletteField(int width, int height, float min_survival);

  // The learned statistics so far become the factors that survival() uses.
  void update();

  // The probability to continue a path from a vertex at `depth` with throughput luminance t in the
  // pixel (x, y); < 0 where nothing is learned yet. The pixel's value is the mean of the
  // luminance its samples brought (recorded here, not the film's: that one's sums round
  // differently when light passes split them, and would move decisions with it).
  float survival(int x, int y, int depth, float t) const {
    const float scale = scale_[slot(x, y, depth)];
    const PixelStats& p = pixels_[size_t(y) * size_t(width_) + size_t(x)];
    if (!(scale >= 0.0f) || p.samples == 0) return -1.0f;
    const float pixel_value = float(p.sum / p.samples);
    const float q = t * scale / std::sqrt(pixel_value * pixel_value + kEpsilon);
    return std::clamp(q, min_survival_, 1.0f);
  }

  // What one camera sample learned (RoulettePath, one thread per block during a pass).
  void record_continuation(int x, int y, int depth, float y_squared, float cost) {
    Slot& s = slots_[slot(x, y, depth)];
    s.y_squared += y_squared;
    s.cost += cost;
    s.count += 1;
  }
  void record_sample(int x, int y, float value, float cost) {
    PixelStats& p = pixels_[size_t(y) * size_t(width_) + size_t(x)];
    p.sum += value;
    p.sum_squares += double(value) * value;
    p.samples += 1;
    p.cost += cost;
  }
  // The image's relative variance and cost per sample at the last update (0 before).
  float relative_variance() const { return relative_variance_; }
  float cost_per_sample() const { return cost_per_sample_; }

 private:
  struct Slot {
    double y_squared = 0.0, cost = 0.0;
    uint32_t count = 0;
  };
  struct PixelStats {
    double sum = 0.0, sum_squares = 0.0;  // of the samples' luminance
    float cost = 0.0f;                    // their rays (at most 17 a sample: exact up to 2^24 / 17 samples)
    uint32_t samples = 0;
  };
  size_t block(int x, int y) const { return size_t(y / kBlock) * blocks_x_ + size_t(x / kBlock); }
  size_t slot(int x, int y, int depth) const { return block(x, y) * kDepths + size_t(std::min(depth, kDepths - 1)); }

  int width_, blocks_x_;
  float min_survival_;
  std::vector<Slot> slots_;   // cumulative over the render
  std::vector<PixelStats> pixels_;
  std::vector<float> scale_;  // per slot: sqrt(E[Y^2] / E[C] x c / v); -1: not known
  float relative_variance_ = 0.0f, cost_per_sample_ = 0.0f;
};

// One camera sample's roulette: decides at each vertex, and on destruction records what each
// continuation brought and cost. It reads the path's luminance so far from `luminance`, which the
// path tracer keeps up to date contribution by contribution (the same sums whether or not light
// passes split them: decisions compare with random numbers, so rounding must not move them).
class RoulettePath {
 public:
  // field null: learns and decides nothing. Cost is counted in path segments: the camera ray and
  // one per continuation (each with its vertex's shading and light sample).
  RoulettePath(RouletteField* field, const float& luminance, int x, int y)
      : field_(field), luminance_(luminance), x_(x), y_(y) {}
  RoulettePath(const RoulettePath&) = delete;
  RoulettePath& operator=(const RoulettePath&) = delete;
  ~RoulettePath() {
    if (field_) flush();
  }

  // The survival probability at this vertex (t: the throughput's luminance after the bounce's
  // weight), or < 0 where the field knows nothing (the caller's own rule applies).
  float survival(int depth, float t) const { return field_ ? field_->survival(x_, y_, depth, t) : -1.0f; }
  // The path goes on from this vertex, having survived with probability q.
  void continued(int depth, float q, float t) {
    if (!field_) return;
    if (branch_ended_) {
      ++later_branch_segments_;
      return;
    }
    if (count_ >= kMaxVertices || !(t > 0.0f)) return;
    vertices_[count_++] = {depth, q / t, luminance_};
  }
  // The path goes back to its first vertex for another branch (RenderSettings::
  // first_bounce_splits): the vertices recorded so far learn from the light of their own branch;
  // the later branches add to the sample's value and cost only.
  void end_branch() {
    if (branch_ended_) return;
    branch_ended_ = true;
    branch_value_ = luminance_;
  }

 private:
  static constexpr int kMaxVertices = 16;
  struct Vertex {
    int depth;
    float q_over_t;
    float value_before;
  };
  void flush() {
    const float value = luminance_;
    const float branch_value = branch_ended_ ? branch_value_ : value;
    if (!std::isfinite(value)) return;
    for (int i = 0; i < count_; ++i) {
      const Vertex& v = vertices_[i];
      const float y = (branch_value - v.value_before) * v.q_over_t;
      field_->record_continuation(x_, y_, v.depth, y * y, float(count_ - i));
    }
    field_->record_sample(x_, y_, value, float(count_ + 1 + later_branch_segments_));
  }

  RouletteField* field_;
  const float& luminance_;
  int x_, y_;
  int count_ = 0;
  Vertex vertices_[kMaxVertices];
  bool branch_ended_ = false;
  float branch_value_ = 0.0f;
  int later_branch_segments_ = 0;
};

}  // namespace torrance
