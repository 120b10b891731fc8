// The scene's AOV and light-group passes (extra_passes.h) and the AOVs' writes at a hit.
#include "film/extra_passes_write.h"

#include "torrance/scene/scene.h"

#include <array>
#include <stdexcept>

namespace torrance {

void ExtraPasses::set_aovs(const std::vector<std::pair<std::string, bool>>& aovs) {
  aovs_ = aovs;
  lay_out();
}

void ExtraPasses::set_light_groups(const std::vector<std::string>& names) {
  light_groups_ = names;
  lay_out();
}

void ExtraPasses::lay_out() {
  passes_.clear();
  aov_channels_.clear();
  int channel = 0;
  for (const auto& [name, color] : aovs_) {
    passes_.push_back({"aov:" + name, color ? 4 : 1});
    aov_channels_.push_back(channel);
    channel += color ? 4 : 1;
  }
  light_group_channel_ = channel;
  for (const std::string& name : light_groups_) {
    passes_.push_back({"lightgroup:" + name, 3});
    channel += 3;
  }
  if (channel > kMaxExtraChannels)
    throw std::invalid_argument("AOVs and light groups take " + std::to_string(channel) + " channels; at most " +
                                std::to_string(kMaxExtraChannels));
  num_light_groups_ = int(light_groups_.size());
  channels_ = channel;
}

void ExtraPasses::set_material_aovs(uint32_t material, int program, std::vector<AovWrite> writes) {
  for (const AovWrite& w : writes)
    if (w.aov < 0 || size_t(w.aov) >= aovs_.size())
      throw std::invalid_argument("AOV " + std::to_string(w.aov) + " does not exist (set_aovs first)");
  if (material >= material_aovs_.size()) material_aovs_.resize(size_t(material) + 1);
  material_aovs_[material] = {writes.empty() ? -1 : program, std::move(writes)};
  writes_aovs_ = false;
  for (const MaterialAovs& m : material_aovs_) writes_aovs_ = writes_aovs_ || m.program >= 0;
}

void add_aovs(const Scene& scene, const SurfaceHit& hit, const Vec3& dir, const PathState& state, float footprint,
              float* extras) {
  const ExtraPasses& x = scene.extra_passes();
  const ExtraPasses::MaterialAovs* m = x.material_aovs(hit.material);
  if (!m) return;
  const ShaderProgram& program = scene.shader_program(uint32_t(m->program));
  ShaderGlobals g = shader_globals(hit, dir, footprint, 0.0f, program.globals_read());
  g.path = state;
  g.tracer = &scene;
  std::array<glm::vec4, ShaderProgram::kMaxRegisters> regs;
  scene.run_shader_program(uint32_t(m->program), g, regs.data());
  for (const AovWrite& w : m->writes) {
    float* c = extras + x.aov_channel(w.aov);
    const glm::vec4& v = regs[size_t(w.reg)];
    if (x.aov_is_color(w.aov)) {
      c[0] += v.x;
      c[1] += v.y;
      c[2] += v.z;
      c[3] += 1.0f;
    } else {
      c[0] += v.x;
    }
  }
}

}  // namespace torrance
