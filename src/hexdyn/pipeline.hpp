#pragma once
/// \file pipeline.hpp
/// One scene, end to end: the library call behind `hexdyn run` and every sweep
/// scenario. Throws a hexdyn::Error subclass when the scene cannot be computed.
#include <iosfwd>

#include "hexdyn/result.hpp"
#include "hexdyn/scene.hpp"

namespace hexdyn {

/// Plans, samples and solves a scene. `log` (may be null) receives one line per episode
/// of relaxed or failed allocation samples.
RunResult run_scene(const Scene& scene, std::ostream* log = nullptr);

}  // namespace hexdyn
