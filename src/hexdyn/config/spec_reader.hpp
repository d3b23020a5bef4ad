#pragma once
/// \file spec_reader.hpp
/// Errors of a hand-written study file (a sweep file, an envelope file) as one line
/// "FILE: key.path: message", the form scene errors take (config.hpp). Every failure
/// throws ConfigError.
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
  /// `node` at `path` ("" for the top level) must be a map whose every key is one of
  /// `allowed`; an unknown key is named with the sorted list of allowed ones.
  void check_keys(const YAML::Node& node, const std::string& path,
                  const std::vector<std::string>& allowed) const;
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

}  // namespace hexdyn
