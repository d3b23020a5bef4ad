#pragma once
/// \file errors.hpp
/// The exception family. Every message is one line naming what was wrong and what
/// is allowed; the CLI prints it and exits with status 2 (input errors) or 3 (a
/// scenario that cannot be computed). A sweep catches `hexdyn::Error`, records the
/// scenario as failed with the message, and goes on.
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace hexdyn {

/// Base of all hexdyn errors.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
  virtual int exit_status() const { return 3; }
};

/// A configuration key is missing, mistyped, non-finite, unknown or out of range;
/// the YAML cannot be parsed; a file cannot be read. Message names key path and value.
class ConfigError : public Error {
 public:
  using Error::Error;
  int exit_status() const override { return 2; }
};

/// An output file cannot be written.
class IoError : public Error {
 public:
  using Error::Error;
  int exit_status() const override { return 2; }
};

/// A foot target outside a leg's workspace or too close to a singularity:
/// the message names the leg, the time and the margin.
class ReachError : public Error {
 public:
  using Error::Error;
};

/// Several problems of one input, one line each (the bad steps of a step list): what() has
/// them joined by line breaks; the CLI prints each as an error line of its own.
class ConfigErrors : public ConfigError {
 public:
  explicit ConfigErrors(std::vector<std::string> lines)
      : ConfigError(joined(lines)), lines_(std::move(lines)) {}
  const std::vector<std::string>& lines() const { return lines_; }

 private:
  static std::string joined(const std::vector<std::string>& lines) {
    std::string out;
    for (const std::string& l : lines) out += (out.empty() ? "" : "\n") + l;
    return out;
  }
  std::vector<std::string> lines_;
};

/// A planning failure (no foothold on a tread, a swing path that cannot clear).
class PlanningError : public Error {
 public:
  using Error::Error;
};

/// A numerical solver could not produce a usable answer at all (not the flagged,
/// relaxed samples, which are values, not exceptions).
class SolverError : public Error {
 public:
  using Error::Error;
};

/// `text` on one line, as the CLI prints an error (and the Python module raises it):
/// line breaks from quoted values are written as "\\n" and "\\r".
inline std::string one_line(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '\n')
      out += "\\n";
    else if (c == '\r')
      out += "\\r";
    else
      out += c;
  }
  return out;
}

}  // namespace hexdyn
