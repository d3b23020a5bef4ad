#pragma once
/// \file key_units.hpp
/// The unit of every numeric scene key (docs/user/configuration.md#keys-by-group), as a
/// UDUNITS-2 string, from the key's row of scene_key_table.hpp. A sweep file writes
/// it as the `units` of an axis over that key (io/schema.hpp kAxisNumbers).
#include <string>

namespace hexdyn {

/// The SI unit of the dotted scene key `key` ("terrain.riser_height" → "m",
/// "gait.duty_factor" → "1"); "" for a key whose values are words or whose unit cannot be
/// written (contact.stiffness, N/m^e with the exponent e of the scene), and for a key
/// not in the table.
std::string scene_key_units(const std::string& key);

}  // namespace hexdyn
