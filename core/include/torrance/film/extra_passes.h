// The render passes a scene defines besides Blender's fixed ones, as Cycles 3.4 writes them:
// - Shader AOVs (the view layer's AOVs, filled by AOV Output nodes): at each surface a camera
//   ray shades until one whose alpha reaches the Alpha Threshold (Cycles' svm_node_aov_check:
//   PATH_RAY_TRANSPARENT_BACKGROUND without PATH_RAY_SINGLE_PASS_DONE), the node's input is added
//   unweighted to the sample (a colour AOV: RGB and 1 in alpha); 0 where nothing writes. Each
//   material's AOV Output nodes are one shader program of their own (set_material_aovs).
// - Light groups (Combined_<name>): the light of each group's emitters (lights, emitting objects,
//   the world), as Combined holds it (throughput, MIS, clamping): Combined = the groups' sum +
//   the light of the emitters of no group.
// The film holds them as extra channels of each sample (PathRadiance::extras): AOVs first, then
// 3 per light group.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace torrance {

inline constexpr int kMaxExtraChannels = 64;

struct ExtraPass {
  std::string name;  // the core's name: "aov:<name>" or "lightgroup:<name>"
  int channels;      // 1 (value AOV), 4 (colour AOV: RGB and the share of samples written) or 3
};

// An AOV Output node's input of a material's AOV program: the register (x of a value AOV, xyz of
// a colour one) and the AOV (index in set_aovs' list) it adds into.
struct AovWrite {
  int aov = 0;
  int reg = 0;
};

class ExtraPasses {
 public:
  struct MaterialAovs {
    int program = -1;  // Scene shader program
    std::vector<AovWrite> writes;
  };

  // The view layer's AOVs in order: name and whether it is a colour (else a value).
  void set_aovs(const std::vector<std::pair<std::string, bool>>& aovs);
  // The light groups in order (their index is an emitter's group).
  void set_light_groups(const std::vector<std::string>& names);
  // Material `material`'s AOV Output nodes: `program` computes their inputs (throws
  // std::invalid_argument for an unknown AOV).
  void set_material_aovs(uint32_t material, int program, std::vector<AovWrite> writes);

  const std::vector<ExtraPass>& passes() const { return passes_; }
  int channels() const { return channels_; }
  // The material's AOV writes, or nullptr.
  const MaterialAovs* material_aovs(uint32_t material) const {
    return material < material_aovs_.size() && material_aovs_[material].program >= 0 ? &material_aovs_[material]
                                                                                       : nullptr;
  }
  bool writes_aovs() const { return writes_aovs_; }
  int aov_channel(int aov) const { return aov_channels_[size_t(aov)]; }
  bool aov_is_color(int aov) const { return passes_[size_t(aov)].channels == 4; }
  int num_light_groups() const { return num_light_groups_; }
  // The first of light group g's three channels.
  int light_group_channel(int group) const { return light_group_channel_ + 3 * group; }

 private:
  void lay_out();
  std::vector<std::pair<std::string, bool>> aovs_;
  std::vector<std::string> light_groups_;
  std::vector<ExtraPass> passes_;
  std::vector<int> aov_channels_;
  std::vector<MaterialAovs> material_aovs_;
  bool writes_aovs_ = false;
  int num_light_groups_ = 0, light_group_channel_ = 0, channels_ = 0;
};

}  // namespace torrance
