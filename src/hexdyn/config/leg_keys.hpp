#pragma once
/// \file leg_keys.hpp
/// Internal to config/: a key that holds one vector for every leg, or one per leg of the
/// robot's n legs (docs/user/configuration.md#robot-from-a-urdf):
///
///   KEY: [a, b, c]                        every leg
///   KEY: [[a, b, c], ... n of them]       L1 … Ln in leg order (/model/leg_names)
///   KEY: {L2: [a, b, c], L5: [...]}       by leg name
///
/// A vector has its leg's length: three numbers for a point; a joint pose has one angle per
/// joint of its leg. Every failure is one line "SOURCE: KEY: got VALUE, expected WHAT" (a map's
/// entry is named KEY.L2, a list's item by its number and leg). The resolved tree records the
/// key as given, its numbers as read.
#include <optional>
#include <string>

#include "hexdyn/config/scene_key_reader.hpp"

namespace hexdyn {

/// What a per-leg key holds, for reading and for messages.
struct LegVectorKey {
  std::string path;         ///< dotted key path, "robot.nominal_pose"
  std::string unit;         ///< of every number, "rad"
  scene_keys::Range range;  ///< allowed for each number
  bool every_leg = false;   ///< a map must name every leg (else legs not named are none)
};

/// The legs a per-leg key is read for. `legs` 0: not known yet (the key is read before the
/// robot), then a list of kMinLegs … kMaxLegs entries and the names L1 … L8 are taken, and
/// the count is checked where the legs are known.
struct LegKeyShape {
  int legs = 0;
  LegArray<std::string> names;  ///< "L1", … (the first `legs`)
  LegArray<int> sizes{};        ///< numbers per leg's vector
  /// True: a vector holds a leg's joint angles, "[coxa, femur, tibia]" for three joints,
  /// "[j1, …, jm]" for m; false: a point "[x, y, z]".
  bool joints = false;
};

/// The shape of a key of one point per leg, legs not known yet.
LegKeyShape point_legs();

/// The key as read: one vector for every leg, or one per leg named.
struct LegKeyValues {
  bool given = false;
  int count = 0;  ///< 1: one for every leg; else the list's length or 1 + the last leg named
  LegArray<std::optional<LegVector>> by_leg;  ///< every leg's, or the legs named
};

/// The key's vectors (none where the key is absent or a map does not name the leg). The key
/// counts as asked for either way.
LegKeyValues read_leg_vectors(scene_keys::Reader& r, const LegVectorKey& key,
                              const LegKeyShape& shape);

/// "[coxa, femur, tibia] rad, each a number in [a, b] (every leg); or 4 of them: a list in leg
/// order L1 … L4, or a map by leg name L1 … L4": what the key allows, for messages.
std::string leg_key_forms(const LegVectorKey& key, const LegKeyShape& shape);

}  // namespace hexdyn
