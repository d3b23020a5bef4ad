#pragma once
// Conversions at the edge of the compiled part, shared by module.cpp and dynamics.cpp: numpy
// arrays that own the C++ values they hold, overrides from their `--set` texts, YAML lookups
// a reader did not guard as the ConfigError the CLI reports.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn_python {

inline std::vector<hexdyn::Override> overrides_of(const std::vector<std::string>& texts) {
  std::vector<hexdyn::Override> out;
  for (const std::string& t : texts) out.push_back(hexdyn::parse_override(t));
  return out;
}

/// Runs `f`, turning a YAML lookup that a reader did not guard into the ConfigError the CLI
/// reports for it (cli/main.cpp): bad input, named by the scene path.
template <class F>
auto guard_yaml(const std::string& scene_path, F&& f) {
  try {
    return f();
  } catch (const YAML::Exception& e) {
    throw hexdyn::ConfigError(scene_path + ": unexpected YAML structure: " + e.what());
  }
}

/// A numpy array owning `values` (moved, no copy), of shape `dims`.
template <class T>
pybind11::array to_numpy(std::vector<T>&& values, const std::vector<std::size_t>& dims) {
  auto* owned = new std::vector<T>(std::move(values));
  pybind11::capsule free_when_done(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  std::vector<pybind11::ssize_t> shape(dims.begin(), dims.end());
  return pybind11::array_t<T>(shape, owned->data(), free_when_done);
}

}  // namespace hexdyn_python
