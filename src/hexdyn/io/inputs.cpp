#include "hexdyn/io/inputs.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>

#include "hexdyn/io/sha256.hpp"

namespace hexdyn {

void add_input(std::vector<InputFile>& inputs, const std::string& role, const std::string& path) {
  std::error_code ec;
  std::filesystem::path abs = std::filesystem::absolute(path, ec);
  const std::string absolute = ec ? path : abs.lexically_normal().string();
  const bool listed = std::any_of(inputs.begin(), inputs.end(),
                                  [&](const InputFile& f) { return f.absolute == absolute; });
  if (listed) return;
  inputs.push_back({role, path, absolute, sha256_file(path)});
}

std::string tree_urdf_path(const YAML::Node& tree) {
  if (!tree.IsMap()) return {};
  const YAML::Node robot = tree["robot"];
  if (!robot.IsDefined() || !robot.IsMap()) return {};
  const YAML::Node urdf = robot["urdf"];
  if (!urdf.IsDefined() || !urdf.IsScalar()) return {};
  return urdf.Scalar();
}

std::vector<InputFile> scene_inputs(const std::vector<std::string>& chain, const YAML::Node& tree) {
  std::vector<InputFile> inputs;
  for (std::size_t i = 0; i < chain.size(); ++i)
    add_input(inputs, i == 0 ? "scene" : "inherited scene", chain[i]);
  const std::string urdf = tree_urdf_path(tree);
  if (!urdf.empty()) add_input(inputs, "URDF", urdf);
  return inputs;
}

std::string input_sha256_text(const std::vector<InputFile>& inputs) {
  std::string text;
  for (const InputFile& f : inputs) text += f.sha256 + "  " + f.absolute + "\n";
  return text;
}

}  // namespace hexdyn
