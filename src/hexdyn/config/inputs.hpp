#pragma once
/// \file inputs.hpp
/// The input files of a command: read once, kept, hashed and known by identity
/// (docs/user/faults.md#inputs; /meta input_sha256: docs/user/output.md#provenance-of-the-inputs;
/// a sweep's checkpoint identity: sweep/journal.hpp).
///
/// A scene's inputs are its file, every file it inherits (in inheritance order), the URDF
/// its robot.urdf names and the height map its terrain.height_map.file names (after `--set`). A
/// sweep adds its own file first and the URDFs named by a robot.urdf axis or a case; an envelope
/// adds its own file first.
///
/// Every input file is read through read_input_text, which refuses anything but a regular
/// file of at most the reader's size before it reads, and text that is not UTF-8 (hexdyn
/// stores its inputs' text in its files, which HDF5 readers decode as UTF-8). While an
/// InputFreeze lives, the first read of a file keeps its bytes, and every later read of the
/// same absolute path returns them: a command (a run, a sweep and all its scenarios, an
/// envelope) sees each input as it was when first read, whatever happens to the file
/// meanwhile, and its digest is the digest of the bytes used.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace hexdyn {

/// One input file, as read.
struct InputFile {
  std::string role;          ///< "scene", "inherited scene", "URDF", "sweep file", "envelope file"
  std::string path;          ///< as named (relative paths joined to the naming file's folder)
  std::string absolute;      ///< absolute and lexically normal (no "." or ".." parts), when read
  std::string sha256;        ///< of `text`: 64 lowercase hexadecimal digits (process/sha256.hpp)
  std::uint64_t device = 0;  ///< st_dev of the file read (0 with inode 0: not known here)
  std::uint64_t inode = 0;   ///< st_ino of the file read
  std::shared_ptr<const std::string> text;  ///< the bytes read (null once dropped)
  /// Listed by a file this command read (its /meta input_sha256: recorded_inputs), not read
  /// by this command: an output may not replace it either (io/output.hpp check_not_input).
  bool recorded = false;
};

/// Largest URDF read [bytes] (16 MiB; the URDFs of robots/ are 5–60 kB; meshes are not read).
inline constexpr std::size_t kMaxUrdfBytes = std::size_t{16} << 20;

/// Reads the input file `path` whole: a regular file (symbolic links followed) of at most
/// `max_bytes`, whose path and text are UTF-8. `expected` names what the reader wants ("a
/// configuration file (a regular YAML file)") in the ConfigError of one line that refuses
/// a missing, special (FIFO, device, folder: refused by type before any open that could
/// block), unreadable, HDF5 or binary (a NUL byte; both named so before the size is looked
/// at: a result file given as a scene), too large or non-UTF-8 file. While an InputFreeze
/// lives, returns the bytes kept from the first read of the same absolute path, if any, and
/// keeps these. `role` is left empty; `path` is `path`.
InputFile read_input_text(const std::string& path, std::size_t max_bytes,
                          const std::string& expected);

/// read_input_text without the text's checks: a binary input (a height map's .npy or HDF5
/// file), kept and hashed the same way.
InputFile read_input_bytes(const std::string& path, std::size_t max_bytes,
                           const std::string& expected);

/// Largest height map file read [bytes] (256 MiB: 32 million float64 heights).
inline constexpr std::size_t kMaxHeightMapBytes = std::size_t{256} << 20;
/// What a height map file is expected to be, in the errors that refuse one.
inline constexpr const char* kHeightMapExpected = "a height map (a 2-D .npy array or an HDF5 file)";

/// Keeps every input file read while at least one InputFreeze lives (any thread; the
/// store is the process's, so a sweep's compute thread and the scenario processes it
/// forks read what its main thread read). A command makes one for its whole length; the
/// kept bytes are released when the last InputFreeze ends.
class InputFreeze {
 public:
  InputFreeze();
  ~InputFreeze();
  InputFreeze(const InputFreeze&) = delete;
  InputFreeze& operator=(const InputFreeze&) = delete;
};

/// Whether an InputFreeze lives and keeps the bytes of `path` (its absolute path).
bool input_kept(const std::string& path);

/// Why `path` cannot be read as an input, or nothing: nothing when its bytes are kept
/// (input_kept: the file on disk no longer matters), else why_not_regular_file(path). What a
/// reader checks before read_input_text to name the key that gave the path.
std::optional<std::string> why_not_input_file(const std::string& path);

/// Makes `file` (with its text) the kept bytes of its absolute path, as if read first,
/// while an InputFreeze lives: a sweep's worker rank takes rank 0's inputs so. No effect
/// without text or without a live InputFreeze.
void keep_input(const InputFile& file);

/// Reads `path` (read_input_text, as a URDF for the role "URDF", else as a configuration
/// file) and appends it with its role, unless a file of the same absolute path is listed
/// already.
void add_input(std::vector<InputFile>& inputs, const std::string& role, const std::string& path);

/// The input in `inputs` that is the file (device, inode), or null. Inputs whose
/// identity is not known (device and inode 0) never match.
const InputFile* find_input(const std::vector<InputFile>& inputs, std::uint64_t device,
                            std::uint64_t inode);

/// `inputs` without their texts: what a result keeps to check its later outputs against.
std::vector<InputFile> without_texts(std::vector<InputFile> inputs);

/// The file robot.urdf of a scene tree names (a URDF robot), or "" when there is none.
std::string tree_urdf_path(const YAML::Node& tree);
/// The file terrain.height_map.file of a scene tree names (terrain.type height_map), or "".
std::string tree_height_map_path(const YAML::Node& tree);

/// A scene's inputs: `chain` (the scene file, then each inherited file, as
/// load_scene_tree lists them) and the URDF of `tree` (the merged tree, overrides applied)
/// when it names a regular file (else the scene's reader refuses it, naming the key).
std::vector<InputFile> scene_inputs(const std::vector<std::string>& chain, const YAML::Node& tree);

/// The text of /meta input_sha256: one line "SHA256  ABSOLUTE_PATH" per input, in order,
/// each ending in a newline: `sha256sum`'s format, so `sha256sum -c` checks the files.
std::string input_sha256_text(const std::vector<InputFile>& inputs);

/// The inputs listed in the text of a /meta input_sha256 (input_sha256_text's format), as
/// InputFile entries with `recorded` set, `role` "input recorded in WHERE", `path` and
/// `absolute` the listed path, `sha256` the listed digest and no identity (device and inode
/// 0). Lines that are not "DIGEST  PATH" are skipped.
std::vector<InputFile> recorded_inputs(const std::string& input_sha256, const std::string& where);

/// Where `text` is not UTF-8 (RFC 3629: no overlong forms, no surrogates, at most
/// U+10FFFF): the byte offset of the first bad sequence, or npos when it is all UTF-8.
std::size_t first_non_utf8(const std::string& text);

/// Throws ConfigError "WHERE: not UTF-8 text: byte 0xNN at line L, column C; …" when
/// `text` is not UTF-8 (first_non_utf8).
void require_utf8(const std::string& text, const std::string& where);

}  // namespace hexdyn
