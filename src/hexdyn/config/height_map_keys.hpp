#pragma once
/// \file height_map_keys.hpp
/// Internal to config/: the keys of terrain.type height_map (docs/theory/stages.md#height-maps)
/// and the map they name, read once per file and settings and shared.
#include "hexdyn/config/scene_key_reader.hpp"
#include "hexdyn/core/scene.hpp"

namespace hexdyn::scene_keys {

/// Reads terrain.height_map.* into `t` (type kHeightMap): the file's grid (height_map_file.hpp)
/// placed by its resolution and origin, refused in one line with holes (a non-finite height:
/// their count and the first one's row and column); its foothold clearances
/// (prepare_height_map) by edge_height and max_slope; its reference line (t.slope_rad,
/// t.ground_height_m) by the slope given or a least-squares fit over every node.
void read_height_map(Reader& r, TerrainParams& t);

}  // namespace hexdyn::scene_keys
