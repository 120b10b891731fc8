// Cryptomatte (Object, Material, Asset) as Cycles 3.4 writes it: at each surface a camera ray
// meets until it stops (through transparency, not past a fully held-out one) the pixel takes the
// ids of the surface's object, material and asset (the object's top-most parent) with the weight
// mean(throughput) x opacity; per pixel and layer a table of 2 x depth (id, weight) slots, an
// id's first sample claiming the first free slot and, when none is free, adding into the last
// (Cycles' film_write_cryptomatte_slots); at the end the slots sorted by weight, each weight
// divided by the pixel's (filter-weighted) samples, two slots to a pass: CryptoObject00 =
// (id0, coverage0, id1, coverage1), ... An id is the name's MurmurHash3 (x86, 32 bit, seed 0)
// as a float whose exponent is kept off 0 and 255 (the Cryptomatte specification).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace torrance {

// MurmurHash3_x86_32 of the bytes of `name` (Cryptomatte: seed 0).
uint32_t murmur_hash3(const std::string& name, uint32_t seed = 0);
// A hash as Cryptomatte's float id: its bits, the exponent clamped to [1, 254].
float cryptomatte_float(uint32_t hash);
inline float cryptomatte_id(const std::string& name) { return cryptomatte_float(murmur_hash3(name)); }

// The surfaces one camera sample gives ids to: object entry (Cryptomatte::set_objects, -1: none),
// material and weight of each, in order along the ray; past kMaxHits surfaces the weight goes to
// the last one.
struct CryptomatteSample {
  static constexpr int kMaxHits = 8;
  struct Hit {
    int32_t object;
    uint32_t material;
    float weight;
  };
  int count = 0;
  Hit hits[kMaxHits];
  void add(int32_t object, uint32_t material, float weight) {
    if (!(weight > 0.0f)) return;
    if (count == kMaxHits) {
      hits[kMaxHits - 1].weight += weight;
      return;
    }
    hits[count++] = {object, material, weight};
  }
};

class Cryptomatte {
 public:
  enum Layer { kObject = 0, kMaterial = 1, kAsset = 2 };
  static constexpr int kLayers = 3;
  static constexpr const char* kLayerNames[kLayers] = {"CryptoObject", "CryptoMaterial", "CryptoAsset"};

  // The view layer's Cryptomatte: which layers and its Levels (Cycles: min(levels, 16) rounded
  // up to even slots, two to a pass).
  void set_layers(bool object, bool material, bool asset, int levels);
  // Per object entry its object's and its asset's id; per material its id (0: none).
  void set_objects(std::vector<float> object_ids, std::vector<float> asset_ids);
  void set_materials(std::vector<float> material_ids) { material_ids_ = std::move(material_ids); }

  bool enabled() const { return layers_ != 0; }
  bool has(Layer layer) const { return layers_ & (1u << layer); }
  int passes_per_layer() const { return depth_; }
  int slots() const { return 2 * depth_; }
  // The pass names of the enabled layers, in order: CryptoObject00, ..., CryptoMaterial00, ...
  std::vector<std::string> pass_names() const;
  // The id of hit `h` in `layer` (0: none).
  float id(Layer layer, const CryptomatteSample::Hit& h) const {
    if (layer == kMaterial) return h.material < material_ids_.size() ? material_ids_[h.material] : 0.0f;
    if (h.object < 0 || size_t(h.object) >= object_ids_.size()) return 0.0f;
    return layer == kObject ? object_ids_[size_t(h.object)] : asset_ids_[size_t(h.object)];
  }
  size_t num_objects() const { return object_ids_.size(); }

 private:
  uint32_t layers_ = 0;
  int depth_ = 3;
  std::vector<float> object_ids_, asset_ids_, material_ids_;
};

}  // namespace torrance
