// The URDF reader's checks of primitive geometry (urdf_checks.hpp): a sphere, box or cylinder
// of size 0 or below in a <collision> or a <visual> is refused in one line naming the file,
// the link, the element and the value, though urdfdom itself takes it; the smallest positive
// sizes and a mesh (whose file is not read) load.
#include <urdf_parser/urdf_parser.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/model/urdf_reader.hpp"

namespace hexdyn {
namespace {

const std::string kHexapod = std::string(HEXDYN_SOURCE_DIR) + "/tests/data/urdf/valid_hexapod.urdf";

/// valid_hexapod.urdf with `<element><geometry>GEOMETRY</geometry></element>` in its trunk link.
std::string with_geometry(const std::string& element, const std::string& geometry) {
  std::ifstream in(kHexapod);
  std::ostringstream s;
  s << in.rdbuf();
  std::string text = s.str();
  const std::string trunk = "<link name=\"trunk\">";
  const std::size_t at = text.find(trunk);
  REQUIRE(at != std::string::npos);
  return text.insert(at + trunk.size(),
                     "<" + element + "><geometry>" + geometry + "</geometry></" + element + ">");
}

/// The one-line message of reading `text`, or "" when it loads.
std::string refusal(const std::string& text) {
  try {
    (void)read_urdf_robot_from_string(text, "hexapod.urdf");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("urdf checks: primitives of size 0 or below are refused naming the link and value",
          "[urdf_reader]") {
  struct Case {
    const char* geometry;
    const char* expected;
  };
  const std::vector<Case> refused = {
      {"<sphere radius=\"0\"/>", "<sphere radius=\"0\">, expected a radius > 0 m"},
      {"<sphere radius=\"-0.01\"/>", "<sphere radius=\"-0.01\">, expected a radius > 0 m"},
      {"<box size=\"0.1 0 0.1\"/>", "<box size=\"0.1 0 0.1\">, expected three sizes > 0 m"},
      {"<box size=\"0.1 0.1 -0.2\"/>", "<box size=\"0.1 0.1 -0.2\">, expected three sizes > 0 m"},
      {"<cylinder radius=\"0\" length=\"0.1\"/>",
       "<cylinder radius=\"0\" length=\"0.1\">, expected a radius and a length > 0 m"},
      {"<cylinder radius=\"0.02\" length=\"-0.06\"/>",
       "<cylinder radius=\"0.02\" length=\"-0.06\">, expected a radius and a length > 0 m"},
  };
  for (const char* element : {"collision", "visual"}) {
    for (const Case& c : refused) {
      const std::string text = with_geometry(element, c.geometry);
      INFO(element << " " << c.geometry);
      REQUIRE(urdf::parseURDF(text));  // urdfdom takes it: the refusal is hexdyn's
      const std::string expected =
          std::string("hexapod.urdf: link 'trunk': <") + element + ">" + c.expected;
      CHECK(refusal(text) == expected);
    }
  }
  for (const char* geometry : {"<sphere radius=\"1e-9\"/>", "<box size=\"1e-9 1e-9 1e-9\"/>",
                               "<cylinder radius=\"1e-9\" length=\"1e-9\"/>",
                               "<mesh filename=\"package://none/trunk.stl\"/>"}) {
    INFO(geometry);
    CHECK(refusal(with_geometry("collision", geometry)).empty());
    CHECK(refusal(with_geometry("visual", geometry)).empty());
  }
}

}  // namespace hexdyn
