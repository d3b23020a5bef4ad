#include "hexdyn/model/urdf_checks.hpp"

#include <tinyxml.h>
#include <urdf_model/model.h>

#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

std::string num(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

/// Why the primitive `g` has no volume, as "<sphere radius=\"0\">, expected …", or "".
std::string empty_primitive(const urdf::Geometry& g) {
  switch (g.type) {
    case urdf::Geometry::SPHERE: {
      const double r = static_cast<const urdf::Sphere&>(g).radius;
      if (r > 0.0) return {};
      return "<sphere radius=\"" + num(r) + "\">, expected a radius > 0 m";
    }
    case urdf::Geometry::BOX: {
      const urdf::Vector3& d = static_cast<const urdf::Box&>(g).dim;
      if (d.x > 0.0 && d.y > 0.0 && d.z > 0.0) return {};
      return "<box size=\"" + num(d.x) + " " + num(d.y) + " " + num(d.z) +
             "\">, expected three sizes > 0 m";
    }
    case urdf::Geometry::CYLINDER: {
      const auto& c = static_cast<const urdf::Cylinder&>(g);
      if (c.radius > 0.0 && c.length > 0.0) return {};
      return "<cylinder radius=\"" + num(c.radius) + "\" length=\"" + num(c.length) +
             "\">, expected a radius and a length > 0 m";
    }
    default:  // a mesh: its file is not read
      return {};
  }
}

/// The first empty primitive among `elements` (<collision> or <visual>, named `tag`) of a
/// link, as "<tag><…>, expected …", or "".
template <class Elements>
std::string first_empty(const Elements& elements, const std::string& tag) {
  for (const auto& e : elements) {
    if (!e || !e->geometry) continue;
    const std::string why = empty_primitive(*e->geometry);
    if (!why.empty()) return "<" + tag + ">" + why;
  }
  return {};
}

}  // namespace

void check_finite_numbers(const std::string& text, const std::string& source) {
  TiXmlDocument doc;
  doc.Parse(text.c_str());
  if (doc.Error()) return;  // urdfdom reports XML errors
  static const std::set<std::string> kNumeric = {
      "xyz", "rpy",   "value", "ixx",    "ixy",      "ixz",    "iyy",    "iyz",
      "izz", "lower", "upper", "effort", "velocity", "radius", "length", "size"};
  std::vector<std::pair<const TiXmlElement*, std::string>> todo;
  if (doc.RootElement() != nullptr) todo.emplace_back(doc.RootElement(), "");
  while (!todo.empty()) {
    const auto [el, owner_in] = todo.back();
    todo.pop_back();
    std::string owner = owner_in;
    const std::string tag = el->Value();
    if ((tag == "link" || tag == "joint") && el->Attribute("name") != nullptr)
      owner = tag + " '" + el->Attribute("name") + "'";
    for (const TiXmlAttribute* a = el->FirstAttribute(); a != nullptr; a = a->Next()) {
      if (!kNumeric.count(a->Name())) continue;
      std::istringstream tokens(a->Value());
      std::string tok;
      while (tokens >> tok) {
        char* end = nullptr;
        const double x = std::strtod(tok.c_str(), &end);
        if (end != tok.c_str() && *end == '\0' && !std::isfinite(x))
          throw ConfigError(source + ": " + (owner.empty() ? std::string("robot") : owner) + ": <" +
                            tag + " " + a->Name() + "=\"" + a->Value() +
                            "\"> is not finite, expected finite numbers");
      }
    }
    for (const TiXmlElement* c = el->FirstChildElement(); c != nullptr; c = c->NextSiblingElement())
      todo.emplace_back(c, owner);
  }
}

void check_link_geometry(const urdf::ModelInterface& model, const std::string& source) {
  for (const auto& [name, link] : model.links_) {
    std::string why = first_empty(link->collision_array, "collision");
    if (why.empty()) why = first_empty(link->visual_array, "visual");
    if (!why.empty()) throw ConfigError(source + ": link '" + name + "': " + why);
  }
}

}  // namespace hexdyn
