// The samples of a render go to the film in blocks fixed by sample count alone: [0, 1), [1, 2),
// [2, 4), [4, 8), then kBlockSamples at a time. Within a block a tile takes each pixel's samples
// one after another (the paths of one pixel share their first hit, its shadow rays and the BVH
// nodes on the way: cache-warm), and its pixels in order; blocks go one after another, and with
// splatting each block through the four phases. Passes (timed) end only at block ends, so the
// order in which the film, guiding's per-pixel weights and the roulette's statistics see the
// samples is one and the same whatever the split into passes: the same render gives the same
// bits (core/tests/test_pass_partition.cpp).
//
// Why blocks and not the whole pass per pixel: a pass's length follows timing, and with splatting
// a pixel takes splats from its neighbours, so "all of this pass's samples, pixel by pixel" would
// order a pixel's sums by the passes. Why not one sample at a time over the tile: that order
// (08b52fd) cost the comparison scenes 10-20 % of their time (grass_stone's CPU time 1.02 s
// against 0.84 s for pixel after pixel, 64 spp, 2 cores shared), from the cache alone: the
// instructions were the same within 2.5 % (callgrind).
#pragma once

namespace torrance {

inline constexpr int kBlockSamples = 8;

// The end of the block that holds sample `done` (its first sample past `done`).
constexpr int sample_block_end(int done) {
  if (done < kBlockSamples) {
    int end = 1;
    while (end <= done) end *= 2;
    return end;
  }
  return (done / kBlockSamples + 1) * kBlockSamples;
}

// A pass from `done` of about `wanted` samples, ending at a block's end: the last block end not
// past done + wanted, or the first one after done if none is (at least one block), and never past
// `total`.
constexpr int pass_end_at_block(int done, int wanted, int total) {
  int end = sample_block_end(done);
  while (end < total && sample_block_end(end) <= done + wanted) end = sample_block_end(end);
  return end < total ? end : total;
}

}  // namespace torrance
