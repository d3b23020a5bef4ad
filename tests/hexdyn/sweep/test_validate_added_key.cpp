// A key added to the scene key table (config/scene_key_table.hpp) and nowhere else: `hexdyn
// validate` (validate_file) requires and checks it, the resolved configuration records it, the
// unit table and the generated docs list it, and it is gone with its row.
#include <catch2/catch.hpp>
#include <string>

#include "hexdyn/config/key_units.hpp"
#include "hexdyn/config/scene_key_docs.hpp"
#include "hexdyn/config/scene_key_table.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/sweep/validate.hpp"

namespace hexdyn {
namespace {

const std::string kPaper = std::string(HEXDYN_SOURCE_DIR) + "/configs/paper.yaml";

/// Where the added key's value goes: a field of the test, through the row's accessor.
double g_added_value = 0.0;

SceneKey added_key() {
  return {.path = "gait.test_gain",
          .section = "gait",
          .kind = KeyKind::kNumber,
          .range = scene_keys::positive(10.0),
          .unit = "N",
          .required = true,
          .meaning = "a key added by a test",
          .read = KeyRead::kTable,
          .field = {.number = [](Scene&) { return &g_added_value; }}};
}

/// The ConfigError message of validating the paper scene with `overrides`, "" when valid.
std::string validate_error(const std::vector<Override>& overrides) {
  try {
    validate_file(kPaper, overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST_CASE("config: a key added to the table is validated, resolved, given a unit and documented",
          "[config][keys]") {
  REQUIRE(validate_error({}).empty());
  REQUIRE(find_scene_key("gait.test_gain") == nullptr);
  {
    const AddedSceneKey row(added_key());
    // validate: required, checked against its range, read into its field, recorded.
    CHECK(validate_error({}) == kPaper + ": gait.test_gain: missing, this key is required");
    CHECK(validate_error({{"gait.test_gain", "11"}}) ==
          kPaper + ": gait.test_gain: got 11, expected a number in (0, 10]");
    const ValidationReport report = validate_file(kPaper, {{"gait.test_gain", "2.5"}});
    CHECK(g_added_value == 2.5);
    REQUIRE(report.scene);
    CHECK(report.scene->resolved_yaml.find("test_gain: 2.5") != std::string::npos);
    // An unknown key of its group names it among the allowed ones.
    CHECK(validate_error({{"gait.test_gain", "2.5"}, {"gait.test_gian", "1"}}).find("test_gain") !=
          std::string::npos);
    // Its unit, and its row in the generated table of docs/user/configuration.md#gait.
    CHECK(scene_key_units("gait.test_gain") == "N");
    CHECK(scene_key_markdown("gait").find(
              "| `gait.test_gain` | (0, 10] N | required | a key added by a test |\n") !=
          std::string::npos);
  }
  CHECK(find_scene_key("gait.test_gain") == nullptr);
  CHECK(validate_error({}).empty());
  CHECK(scene_key_markdown("gait").find("test_gain") == std::string::npos);
}

}  // namespace
}  // namespace hexdyn
