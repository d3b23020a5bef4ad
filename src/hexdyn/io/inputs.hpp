#pragma once
/// \file inputs.hpp
/// The input files of a run, sweep or envelope and their SHA-256 digests: what /meta
/// input_sha256 records (docs/user/output.md#provenance-of-the-inputs) and what a sweep's
/// checkpoint identity covers (sweep/journal.hpp).
///
/// A scene's inputs are its file, every file it inherits (in inheritance order) and the
/// URDF its robot.urdf names. A sweep adds its own file first and the URDFs named by a
/// robot.urdf axis; an envelope adds its own file first.
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace hexdyn {

/// One input file, hashed when it was listed.
struct InputFile {
  std::string role;      ///< "scene", "inherited scene", "URDF", "sweep file", "envelope file"
  std::string path;      ///< as named (relative paths joined to the naming file's folder)
  std::string absolute;  ///< absolute and lexically normal (no "." or ".." parts)
  std::string sha256;    ///< 64 lowercase hexadecimal digits (io/sha256.hpp)
};

/// Hashes `path` and appends it, unless a file of the same absolute path is listed
/// already. Throws IoError naming the file when it cannot be read.
void add_input(std::vector<InputFile>& inputs, const std::string& role, const std::string& path);

/// The file robot.urdf of a scene tree names (a URDF robot), or "" when there is none.
std::string tree_urdf_path(const YAML::Node& tree);

/// A scene's inputs: `chain` (the scene file, then each inherited file, as
/// load_scene_tree lists them) and the URDF of `tree` (the merged tree, overrides applied).
std::vector<InputFile> scene_inputs(const std::vector<std::string>& chain, const YAML::Node& tree);

/// The text of /meta input_sha256: one line "SHA256  ABSOLUTE_PATH" per input, in order,
/// each ending in a newline: `sha256sum`'s format, so `sha256sum -c` checks the files.
std::string input_sha256_text(const std::vector<InputFile>& inputs);

}  // namespace hexdyn
