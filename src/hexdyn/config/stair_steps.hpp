#pragma once
/// \file stair_steps.hpp
/// Internal to config/: the stairs' keys beyond the uniform ones (docs/theory/stages.md#terrain):
/// `terrain.steps` as a list of steps and landings, `terrain.nosing`, and the perturbations a
/// sweep varies (`terrain.riser_scale`, `terrain.step_offset`).
#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn::scene_keys {

/// Reads the stairs of `t` (type kStairs already set): the count or the list of
/// `terrain.steps`, the uniform keys (required with a count, the defaults of the entries with
/// a list), the nosing and the perturbations. Every bad step is named, one line each, in one
/// ConfigError: "FILE: terrain.steps[k].field: got VALUE, expected WHAT" (k from 1). A list
/// that is uniform (equal risers, goings and nosings, no landing) is read as uniform stairs,
/// so that it gives today's stairs bit for bit.
void read_stairs(Reader& r, TerrainParams& t);

}  // namespace hexdyn::scene_keys
