#include "torrance/media/volume_grid.h"

#include "torrance/shader/shader_program.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace torrance {

namespace {

constexpr int B = VolumeGrid::kBrickSize;
constexpr double kMaxLatticeCells = double(1 << 26);  // a guard against far-apart bricks

int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

glm::ivec3 brick_of(const glm::ivec3& voxel) {
  return {floor_div(voxel.x, B), floor_div(voxel.y, B), floor_div(voxel.z, B)};
}

bool finite_matrix(const Mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

}  // namespace

VolumeGrid::VolumeGrid(int channels, const Mat4& world_to_index, const std::vector<glm::ivec3>& origins,
                       const std::vector<float>& values)
    : channels_(channels), world_to_index_(world_to_index), origins_(origins), values_(values) {
  if (channels < 1 || channels > 4)
    throw std::invalid_argument("a volume grid has 1 to 4 channels, got " + std::to_string(channels));
  if (values_.size() != origins_.size() * size_t(kBrickVoxels) * size_t(channels))
    throw std::invalid_argument("a volume grid's values must be bricks x " + std::to_string(kBrickVoxels) +
                                " x channels floats");
  const float det = glm::determinant(world_to_index_);
  if (!finite_matrix(world_to_index_) || !std::isfinite(det) || det == 0.0f)
    throw std::invalid_argument("a volume grid's transform must be finite and invertible");
  index_to_world_ = glm::inverse(world_to_index_);
  for (float& v : values_)
    if (!std::isfinite(v)) v = 0.0f;
  if (origins_.empty()) return;
  glm::ivec3 lo(INT32_MAX), hi(INT32_MIN);
  for (const glm::ivec3& o : origins_) {
    if (o.x % B != 0 || o.y % B != 0 || o.z % B != 0)
      throw std::invalid_argument("a volume grid's brick origins must be multiples of " + std::to_string(B));
    lo = glm::min(lo, brick_of(o));
    hi = glm::max(hi, brick_of(o));
  }
  // One empty cell around the bricks: the apron their lookups and maxima reach.
  lo_ = lo - 1;
  dims_ = hi - lo + 3;
  if (double(dims_.x) * double(dims_.y) * double(dims_.z) > kMaxLatticeCells)
    throw std::invalid_argument("a volume grid's bricks spread over too large a box");
  const size_t cells = size_t(dims_.x) * size_t(dims_.y) * size_t(dims_.z);
  index_.assign(cells, -1);
  std::vector<float> own(cells, 0.0f);
  auto cell = [&](const glm::ivec3& b) {
    const glm::ivec3 c = b - lo_;
    return (size_t(c.z) * size_t(dims_.y) + size_t(c.y)) * size_t(dims_.x) + size_t(c.x);
  };
  for (size_t i = 0; i < origins_.size(); ++i) {
    const size_t c = cell(brick_of(origins_[i]));
    if (index_[c] >= 0) throw std::invalid_argument("a volume grid's brick origins repeat");
    index_[c] = int32_t(i);
    const float* v = values_.data() + i * size_t(kBrickVoxels) * size_t(channels_);
    for (size_t k = 0; k < size_t(kBrickVoxels) * size_t(channels_); ++k) own[c] = std::max(own[c], std::abs(v[k]));
  }
  max_.assign(cells, 0.0f);
  for (int z = 1; z + 1 < dims_.z; ++z)
    for (int y = 1; y + 1 < dims_.y; ++y)
      for (int x = 1; x + 1 < dims_.x; ++x) {
        const float m = own[cell(lo_ + glm::ivec3(x, y, z))];
        if (m == 0.0f) continue;
        for (int dz = -1; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              float& target = max_[cell(lo_ + glm::ivec3(x + dx, y + dy, z + dz))];
              target = std::max(target, m);
            }
      }
}

void VolumeGrid::clip(const Vec3& lo, const Vec3& hi) {
  if (!(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z))
    throw std::invalid_argument("a volume grid's clip box must have lo <= hi");
  clip_lo_ = lo;
  clip_hi_ = hi;
}

int32_t VolumeGrid::brick_at(const glm::ivec3& brick) const {
  const glm::ivec3 c = brick - lo_;
  if (c.x < 0 || c.y < 0 || c.z < 0 || c.x >= dims_.x || c.y >= dims_.y || c.z >= dims_.z) return -1;
  return index_[(size_t(c.z) * size_t(dims_.y) + size_t(c.y)) * size_t(dims_.x) + size_t(c.x)];
}

glm::vec4 VolumeGrid::voxel(const glm::ivec3& i) const {
  const int32_t b = brick_at(brick_of(i));
  if (b < 0) return glm::vec4(0.0f);
  const glm::ivec3 l = i - origins_[size_t(b)];
  const float* v =
      values_.data() + (size_t(b) * size_t(kBrickVoxels) + size_t((l.z * B + l.y) * B + l.x)) * size_t(channels_);
  glm::vec4 out(0.0f);
  for (int c = 0; c < channels_; ++c) out[c] = v[c];
  return out;
}

namespace {

// Whether index-space point p lies where integer voxel coordinates of the lattice are safe.
bool within(const Vec3& p, const glm::ivec3& lo, const glm::ivec3& dims) {
  const Vec3 a = Vec3(lo * B), b = Vec3((lo + dims) * B);
  return p.x >= a.x && p.y >= a.y && p.z >= a.z && p.x < b.x && p.y < b.y && p.z < b.z;
}

glm::vec4 as_rgba(const glm::vec4& v, int channels) {
  if (channels == 1) return {v.x, v.x, v.x, 1.0f};
  return {v.x, v.y, channels > 2 ? v.z : 0.0f, channels > 3 ? v.w : 1.0f};
}

}  // namespace

glm::vec4 VolumeGrid::lookup(const Vec3& world) const {
  const Vec3 p = Vec3(world_to_index_ * glm::vec4(world, 1.0f));
  if (index_.empty() || !within(p, lo_, dims_) || glm::any(glm::lessThan(p, clip_lo_)) ||
      glm::any(glm::greaterThan(p, clip_hi_)))
    return as_rgba(glm::vec4(0.0f), channels_);
  const Vec3 floor_p = glm::floor(p);
  const Vec3 f = p - floor_p;
  const glm::ivec3 i(floor_p);
  glm::vec4 sum(0.0f);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::ivec3 d(corner & 1, (corner >> 1) & 1, corner >> 2);
    const float w = (d.x ? f.x : 1.0f - f.x) * (d.y ? f.y : 1.0f - f.y) * (d.z ? f.z : 1.0f - f.z);
    if (w > 0.0f) sum += w * voxel(i + d);
  }
  return as_rgba(sum, channels_);
}

float VolumeGrid::brick_max(const Vec3& world) const {
  const Vec3 p = Vec3(world_to_index_ * glm::vec4(world, 1.0f));
  if (index_.empty() || !within(p, lo_, dims_)) return 0.0f;
  const glm::ivec3 c = brick_of(glm::ivec3(glm::floor(p))) - lo_;
  return max_[(size_t(c.z) * size_t(dims_.y) + size_t(c.y)) * size_t(dims_.x) + size_t(c.x)];
}

std::vector<Vec3> VolumeGrid::brick_centres() const {
  std::vector<Vec3> out;
  out.reserve(origins_.size());
  for (const glm::ivec3& o : origins_)
    out.push_back(Vec3(index_to_world_ * glm::vec4(Vec3(o) + Vec3(0.5f * float(B - 1)), 1.0f)));
  return out;
}

OpValue volume_grid_op(const ShaderOpContext& c) {
  const auto* grids = c.globals.grids;
  const int32_t id = c.ins.resource;
  if (grids == nullptr || id < 0 || size_t(id) >= grids->size()) return glm::vec4(0.0f);
  const VolumeGrid& grid = *(*grids)[size_t(id)];
  if (c.globals.grid_bounds) return glm::vec4(grid.brick_max(c.vector(0)));
  return grid.lookup(c.vector(0));
}

}  // namespace torrance
