// The scene's volumes: a homogeneous medium inside the closed meshes of a material (its Material
// Output's Volume) and around everything (the World's Volume). A material with a volume but no
// surface shader is a pass-through boundary (as Cycles renders a material with only a Volume
// output): paths and shadow rays cross it without a bounce, entering or leaving its medium.
#pragma once

#include "torrance/media/homogeneous_medium.h"
#include "torrance/media/varying_medium.h"

#include <cstdint>
#include <vector>

namespace torrance {

class SceneMedia {
 public:
  // Throws std::invalid_argument for a negative or non-finite coefficient or |g| > 1.
  static void check(const HomogeneousMedium& medium);
  void set_material(uint32_t material, const HomogeneousMedium& medium, bool pass_through);
  void set_world(const HomogeneousMedium& medium);
  // A heterogeneous medium inside material's meshes (checked and its majorant set by Scene).
  void set_material(uint32_t material, const VaryingMedium& medium, bool pass_through);

  bool any() const { return !media_.empty(); }
  // The medium id of material's volume, or -1.
  int32_t of(uint32_t material) const { return material < id_of_material_.size() ? id_of_material_[material] : -1; }
  bool pass_through(uint32_t material) const {
    return material < pass_through_.size() && pass_through_[material] != 0;
  }
  int32_t world() const { return world_; }  // -1: none
  const HomogeneousMedium& medium(int32_t id) const { return media_[size_t(id)]; }
  // The index (for varying()) of medium id's heterogeneous medium, or -1 (homogeneous).
  int32_t varying_index(int32_t id) const { return size_t(id) < varying_of_.size() ? varying_of_[size_t(id)] : -1; }
  const VaryingMedium& varying(int32_t index) const { return varying_[size_t(index)]; }
  bool any_varying() const { return !varying_.empty(); }
  // Some homogeneous medium scatters and asks for equiangular sampling (its Volume Sampling is
  // not Distance): paths through media then choose a light to aim at (media/medium_walk.h).
  bool aims() const { return aims_; }

 private:
  int32_t id_for(uint32_t material, bool pass_through);
  void note_sampling(const HomogeneousMedium& medium);
  std::vector<HomogeneousMedium> media_;
  std::vector<int32_t> varying_of_;  // per medium id
  std::vector<VaryingMedium> varying_;
  std::vector<int32_t> id_of_material_;
  std::vector<uint8_t> pass_through_;
  int32_t world_ = -1;
  bool aims_ = false;
};

}  // namespace torrance
