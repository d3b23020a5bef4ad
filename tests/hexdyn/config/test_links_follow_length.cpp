// robot.links_follow_length (config/config.cpp, model/link_scaling.hpp): the default keeps the
// stated masses whatever the lengths; uniform_density scales each link's mass by its length
// over robot.<link>.reference_length and moves its COM with it, so that the model's total
// mass is the hand sum over the scaled links (numbers read here from configs/paper.yaml with
// yaml-cpp); bad values are refused in one line naming the key.
#include <yaml-cpp/yaml.h>

#include <catch2/catch.hpp>
#include <string>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/robot_model.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";
const std::string kDesign = std::string(HEXDYN_SOURCE_DIR) + "/configs/designs/paper_base.yaml";
const char* kLinks[3] = {"coxa", "femur", "tibia"};

const YAML::Node& paper_robot() {
  static const YAML::Node robot = YAML::LoadFile(kPaper)["robot"];
  return robot;
}

double stated(const char* link, const char* key) { return paper_robot()[link][key].as<double>(); }

/// The paper scene with the rule on and the reference lengths at the paper's lengths.
std::vector<Override> rule_on() {
  std::vector<Override> o{{"robot.links_follow_length", "uniform_density"}};
  for (const char* l : kLinks)
    o.push_back(
        {std::string("robot.") + l + ".reference_length", paper_robot()[l]["length"].Scalar()});
  return o;
}

std::string config_error(const std::string& path, const std::vector<Override>& o) {
  try {
    load_scene(path, o);
  } catch (const ConfigError& e) {
    return e.what();
  }
  FAIL("no ConfigError was thrown");
  return "";
}

TEST_CASE("links_follow_length: none keeps the stated masses whatever the length",
          "[io][links_follow_length]") {
  const Scene scene = load_scene(kPaper, {{"robot.femur.length", "0.15"}});
  CHECK(scene.robot.link[1].mass_kg == stated("femur", "mass"));
  CHECK(scene.robot.link[1].com_m.x() == paper_robot()["femur"]["com"][0].as<double>());
  CHECK(scene.resolved_yaml.find("links_follow_length: none") != std::string::npos);
}

TEST_CASE("uniform_density at the reference lengths is the paper robot bit for bit",
          "[io][links_follow_length]") {
  const Scene paper = load_scene(kPaper);
  const Scene same = load_scene(kPaper, rule_on());
  for (int j = 0; j < 3; ++j) {
    CHECK(same.robot.link[j].mass_kg == paper.robot.link[j].mass_kg);
    CHECK(same.robot.link[j].com_m == paper.robot.link[j].com_m);
    CHECK(same.robot.link[j].inertia_kgm2 == paper.robot.link[j].inertia_kgm2);
  }
}

TEST_CASE("uniform_density scales each link's mass and COM by its length ratio",
          "[io][links_follow_length]") {
  const double L[3] = {0.07, 0.15, 0.08};
  auto o = rule_on();
  for (int j = 0; j < 3; ++j)
    o.push_back({std::string("robot.") + kLinks[j] + ".length", std::to_string(L[j])});
  const Scene scene = load_scene(kPaper, o);
  double legs = 0.0;
  for (int j = 0; j < 3; ++j) {
    const double r = L[j] / stated(kLinks[j], "length");
    INFO(kLinks[j] << ", r = " << r);
    CHECK(scene.robot.link[j].mass_kg == Approx(r * stated(kLinks[j], "mass")).epsilon(1e-14));
    CHECK(scene.robot.link[j].com_m.x() ==
          Approx(r * paper_robot()[kLinks[j]]["com"][0].as<double>()).epsilon(1e-14));
    legs += r * stated(kLinks[j], "mass");
  }
  const double total = paper_robot()["trunk"]["mass"].as<double>() +
                       paper_robot()["payload"]["mass"].as<double>() + 6.0 * legs;
  CHECK(build_robot_model(scene.robot).total_mass_kg == Approx(total).epsilon(1e-14));
  // Massless legs lump the same scaled masses at the hips.
  o.push_back({"robot.leg_inertia", "massless"});
  CHECK(build_robot_model(load_scene(kPaper, o).robot).total_mass_kg ==
        Approx(total).epsilon(1e-14));
}

TEST_CASE("uniform_density: the COM's default is the middle of the link at any length",
          "[io][links_follow_length]") {
  auto o = rule_on();
  o.push_back({"robot.femur.com", "null"});
  o.push_back({"robot.femur.length", "0.16"});
  const Scene scene = load_scene(kPaper, o);
  CHECK(scene.robot.link[1].com_m.x() == Approx(0.08).epsilon(1e-14));
  // The resolved configuration states the reference's COM and reloads to the same scene.
  const Scene again = load_scene_from_string(scene.resolved_yaml, "resolved.yaml");
  CHECK(again.robot.link[1].com_m == scene.robot.link[1].com_m);
  CHECK(again.robot.link[1].mass_kg == scene.robot.link[1].mass_kg);
  CHECK(again.robot.link[1].inertia_kgm2 == scene.robot.link[1].inertia_kgm2);
}

TEST_CASE("the design base scene states the paper's lengths as references",
          "[io][links_follow_length]") {
  const Scene design = load_scene(kDesign);
  const Scene paper = load_scene(kPaper);
  for (int j = 0; j < 3; ++j) CHECK(design.robot.link[j].mass_kg == paper.robot.link[j].mass_kg);
  const Scene longer = load_scene(kDesign, {{"robot.tibia.length", "0.12"}});
  CHECK(longer.robot.link[2].mass_kg == Approx(stated("tibia", "mass") * 1.2).epsilon(1e-14));
}

TEST_CASE("links_follow_length: bad values are refused in one line naming the key",
          "[io][links_follow_length]") {
  const std::string unknown = config_error(kPaper, {{"robot.links_follow_length", "linear"}});
  CHECK(unknown.find("robot.links_follow_length: got linear, expected one of none, "
                     "uniform_density") != std::string::npos);
  CHECK(unknown.find('\n') == std::string::npos);
  const std::string missing =
      config_error(kPaper, {{"robot.links_follow_length", "uniform_density"}});
  CHECK(missing.find("robot.coxa.reference_length: missing") != std::string::npos);
  CHECK(missing.find('\n') == std::string::npos);
  auto zero = rule_on();
  zero.push_back({"robot.tibia.reference_length", "0"});
  const std::string bad = config_error(kPaper, zero);
  CHECK(bad.find("robot.tibia.reference_length: got 0") != std::string::npos);
  CHECK(bad.find('\n') == std::string::npos);
}

}  // namespace
}  // namespace hexdyn
