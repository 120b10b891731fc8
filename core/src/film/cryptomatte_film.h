// The film's Cryptomatte passes (torrance/film/cryptomatte.h): per pixel and enabled layer a
// table of (id, weight) slots that samples add into as Cycles' do, sorted and divided by the
// pixel's sample weight when the passes are read.
#pragma once

#include "torrance/film/cryptomatte.h"
#include "torrance/integrator/integrator.h"

#include <string>
#include <utility>
#include <vector>

namespace torrance {

class CryptomatteFilm {
 public:
  // pixels: the film's buffer of pixels (window and ring), indexed as the film indexes them.
  CryptomatteFilm(const Cryptomatte& cryptomatte, size_t pixels);

  // Sample s into pixel `pixel`'s tables, its weights times `weight` (the filter's, or 1).
  void add(size_t pixel, double weight, const CryptomatteSample& s);

  // The passes (pass_names() order) of a w x h window: pixel i of it is buffer pixel
  // pixels[i], its weights divided by norms[i].
  std::vector<std::pair<std::string, Image>> resolve(int w, int h, const std::vector<size_t>& pixels,
                                                     const std::vector<double>& norms) const;

 private:
  struct Slot {
    float id = 0.0f;  // 0: free (Cycles' ID_NONE; no id is 0)
    double weight = 0.0;
  };
  Slot* table(size_t pixel, int layer) { return &slots_[(pixel * layers_.size() + size_t(layer)) * slots_per_]; }
  const Slot* table(size_t pixel, int layer) const {
    return &slots_[(pixel * layers_.size() + size_t(layer)) * slots_per_];
  }

  const Cryptomatte& cryptomatte_;
  std::vector<Cryptomatte::Layer> layers_;  // the enabled ones, in pass order
  size_t slots_per_;
  std::vector<Slot> slots_;
};

}  // namespace torrance
