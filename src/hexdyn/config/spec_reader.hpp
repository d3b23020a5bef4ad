#pragma once
/// \file spec_reader.hpp
/// The one error format of every hand-written YAML file hexdyn reads: a scene (its key
/// reader, scene_key_reader.hpp, is a SpecReader), a sweep file and an envelope file. Every
/// failure throws ConfigError with one line "FILE: key.path: message": "got VALUE, expected
/// WHAT", "missing, ...", "unknown key, allowed here: A, B".
#include <string>
#include <vector>

namespace YAML {
class Node;
}

namespace hexdyn {

class SpecReader {
 public:
  explicit SpecReader(std::string file) : file_(std::move(file)) {}

  /// Throws "FILE: path: what".
  [[noreturn]] void fail(const std::string& path, const std::string& what) const;
  /// Throws "FILE: path: got VALUE, expected WHAT", or "missing, expected WHAT" when the
  /// node is undefined.
  [[noreturn]] void fail_value(const std::string& path, const YAML::Node& node,
                               const std::string& expected) const;
  /// Throws "FILE: path: got the string \"1e-2\", expected WHAT (write it unquoted)" when
  /// `node` is a quoted number (yaml_load.hpp's is_quoted_number): every number of a study
  /// file is read through a check of this.
  void refuse_quoted_number(const std::string& path, const YAML::Node& node,
                            const std::string& expected) const;
  /// Refuses the first quoted number (is_quoted_number) in `node` or in the lists in it, named
  /// by its path ("key[2][0]"), where a number `expected` is wanted.
  void refuse_quoted_numbers(const std::string& path, const YAML::Node& node,
                             const std::string& expected) const;
  /// Throws "FILE: path: unknown key, allowed here: A, B", `allowed` sorted, once each.
  [[noreturn]] void fail_unknown(const std::string& path,
                                 const std::vector<std::string>& allowed) const;
  /// Throws "FILE: path: got VALUE, expected a mapping of keys" ("(top level)" for path "").
  [[noreturn]] void fail_not_map(const std::string& path, const YAML::Node& node) const;
  /// `node` at `path` ("" for the top level) must be a map whose every key is one of
  /// `allowed`; an unknown key is named with the sorted list of allowed ones.
  void check_keys(const YAML::Node& node, const std::string& path,
                  const std::vector<std::string>& allowed) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace hexdyn
