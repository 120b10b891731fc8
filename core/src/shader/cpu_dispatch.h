// Hot procedural-texture code built twice: for the build's baseline (x86-64: SSE2, 4 lanes) and
// for AVX2 (8 lanes: the hash lanes of shader_hash_lanes.h and the loops over cells and corners),
// the AVX2 build run where the CPU has it. Both are the same C++: run_fast(f) calls f inside a
// function built for AVX2 with everything f calls inlined into it (flatten; the core is built
// with -fno-semantic-interposition, so that includes its exported functions). AVX2 without FMA,
// so no multiply-add is contracted and every float operation rounds as in the baseline: the two
// builds give the same bits (test_shader_cpu_dispatch compares them).
#pragma once

namespace torrance::cpu_dispatch {

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__AVX2__)
// Whether run_fast runs the AVX2 build: where the CPU has AVX2 (tests turn it off to compare).
inline bool& use_avx2() {
  static bool on = __builtin_cpu_supports("avx2");
  return on;
}

template <typename F>
__attribute__((target("avx2"), flatten)) auto run_avx2(const F& f) {
  return f();
}

// f(), built for AVX2 where the CPU has it.
template <typename F>
auto run_fast(const F& f) {
  return use_avx2() ? run_avx2(f) : f();
}
#else
inline bool& use_avx2() {
  static bool on = false;  // one build only
  return on;
}

template <typename F>
auto run_fast(const F& f) {
  return f();
}
#endif

}  // namespace torrance::cpu_dispatch
