// The scene key table (config/scene_key_table.hpp): rows that can be read, defaults inside
// their own ranges, the units a sweep axis takes from it, and the numbers of the docs.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <string>

#include "hexdyn/config/key_units.hpp"
#include "hexdyn/config/scene_key_docs.hpp"
#include "hexdyn/config/scene_key_table.hpp"

namespace hexdyn {
namespace {

TEST_CASE("config: every row of the key table can be read and documented", "[config][keys]") {
  std::set<std::pair<std::string, std::string>> seen;
  for (const SceneKey& k : scene_key_table()) {
    INFO(k.path);
    CHECK(!k.path.empty());
    CHECK(
        seen.insert({std::string(k.path) + " " + std::string(k.instances), std::string(k.section)})
            .second);  // once a table
    CHECK((k.path.find('*') == std::string_view::npos) == k.instances.empty());
    if (k.kind == KeyKind::kChoice) CHECK(!key_words(k.choices).empty());
    if (k.kind == KeyKind::kNumbers) CHECK((k.min_count >= 1 && k.min_count <= k.max_count));
    if (k.kind == KeyKind::kText) CHECK(!k.allowed_text.empty());
    if (k.read == KeyRead::kTable) {  // the table's loop stores it through its field
      CHECK(!k.section.empty());
      CHECK(((k.kind == KeyKind::kNumber && k.field.number) ||
             (k.kind == KeyKind::kInteger && k.field.integer) ||
             (k.kind == KeyKind::kChoice && k.field.set_choice)));
    }
    if (!k.section.empty()) CHECK(!k.meaning.empty());
  }
}

TEST_CASE("config: the default of every optional key lies in its own range", "[config][keys]") {
  Scene d;
  for (const SceneKey& k : scene_key_table()) {
    if (k.required) continue;
    INFO(k.path);
    if (k.field.number) CHECK(k.range.contains(*k.field.number(d)));
    if (k.field.integer) CHECK(k.range.contains(*k.field.integer(d)));
    if (k.field.get_choice) {
      const int i = k.field.get_choice(d);
      CHECK((i >= 0 && i < static_cast<int>(key_words(k.choices).size())));
    }
  }
}

TEST_CASE("config: a key's unit is its row's, for instances and legs too", "[config][keys]") {
  CHECK(scene_key_units("terrain.riser_height") == "m");
  CHECK(scene_key_units("gait.duty_factor") == "1");
  CHECK(scene_key_units("robot.femur.mass") == "kg");
  CHECK(scene_key_units("robot.payload.inertia") == "kg m^2");
  CHECK(scene_key_units("robot.foot_offset.L3") == "m");
  CHECK(scene_key_units("contact.damping_max") == "N s/m");
  CHECK(scene_key_units("contact.stiffness").empty());  // N/m^e: e is the scene's
  CHECK(scene_key_units("allocation.friction").empty());
  CHECK(scene_key_units("robot.knee.mass").empty());  // not an instance of robot.*.mass
  CHECK(scene_key_units("gait.no_such_key").empty());
}

TEST_CASE("config: numbers as the docs write them", "[config][keys]") {
  CHECK(doc_number(0.02) == "0.02");
  CHECK(doc_number(1e-4) == "1e-4");
  CHECK(doc_number(1e6) == "1e6");
  CHECK(doc_number(10.0) == "10");
  CHECK(doc_number(-100.0) == "−100");
  CHECK(doc_number(M_PI / 2) == "π/2");
  CHECK(doc_number(-2 * M_PI) == "−2π");
  CHECK(doc_number(0.3) == "0.3");
  CHECK(doc_number(INFINITY) == "∞");
}

}  // namespace
}  // namespace hexdyn
