#pragma once
/// \file run.hpp
/// One scene end to end, the pipeline's public entry point (<hexdyn/hexdyn.hpp>): the
/// stages it runs and the prepared scene a caller may look at first are in pipeline.hpp.
#include <iosfwd>

#include "hexdyn/core/result.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// Plans, samples and solves a scene. `log` (may be null) receives the episodes of relaxed
/// or failed allocation samples (pipeline/episode_log.hpp: one line per kind, a repeated
/// kind summarised), and once, before the first relaxed one, what relaxed means. Throws a
/// hexdyn::Error subclass when the scene cannot be computed.
RunResult run_scene(const Scene& scene, std::ostream* log = nullptr);

}  // namespace hexdyn
