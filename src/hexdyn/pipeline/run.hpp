#pragma once
/// \file run.hpp
/// One scene end to end, the pipeline's public entry point (<hexdyn/hexdyn.hpp>): the
/// stages it runs and the prepared scene a caller may look at first are in pipeline.hpp.
#include <iosfwd>

#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// Plans, samples and solves a scene. `log` (may be null) receives one line per episode
/// of relaxed or failed allocation samples, and once, before the first relaxed one, what
/// relaxed means. Throws a hexdyn::Error subclass when the scene cannot be computed.
RunResult run_scene(const Scene& scene, std::ostream* log = nullptr);

}  // namespace hexdyn
