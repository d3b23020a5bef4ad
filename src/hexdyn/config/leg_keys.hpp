#pragma once
/// \file leg_keys.hpp
/// Internal to config/: a key that holds one 3-vector for every leg, or one per leg:
///
///   KEY: [a, b, c]                     every leg
///   KEY: [[a, b, c], ... six of them]  L1 … L6 in leg order (/model/leg_names)
///   KEY: {L2: [a, b, c], L5: [...]}    by leg name
///
/// Every failure is one line "SOURCE: KEY: got VALUE, expected WHAT" (a map's entry is named
/// KEY.L2, a list's item by its number and leg). The resolved tree records the key as given,
/// its numbers as read.
#include <array>
#include <optional>
#include <string>

#include "hexdyn/config/scene_key_reader.hpp"

namespace hexdyn {

/// What a per-leg key holds, for reading and for messages.
struct LegVectorKey {
  std::string path;         ///< dotted key path, "robot.nominal_pose"
  std::string meaning;      ///< the three numbers, "[coxa, femur, tibia] rad"
  scene_keys::Range range;  ///< allowed for each number
  bool every_leg = false;   ///< a map must name all six legs (else legs not named are none)
};

/// The key's vector per leg, L1 … L6; none where the key is absent or a map does not name
/// the leg. The key counts as asked for either way.
std::array<std::optional<Vec3>, kLegs> read_leg_vectors(scene_keys::Reader& r,
                                                        const LegVectorKey& key);

}  // namespace hexdyn
