// Shared by the libFuzzer harnesses: a small budget, and what counts as a clear rejection.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>

namespace torrance_fuzz {

// Requests are checked against 256 MiB (far below libFuzzer's -rss_limit_mb / -malloc_limit_mb),
// so a size check that is missing shows up as a malloc-limit or out-of-memory crash.
inline void set_small_budget() { setenv("TORRANCE_MEMORY_BUDGET", "268435456", 1); }

// A broken promise of the core: say which (scripts/fuzz prints lines marked "fuzz check failed"),
// then abort so that libFuzzer keeps the input.
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "fuzz check failed: %s\n", what);
  std::abort();
}

// Runs f; invalid_argument and runtime_error are the core's clear rejections. Anything else
// (bad_alloc, length_error, out_of_range, ...) means a check is missing: abort, so the fuzzer
// records the input.
template <class F>
bool clearly(F&& f) {
  try {
    f();
    return true;
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {
  } catch (const std::exception& e) {
    fail((std::string("unexpected exception: ") + e.what()).c_str());
  }
  return false;
}

}  // namespace torrance_fuzz
