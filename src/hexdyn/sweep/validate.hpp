#pragma once
/// \file validate.hpp
/// `hexdyn validate` and Python's hexdyn.validate, one function: checks a scene file or a
/// sweep file without computing anything and reports what it found. The command line
/// prints the report's messages; the Python module returns its fields as a dict.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn {

/// What a validated file is: a scene, or a sweep (a file with a top-level `axes:` key).
enum class ValidatedKind { kScene, kSweep };

/// "scene" or "sweep".
const char* validated_kind_name(ValidatedKind kind);

/// What validate_file found in a valid file.
struct ValidationReport {
  ValidatedKind kind = ValidatedKind::kScene;
  std::string path;  ///< the file as given
  std::string name;  ///< the scene's or the sweep's `name:`
  /// The scene read (a scene file only): `hexdyn validate -v` prints its URDF leg mapping.
  std::optional<Scene> scene;
  std::size_t scenarios = 0;       ///< a sweep's scenarios, each one's scene validated
  std::size_t out_of_range = 0;    ///< of those, scenarios that would be rows with status config
  std::string first_out_of_range;  ///< the first such scenario's message ("" when none)
  /// The lines `hexdyn validate` prints, without newlines: "PATH: valid scene 'NAME'", or
  /// for a sweep "PATH: valid sweep 'NAME', base scene B, N scenarios over KEY (n) ..." and,
  /// when some are out of range, "PATH: K of N scenarios have a value out of range ...".
  std::vector<std::string> messages;
};

/// Checks the scene or sweep file at `path` as `hexdyn run` or `hexdyn sweep` would read
/// it: a scene with `overrides` applied (load_scene); a sweep file (load_sweep, then every
/// scenario's scene: check_sweep_scenarios), for which `overrides` must be empty. Throws
/// the ConfigError or IoError of the first error, one line; out-of-range sweep scenarios
/// are counted, not thrown (`hexdyn sweep` records them as rows with status config).
ValidationReport validate_file(const std::string& path,
                               const std::vector<Override>& overrides = {});

}  // namespace hexdyn
