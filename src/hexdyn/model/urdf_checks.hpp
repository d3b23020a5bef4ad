#pragma once
/// \file urdf_checks.hpp
/// Internal to the URDF reader (urdf_reader.cpp, target hexdyn_urdf_reader): the checks of a
/// description's values that need no leg structure. Each throws ConfigError of one line
/// "SOURCE: link|joint 'NAME': WHAT, expected WHAT" (docs/user/faults.md#sizes).
#include <string>

namespace urdf {
class ModelInterface;
}

namespace hexdyn {

/// NaN and inf in numeric attributes, on the XML text before urdfdom reads it (it turns
/// some into 0 without a word, and refuses others without naming the link or joint): the
/// first non-finite number names its <link> or <joint>, element and attribute.
void check_finite_numbers(const std::string& text, const std::string& source);

/// The primitive geometries of every link's <collision> and <visual> elements, as urdfdom
/// read them: a sphere's radius, each of a box's three sizes and a cylinder's radius and
/// length must be > 0 m (urdfdom takes 0 and negative sizes as given). The first other
/// names its link, element and value: "SOURCE: link 'foot': <collision><sphere radius="-0.01">,
/// expected a radius > 0 m".
void check_link_geometry(const urdf::ModelInterface& model, const std::string& source);

}  // namespace hexdyn
