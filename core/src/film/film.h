// The film of render() (integrator.cpp): per-pixel sums of the samples of Combined and the
// requested passes, sample counts, and adaptive sampling's per-pixel convergence.
#pragma once

#include "film/cryptomatte_film.h"
#include "film/film_passes.h"
#include "film/shadow_catcher.h"
#include "integrator/path_tracer.h"

#include "torrance/util/sampling.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <vector>

namespace torrance {

// Adaptive sampling's split of a pixel's samples into two halves (Christensen et al. 2018,
// "Progressive Multi-Jittered Sample Sequences", 10.2.1, as Cycles 3.4): a sample is in class A
// when its index has an odd number of set odd bits, so every aligned group of 4 samples gives 2.
inline bool sample_is_class_a(uint32_t sample) { return __builtin_popcount(sample & 0xaaaaaaaau) & 1; }

// Per-pixel accumulation of sums for Combined (RGBA) and the requested passes, and sample counts,
// for a window of the frame. The passes of kFirstSamplePasses (the last of kPasses) hold the value
// of the pixel's sample 0 instead, unfiltered (Cycles' Position and Index passes). Two ways in:
// - add(): a sample drawn by the filter's importance (Cycles' way) counts once in its own pixel,
//   which is the mean of its samples. With adaptive sampling also twice the sum of the class-A
//   samples' RGB (an estimate of the pixel from half of its samples) and whether it converged.
// - splat() (a film made with a splatting filter): a sample anywhere in its pixel adds into every
//   pixel of the window whose filter covers it, weighted by the filter there; a pixel is the
//   weighted mean (the ratio of its weighted sums to its summed weights: consistent, and exact on
//   flat regions at any sample count). Samples of a ring of margin() pixels around the window
//   reach its edge pixels; their counts are kept (the work done) but they are not pixels of it.
//   With adaptive sampling (a reach of 1 pixel) a pixel takes splats only in the steps in which
//   its whole 3 x 3 neighbourhood is sampled, so each of its steps sees its neighbourhood evenly
//   sampled and its weighted mean stays consistent while the neighbours stop one by one.
class Film {
 public:
  // extra: the scene's AOV and light-group passes (extra_passes.h), summed like the image;
  // cryptomatte: the scene's Cryptomatte layers (none when null or not enabled); catcher: the
  // shadow catcher's outputs (film/shadow_catcher.h; none when null).
  Film(int w, int h, uint32_t passes, bool adaptive, const PixelFilter* splatting = nullptr,
       std::vector<ExtraPass> extra = {}, const Cryptomatte* cryptomatte = nullptr,
       const ShadowCatcherOutput* catcher = nullptr)
      : width_(w),
        height_(h),
        passes_(passes),
        adaptive_(adaptive),
        splatting_(splatting),
        margin_(splatting ? splatting->reach() : 0),
        extra_(std::move(extra)) {
    for (const ExtraPass& e : extra_) extra_channels_ += e.channels;
    if (catcher) catcher_ = *catcher;
    if (catcher_ && catcher_->catchers) catcher_channels_ = kShadowCatcherChannels;
    if (margin_ > kMaxReach) throw std::logic_error("Film: a splat reaches 2 pixels beyond its own at most");
    if (adaptive && margin_ > 1) throw std::logic_error("Film: adaptive sampling splats 1 pixel far at most");
    accumulated_ = passes | pass_dependencies(passes);
    stride_ = 4 + extra_channels_ + catcher_channels_;
    filtered_ = -1;
    for (const PassInfo& p : kPasses) {
      if (!(accumulated_ & p.pass)) continue;
      if ((p.pass & kFirstSamplePasses) && filtered_ < 0) filtered_ = stride_;
      if (!(p.pass & kFirstSamplePasses) && filtered_ >= 0)
        throw std::logic_error("Film: the first-sample passes must come last in kPasses");
      stride_ += p.channels;
      accumulated_list_.push_back(p);
    }
    values_ = stride_;
    if (filtered_ < 0) filtered_ = values_;
    if (values_ > int(kMaxValues)) throw std::logic_error("Film: more channels than a sample holds");
    if (splatting_) stride_ += 1;  // the sum of the filter weights
    stride_ += 1;                  // the sample count
    norm_slot_ = splatting_ ? stride_ - 2 : stride_ - 1;
    buffer_width_ = w + 2 * margin_;
    sums_.assign(size_t(buffer_width_) * (h + 2 * margin_) * stride_, 0.0);
    if (cryptomatte && cryptomatte->enabled())
      cryptomatte_.emplace(*cryptomatte, size_t(buffer_width_) * (h + 2 * margin_));
    if (adaptive_) {
      const size_t pixels = size_t(buffer_width_) * (h + 2 * margin_);
      half_stride_ = splatting_ ? 4 : 3;
      half_.assign(pixels * half_stride_, 0.0);
      sampled_.assign(pixels, 1);
      if (splatting_) receiving_.assign(pixels, 1);
    }
  }

  // Pixels beyond each side of the window whose samples reach it (0 without splatting).
  int margin() const { return margin_; }

  // Whether pixel (x, y) (in the window or its ring) is left out of the next samples.
  bool converged(int x, int y) const { return adaptive_ && !sampled_[index(x, y)]; }
  // The pixel's combined colour so far (0 before any sample).
  Vec3 mean(int x, int y) const {
    const double* acc = at(x, y);
    const double norm = acc[norm_slot_];
    return norm > 0.0 ? Vec3(float(acc[0] / norm), float(acc[1] / norm), float(acc[2] / norm)) : Vec3(0.0f);
  }

  // The convergence test of every pixel still sampled (Cycles' film_adaptive_sampling_convergence_check,
  // the per-pixel error of Dammertz et al. 2010, "A hierarchical automatic stopping condition for
  // Monte Carlo global illumination": |I - A| / sqrt(I) over the RGB of the mean of all samples I
  // and of the class-A half A), then every unconverged pixel keeps its 3x3 neighbourhood (the
  // ring's pixels too) sampling. Returns the number of the window's pixels still sampled.
  size_t update_convergence(float threshold) {
    const int bw = buffer_width_, bh = height_ + 2 * margin_;
    std::vector<uint8_t> unconverged(size_t(bw) * bh, 0), dilated(size_t(bw) * bh, 0);
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        if (sampled_[index(x, y)]) unconverged[index(x, y)] = !passes_convergence_test(x, y, threshold);
    // Dilate the unconverged set by one pixel in x, then in y.
    for (int y = 0; y < bh; ++y)
      for (int x = 0; x < bw; ++x) {
        const size_t i = size_t(y) * bw + x;
        dilated[i] = unconverged[i] | (x > 0 && unconverged[i - 1]) | (x + 1 < bw && unconverged[i + 1]);
      }
    for (int y = 0; y < bh; ++y)
      for (int x = 0; x < bw; ++x) {
        const size_t i = size_t(y) * bw + x;
        sampled_[i] = dilated[i] | (y > 0 && dilated[i - bw]) | (y + 1 < bh && dilated[i + bw]);
      }
    size_t remaining = 0;
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        remaining += sampled_[index(x, y)];
        if (!splatting_) continue;
        bool all = true;  // the whole 3 x 3 neighbourhood sampled (it lies in the window and ring)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) all = all && sampled_[index(x + dx, y + dy)];
        receiving_[index(x, y)] = all;
      }
    return remaining;
  }

  // A sample of pixel (x, y) of the window, drawn by the filter's importance.
  void add(int x, int y, const PathRadiance& r, uint32_t sample) {
    double* acc = at(x, y);
    const Values v = values(r);
    if (adaptive_ && sample_is_class_a(sample)) {
      double* a = &half_[index(x, y) * half_stride_];
      a[0] += 2.0 * v[0];
      a[1] += 2.0 * v[1];
      a[2] += 2.0 * v[2];
    }
    for (int c = 0; c < filtered_; ++c) acc[c] += v[size_t(c)];
    if (cryptomatte_) cryptomatte_->add(index(x, y), 1.0, r.cryptomatte);
    if (sample == 0) keep_first_sample(acc, v);
    acc[stride_ - 1] += 1.0;
  }

  // A sample at `offset` (each coordinate in [-1/2, 1/2)) from the centre of pixel (x, y), which
  // is in the window or within margin() of it; only a film made with a splatting filter.
  void splat(int x, int y, const Vec2& offset, const PathRadiance& r, uint32_t sample) {
    // The filter's rows and columns that reach the window or its ring with a weight, and the
    // sample's channels as doubles, found once: the taps' loop below then only sums (checking,
    // indexing and converting per tap made splat() 11.5 % of the water scene's render).
    Taps columns, rows;
    for (int k = -margin_; k <= margin_; ++k) {
      columns.add(x + k >= 0 && x + k < width_, size_t(x + k + margin_), splatting_->weight(offset.x - float(k)));
      rows.add(y + k >= 0 && y + k < height_, size_t(y + k + margin_) * size_t(buffer_width_),
               splatting_->weight(offset.y - float(k)));
    }
    const Values v = values(r);
    std::array<double, kMaxValues> dv;
    for (int c = 0; c < filtered_; ++c) dv[size_t(c)] = v[size_t(c)];
    if (filtered_ == 4) splat_taps<4>(columns, rows, dv, r, sample);  // Combined RGBA only
    else splat_taps<0>(columns, rows, dv, r, sample);
    if (sample == 0) keep_first_sample(at(x, y), v);
    at(x, y)[stride_ - 1] += 1.0;
  }

  Image resolve_combined() const { return catcher_channels_ ? resolve_catcher(true) : resolve(0, 4); }

  // The samples taken in each pixel of the window.
  Image sample_counts() const {
    Image img{width_, height_, std::vector<float>(size_t(width_) * height_, 0.0f), 1};
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) img.rgba[size_t(y) * width_ + x] = float(at(x, y)[stride_ - 1]);
    return img;
  }
  // Every sample taken, the ring's included.
  uint64_t total_samples() const {
    double total = 0.0;
    for (size_t i = 0, n = sums_.size() / size_t(stride_); i < n; ++i) total += sums_[i * stride_ + stride_ - 1];
    return uint64_t(total);
  }

  // The requested passes as Blender shows them (film_passes.h: finish_pass).
  std::vector<std::pair<std::string, Image>> resolve_passes() const {
    std::vector<std::pair<std::string, Image>> out;
    std::vector<std::pair<Pass, Image>> resolved;
    int k = 4 + extra_channels_ + catcher_channels_;
    for (const PassInfo& p : accumulated_list_) {
      resolved.emplace_back(p.pass, (p.pass & kFirstSamplePasses) ? copy(k, p.channels) : resolve(k, p.channels));
      k += p.channels;
    }
    for (const PassInfo& p : kPasses)
      if (passes_ & p.pass) out.emplace_back(p.name, finish_pass(p.pass, resolved));
    k = 4;
    for (const ExtraPass& e : extra_) {
      out.emplace_back(e.name, resolve(k, e.channels));
      k += e.channels;
    }
    if (catcher_ && catcher_->pass) out.emplace_back("Shadow Catcher", resolve_catcher(false));
    if (cryptomatte_) {
      std::vector<size_t> pixels;
      std::vector<double> norms;
      for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
          pixels.push_back(index(x, y));
          norms.push_back(at(x, y)[norm_slot_]);
        }
      for (auto& pass : cryptomatte_->resolve(width_, height_, pixels, norms))
        out.emplace_back("cryptomatte:" + pass.first, std::move(pass.second));
    }
    return out;
  }

 private:
  static constexpr int kMaxReach = 2;  // pixels beyond its own that a splat may reach
  static constexpr size_t kMaxValues = 128;
  using Values = std::array<float, kMaxValues>;
  // A sample's values in the film's channel order: Combined RGBA, then the requested passes.
  Values values(const PathRadiance& r) const {
    Values v;
    const Vec3 c = r.combined();
    v[0] = c.r;
    v[1] = c.g;
    v[2] = c.b;
    v[3] = r.alpha;
    for (int c = 0; c < extra_channels_; ++c) v[size_t(4 + c)] = r.extras[c];
    if (catcher_channels_) {
      const ShadowCatcherValues sc = shadow_catcher_values(r.catcher, c, r.alpha, r.environment);
      std::copy(sc.begin(), sc.end(), v.begin() + 4 + extra_channels_);
    }
    size_t k = size_t(4 + extra_channels_ + catcher_channels_);
    for (const PassInfo& p : accumulated_list_) {
      if (p.channels == 1) {
        v[k++] = pass_scalar(p.pass, r);
      } else if (p.channels == 4) {
        const glm::vec4 q = pass_quad(p.pass, r);
        for (int c = 0; c < 4; ++c) v[k++] = q[c];
      } else {
        const Vec3 pv = pass_color(p.pass, r);
        v[k++] = pv.x;
        v[k++] = pv.y;
        v[k++] = pv.z;
      }
    }
    return v;
  }
  // A splat's pixels along one axis: those in the window or its ring with a weight above 0, each
  // as its part of the pixel's index (index()), and its weight.
  struct Taps {
    std::array<size_t, 2 * kMaxReach + 1> part;
    std::array<double, 2 * kMaxReach + 1> weight;
    int n = 0;
    void add(bool inside, size_t index_part, float w) {
      if (!inside || !(w > 0.0f)) return;
      part[size_t(n)] = index_part;
      weight[size_t(n++)] = w;
    }
  };
  // splat()'s sums into each tap, in the same order as a tap at a time (the same doubles):
  // kChannels of them summed (0: filtered_). The members it reads are copied first, as the
  // compiler would reload them after each sum otherwise.
  template <int kChannels>
  void splat_taps(const Taps& columns, const Taps& rows, const std::array<double, kMaxValues>& v,
                  const PathRadiance& r, uint32_t sample) {
    const bool class_a = adaptive_ && sample_is_class_a(sample);
    const int channels = kChannels > 0 ? kChannels : filtered_;
    const size_t stride = size_t(stride_), norm_slot = size_t(norm_slot_);
    double* const sums = sums_.data();
    const bool adaptive = adaptive_, cryptomatte = cryptomatte_.has_value();
    for (int j = 0; j < rows.n; ++j) {
      for (int i = 0; i < columns.n; ++i) {
        const size_t pixel = rows.part[size_t(j)] + columns.part[size_t(i)];
        if (adaptive && !receiving_[pixel]) continue;
        const double w = columns.weight[size_t(i)] * rows.weight[size_t(j)];
        double* acc = sums + pixel * stride;
        for (int c = 0; c < channels; ++c) acc[c] += w * v[size_t(c)];
        acc[norm_slot] += w;
        if (cryptomatte) cryptomatte_->add(pixel, w, r.cryptomatte);
        if (class_a) {
          double* a = &half_[pixel * half_stride_];
          for (int c = 0; c < 3; ++c) a[c] += w * v[size_t(c)];
          a[3] += w;
        }
      }
    }
  }

  // Pixel (x, y) of the window (or its ring) in the buffers.
  size_t index(int x, int y) const { return size_t(y + margin_) * buffer_width_ + size_t(x + margin_); }
  double* at(int x, int y) { return &sums_[index(x, y) * stride_]; }
  const double* at(int x, int y) const { return &sums_[index(x, y) * stride_]; }
  // Whether the mean of pixel (x, y) and that of its class-A half are close enough.
  bool passes_convergence_test(int x, int y, float threshold) const {
    const double* acc = at(x, y);
    const double* a = &half_[index(x, y) * half_stride_];
    double difference, normalize;
    if (splatting_) {  // weighted means of all samples and of the class-A ones
      if (!(acc[norm_slot_] > 0.0 && a[3] > 0.0)) return false;
      const double inv_all = 1.0 / acc[norm_slot_], inv_half = 1.0 / a[3];
      difference = std::abs(acc[0] * inv_all - a[0] * inv_half) + std::abs(acc[1] * inv_all - a[1] * inv_half) +
                   std::abs(acc[2] * inv_all - a[2] * inv_half);
      normalize = std::sqrt(std::max(acc[0] + acc[1] + acc[2], 0.0) * inv_all);
    } else {  // the sums of all samples and twice the class-A sums, per sample
      const double inv_count = 1.0 / std::max(acc[stride_ - 1], 1.0);
      difference = (std::abs(acc[0] - a[0]) + std::abs(acc[1] - a[1]) + std::abs(acc[2] - a[2])) * inv_count;
      normalize = std::sqrt(std::max(acc[0] + acc[1] + acc[2], 0.0) * inv_count);
    }
    return difference / (1e-4 + normalize) < threshold;  // the epsilon: the floor of black pixels
  }
  // The first-sample passes' channels of sample 0's values v, kept as they are.
  void keep_first_sample(double* acc, const Values& v) const {
    for (int c = filtered_; c < values_; ++c) acc[c] = v[size_t(c)];
  }
  // A pass's channels as stored (the first-sample passes).
  Image copy(int offset, int channels) const {
    Image img{width_, height_, std::vector<float>(size_t(width_) * height_ * channels, 0.0f), channels};
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x)
        for (int c = 0; c < channels; ++c)
          img.rgba[(size_t(y) * width_ + x) * channels + c] = float(at(x, y)[offset + c]);
    return img;
  }
  // With shadow catchers: Combined (RGBA) as Cycles shows it, or the Shadow Catcher pass (RGB;
  // 1 without catchers), from the pixel's means.
  Image resolve_catcher(bool combined) const {
    const int channels = combined ? 4 : 3;
    Image img{width_, height_, std::vector<float>(size_t(width_) * height_ * channels, 1.0f), channels};
    if (!catcher_channels_) return img;
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        const double* acc = at(x, y);
        const double norm = acc[norm_slot_];
        float* px = &img.rgba[(size_t(y) * width_ + x) * channels];
        if (!(norm > 0)) {
          std::fill_n(px, channels, combined ? 0.0f : 1.0f);
          continue;
        }
        std::array<double, 4> mean_combined;
        std::array<double, kShadowCatcherChannels> mean_catcher;
        for (int c = 0; c < 4; ++c) mean_combined[size_t(c)] = acc[c] / norm;
        for (int c = 0; c < kShadowCatcherChannels; ++c)
          mean_catcher[size_t(c)] = acc[4 + extra_channels_ + c] / norm;
        if (combined) {
          const std::array<float, 4> rgba =
              shadow_catcher_combined(*catcher_, mean_combined.data(), mean_catcher.data());
          std::copy(rgba.begin(), rgba.end(), px);
        } else {
          const Vec3 ratio = shadow_catcher_pass(mean_combined.data(), mean_catcher.data());
          for (int c = 0; c < 3; ++c) px[c] = ratio[c];
        }
      }
    return img;
  }
  Image resolve(int offset, int channels) const {
    Image img{width_, height_, std::vector<float>(size_t(width_) * height_ * channels, 0.0f), channels};
    for (int y = 0; y < height_; ++y)
      for (int x = 0; x < width_; ++x) {
        const size_t i = size_t(y) * width_ + x;
        const double* acc = at(x, y);
        const double norm = acc[norm_slot_];
        if (norm > 0)
          for (int c = 0; c < channels; ++c) img.rgba[i * channels + c] = float(acc[offset + c] / norm);
      }
    return img;
  }

  int width_, height_;
  uint32_t passes_;
  uint32_t accumulated_;  // passes_ and what they need (the colours the light passes are divided by)
  std::vector<PassInfo> accumulated_list_;  // their PassInfos in kPasses order (each sample's loop)
  bool adaptive_;
  const PixelFilter* splatting_;  // null: samples drawn by the filter's importance
  int margin_;
  std::vector<ExtraPass> extra_;
  int extra_channels_ = 0;
  std::optional<ShadowCatcherOutput> catcher_;
  int catcher_channels_ = 0;  // kShadowCatcherChannels with catchers, after the extra channels
  int buffer_width_;
  int values_;     // channels of a sample: Combined RGBA and the passes
  int filtered_;   // the channels before it are summed; from it on, the first-sample passes
  int norm_slot_;  // what a pixel's sums are divided by: its weight sum, or its sample count
  int stride_;
  std::vector<double> sums_;
  // Adaptive sampling: the class-A samples' RGB sums (2 x; splatting: weighted, and their weight
  // sum), whether a pixel is sampled in the next step, and (splatting) whether it takes splats.
  int half_stride_ = 3;
  std::vector<double> half_;
  std::vector<uint8_t> sampled_, receiving_;
  std::optional<CryptomatteFilm> cryptomatte_;
};

}  // namespace torrance
