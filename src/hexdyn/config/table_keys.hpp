#pragma once
/// \file table_keys.hpp
/// Internal to config/: reading scene keys by their rows of scene_key_table.hpp, so that a
/// key's path, range, choices and default are written once, in the table. The scene
/// reader's code names a key by its path (an instance of a `*` row: "robot.coxa.length");
/// the row gives the rest. A required key that is absent is an error; an optional one takes
/// its field's value in a default-constructed Scene (core/scene.hpp), or for a choice without
/// a field its first word.
#include <string>
#include <string_view>
#include <vector>

#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/config/scene_key_table.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn::scene_keys {

/// The Scene whose fields are the defaults of the optional keys.
const Scene& default_scene();

/// One number, required or with its default.
double number_key(Reader& r, const std::string& path);
/// One number with a default that depends on other keys (contact.static_friction).
double number_key_or(Reader& r, const std::string& path, double def);
/// One integer, required or with its default.
int integer_key(Reader& r, const std::string& path);
/// A list of the row's count of numbers; `def` for an optional key (null: required).
std::vector<double> numbers_key(Reader& r, const std::string& path,
                                const std::vector<double>* def = nullptr);
Vec3 vec3_key(Reader& r, const std::string& path, const Vec3* def = nullptr);
/// One of the row's words, required or with its default.
std::string choice_key(Reader& r, const std::string& path);

/// Reads every row of `section` that the table reads (KeyRead::kTable), in table order,
/// into `s` through the rows' fields.
void read_table_keys(Reader& r, Scene& s, std::string_view section);

/// `resolved` (a Reader's resolved tree) with the keys of each group the table reads
/// (KeyRead::kTable) in the order of the table's rows, those without a row after them in the
/// order read: the resolved configuration lists keys as the docs do, whichever code read them.
YAML::Node in_table_order(const YAML::Node& resolved);

}  // namespace hexdyn::scene_keys
