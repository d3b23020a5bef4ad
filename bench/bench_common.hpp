#pragma once
/// \file bench_common.hpp
/// What the benchmarks share: files of the source tree and a wall clock.
#include <chrono>
#include <cstdlib>
#include <string>

namespace hexdyn::bench {

/// A file of the source tree by its path from the tree's root ("configs/paper.yaml"):
/// under $HEXDYN_SOURCE_DIR if set, else found from this header's own path (bench/ sits
/// at the root).
inline std::string source_file(const std::string& relative) {
  if (const char* dir = std::getenv("HEXDYN_SOURCE_DIR")) return std::string(dir) + "/" + relative;
  const std::string here = __FILE__;
  const auto slash = here.find_last_of('/');
  const std::string bench_dir =
      slash == std::string::npos ? std::string(".") : here.substr(0, slash);
  return bench_dir + "/../" + relative;
}

using Clock = std::chrono::steady_clock;

/// Seconds since `t`.
inline double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

}  // namespace hexdyn::bench
