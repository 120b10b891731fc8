// Cryptomatte's ids (MurmurHash3 as the specification's float) and the film's slot tables.
#include "film/cryptomatte_film.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace torrance {

namespace {
uint32_t rotl32(uint32_t x, int r) { return (x << r) | (x >> (32 - r)); }
uint32_t scramble(uint32_t k) { return rotl32(k * 0xcc9e2d51u, 15) * 0x1b873593u; }
}  // namespace

uint32_t murmur_hash3(const std::string& name, uint32_t seed) {
  const auto* data = reinterpret_cast<const uint8_t*>(name.data());
  const size_t len = name.size(), blocks = len / 4;
  uint32_t h = seed;
  for (size_t i = 0; i < blocks; ++i) {  // little-endian 4-byte blocks
    const uint32_t k = uint32_t(data[4 * i]) | uint32_t(data[4 * i + 1]) << 8 | uint32_t(data[4 * i + 2]) << 16 |
                       uint32_t(data[4 * i + 3]) << 24;
    h = rotl32(h ^ scramble(k), 13) * 5u + 0xe6546b64u;
  }
  const uint8_t* tail = data + 4 * blocks;
  uint32_t k = 0;
  switch (len & 3u) {
    case 3: k ^= uint32_t(tail[2]) << 16; [[fallthrough]];
    case 2: k ^= uint32_t(tail[1]) << 8; [[fallthrough]];
    case 1: k ^= tail[0]; h ^= scramble(k);
  }
  h ^= uint32_t(len);
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  h *= 0xc2b2ae35u;
  h ^= h >> 16;
  return h;
}

float cryptomatte_float(uint32_t hash) {
  const uint32_t exponent = std::clamp<uint32_t>((hash >> 23) & 0xffu, 1u, 254u);
  const uint32_t bits = (hash & 0x807fffffu) | exponent << 23;
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

void Cryptomatte::set_layers(bool object, bool material, bool asset, int levels) {
  layers_ = (object ? 1u << kObject : 0u) | (material ? 1u << kMaterial : 0u) | (asset ? 1u << kAsset : 0u);
  depth_ = (std::clamp(levels, 1, 16) + 1) / 2;
}

void Cryptomatte::set_objects(std::vector<float> object_ids, std::vector<float> asset_ids) {
  asset_ids.resize(object_ids.size(), 0.0f);
  object_ids_ = std::move(object_ids);
  asset_ids_ = std::move(asset_ids);
}

std::vector<std::string> Cryptomatte::pass_names() const {
  std::vector<std::string> names;
  for (int layer = 0; layer < kLayers; ++layer) {
    if (!has(Layer(layer))) continue;
    for (int p = 0; p < depth_; ++p) {
      char suffix[12];  // any int
      std::snprintf(suffix, sizeof suffix, "%02d", p);
      names.push_back(std::string(kLayerNames[layer]) + suffix);
    }
  }
  return names;
}

CryptomatteFilm::CryptomatteFilm(const Cryptomatte& cryptomatte, size_t pixels)
    : cryptomatte_(cryptomatte), slots_per_(size_t(cryptomatte.slots())) {
  for (int layer = 0; layer < Cryptomatte::kLayers; ++layer)
    if (cryptomatte.has(Cryptomatte::Layer(layer))) layers_.push_back(Cryptomatte::Layer(layer));
  slots_.resize(pixels * layers_.size() * slots_per_);
}

void CryptomatteFilm::add(size_t pixel, double weight, const CryptomatteSample& s) {
  for (int i = 0; i < s.count; ++i) {
    const CryptomatteSample::Hit& hit = s.hits[i];
    const double w = weight * double(hit.weight);
    for (size_t l = 0; l < layers_.size(); ++l) {
      const float id = cryptomatte_.id(layers_[l], hit);
      if (id == 0.0f) continue;
      Slot* slot = table(pixel, int(l));
      for (size_t k = 0; k < slots_per_; ++k) {
        if (slot[k].id == 0.0f) slot[k].id = id;  // the first free slot: the id's now
        if (slot[k].id == id || k + 1 == slots_per_) {  // its slot, or the last one
          slot[k].weight += w;
          break;
        }
      }
    }
  }
}

std::vector<std::pair<std::string, Image>> CryptomatteFilm::resolve(int w, int h, const std::vector<size_t>& pixels,
                                                                    const std::vector<double>& norms) const {
  const std::vector<std::string> names = cryptomatte_.pass_names();
  std::vector<std::pair<std::string, Image>> out;
  const size_t n = size_t(w) * size_t(h);
  for (const std::string& name : names) out.emplace_back(name, Image{w, h, std::vector<float>(n * 4, 0.0f), 4});
  const size_t passes = size_t(cryptomatte_.passes_per_layer());
  std::vector<Slot> sorted(slots_per_);
  for (size_t l = 0; l < layers_.size(); ++l)
    for (size_t i = 0; i < n; ++i) {
      const Slot* slot = table(pixels[i], int(l));
      std::copy(slot, slot + slots_per_, sorted.begin());
      // By weight, heaviest first (stable: ties keep the order the ids came in, as Cycles').
      std::stable_sort(sorted.begin(), sorted.end(), [](const Slot& a, const Slot& b) { return a.weight > b.weight; });
      const double inv = norms[i] > 0.0 ? 1.0 / norms[i] : 0.0;
      for (size_t k = 0; k < slots_per_; ++k) {
        if (sorted[k].id == 0.0f) break;
        float* px = &out[l * passes + k / 2].second.rgba[i * 4 + 2 * (k % 2)];
        px[0] = sorted[k].id;
        px[1] = float(sorted[k].weight * inv);
      }
    }
  return out;
}

}  // namespace torrance
