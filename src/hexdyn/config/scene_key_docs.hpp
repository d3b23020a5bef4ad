#pragma once
/// \file scene_key_docs.hpp
/// The key tables of docs/user/configuration.md, written from scene_key_table.hpp: one
/// Markdown table per section (key | allowed | default | meaning). The program
/// hexdyn_scene_key_tables prints them and docs/gen_config_tables.py puts them in the page.
#include <string>
#include <string_view>
#include <vector>

namespace hexdyn {

/// The sections of the table that the docs list, in order of their first row.
std::vector<std::string> scene_key_sections();

/// The Markdown table of the rows of `section`, header included, one line per row.
std::string scene_key_markdown(std::string_view section);

/// The table of the keys of an actuator entry (config/actuators.hpp actuator_keys).
std::string actuator_key_markdown();

/// Every section's table, then the actuator entry's ("actuators"), between the marker lines
/// of its generated region:
/// "<!-- BEGIN GENERATED: SECTION -->", the table, "<!-- END GENERATED -->".
std::string scene_key_regions();

/// A number as the docs write it: "0.02", "1e-4", "1e6", "π/2", "−10" (a minus sign), "∞".
std::string doc_number(double x);

}  // namespace hexdyn
