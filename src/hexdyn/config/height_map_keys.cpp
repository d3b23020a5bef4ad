// terrain.type height_map (height_map_keys.hpp).
#include "hexdyn/config/height_map_keys.hpp"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <tuple>

#include "hexdyn/config/height_map_file.hpp"
#include "hexdyn/config/inputs.hpp"
#include "hexdyn/config/table_keys.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn::scene_keys {

namespace {

using MapKey =
    std::tuple<std::string, std::string, std::string, double, double, double, double, double>;

/// The maps read in this process by file digest and settings (a sweep reads each once).
std::mutex cache_mutex;
std::map<MapKey, std::shared_ptr<const HeightMap>> cache;

/// Refuses a grid with holes in one line: their count and the first one's place.
void check_holes(const Reader& r, const HeightGrid& g, const std::string& path) {
  std::size_t holes = 0, first = 0;
  for (std::size_t k = 0; k < g.z.size(); ++k)
    if (!std::isfinite(g.z[k]) && holes++ == 0) first = k;
  if (holes > 0)
    r.fail("terrain.height_map.file",
           "'" + path + "' has " + std::to_string(holes) + " holes (heights that are NaN or " +
               "infinite), the first at row " + std::to_string(first / g.nx) + ", column " +
               std::to_string(first % g.nx) +
               "; expected a height at every node (fill them first)");
}

/// The least-squares line z = a + b y through every node; with `slope` given, b = tan(slope).
void fit_reference(const HeightMap& m, const std::optional<double>& slope, TerrainParams& t) {
  double sy = 0.0, sz = 0.0, syy = 0.0, syz = 0.0;
  const double n = static_cast<double>(m.nx) * m.ny;
  for (int i = 0; i < m.ny; ++i)
    for (int j = 0; j < m.nx; ++j) {
      const double y = m.y(i), z = m.at(i, j);
      sy += y;
      sz += z;
      syy += y * y;
      syz += y * z;
    }
  const double my = sy / n, mz = sz / n;
  const double b = slope ? std::tan(*slope) : (syz / n - my * mz) / (syy / n - my * my);
  t.slope_rad = std::atan(b);
  t.slope_origin_y_m = 0.0;
  t.ground_height_m = mz - b * my;
}

}  // namespace

void read_height_map(Reader& r, TerrainParams& t) {
  const std::string file_key = "terrain.height_map.file";
  const std::string path = r.string_or(file_key, "");
  if (path.empty())
    r.fail(file_key,
           "missing, this key is required (the map's .npy or HDF5 file, relative to "
           "the scene file)");
  const std::string dataset = r.string_or("terrain.height_map.dataset", "elevation");
  const double resolution = number_key(r, "terrain.height_map.resolution");
  const std::vector<double> origin = numbers_key(r, "terrain.height_map.origin");
  const double edge_height = number_key(r, "terrain.height_map.edge_height");
  const double max_slope = number_key(r, "terrain.height_map.max_slope");
  std::optional<double> slope;
  if (r.given("terrain.height_map.slope"))
    slope = number_key_or(r, "terrain.height_map.slope", 0.0);
  else
    (void)r.has("terrain.height_map.slope");  // counted as asked for
  if (const auto why = why_not_input_file(path))
    r.fail(file_key, "'" + path + "': " + *why + ", expected " + kHeightMapExpected);
  InputFile bytes;
  try {
    bytes = read_input_bytes(path, kMaxHeightMapBytes, kHeightMapExpected);
  } catch (const ConfigError& e) {
    r.fail(file_key, e.what());
  }
  const MapKey key{bytes.sha256, dataset,   path,        resolution,
                   origin[0],    origin[1], edge_height, max_slope};
  std::shared_ptr<const HeightMap> map;
  {
    const std::lock_guard<std::mutex> lock(cache_mutex);
    if (const auto it = cache.find(key); it != cache.end()) map = it->second;
  }
  if (!map) {
    const HeightGrid g = read_height_grid(*bytes.text, path, dataset,
                                          r.file() + ": " + file_key + ": '" + path + "'");
    check_holes(r, g, path);
    auto m = std::make_shared<HeightMap>();
    m->nx = g.nx;
    m->ny = g.ny;
    m->x0_m = origin[0];
    m->y0_m = origin[1];
    m->resolution_m = resolution;
    m->z_m = g.z;
    prepare_height_map(*m, edge_height, max_slope);
    map = m;
    const std::lock_guard<std::mutex> lock(cache_mutex);
    if (cache.size() >= 4) cache.clear();
    cache.emplace(key, map);
  }
  t.map = map;
  t.map_edge_height_m = edge_height;
  t.map_max_slope_rad = max_slope;
  fit_reference(*map, slope, t);
}

}  // namespace hexdyn::scene_keys
