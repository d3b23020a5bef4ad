// Height map files: .npy and HDF5 (height_map_file.hpp).
#include "hexdyn/config/height_map_file.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <cstdint>
#include <cstring>
#include <regex>
#include <string>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {

namespace {

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// The .npy format (numpy.lib.format): magic, version, header length, a Python dict literal
/// {'descr': '<f8', 'fortran_order': False, 'shape': (ny, nx), }, then the data.
HeightGrid read_npy(const std::string& b, const std::string& what) {
  const auto bad = [&](const std::string& why) {
    throw ConfigError(what + ": " + why +
                      ", expected a .npy file of a 2-D float64 or float32 array");
  };
  if (b.size() < 10 || b.compare(0, 6, "\x93NUMPY") != 0) bad("not a .npy file (no magic string)");
  const int major = static_cast<unsigned char>(b[6]);
  std::size_t header_len = 0, start = 0;
  if (major == 1) {
    header_len = static_cast<unsigned char>(b[8]) | (static_cast<unsigned char>(b[9]) << 8);
    start = 10;
  } else if (major == 2 || major == 3) {
    if (b.size() < 12) bad("a truncated header");
    std::uint32_t n = 0;
    std::memcpy(&n, b.data() + 8, 4);  // little-endian hosts (core/bytes.hpp's assumption)
    header_len = n;
    start = 12;
  } else {
    bad(".npy format version " + std::to_string(major));
  }
  if (start + header_len > b.size()) bad("a truncated header");
  const std::string header = b.substr(start, header_len);
  std::smatch m;
  if (!std::regex_search(header, m, std::regex(R"('descr'\s*:\s*'([^']*)')")))
    bad("no 'descr' in its header");
  const std::string descr = m[1];
  const bool f8 = descr == "<f8", f4 = descr == "<f4";
  if (!f8 && !f4) bad("element type '" + descr + "'");
  const bool fortran = std::regex_search(header, std::regex(R"('fortran_order'\s*:\s*True)"));
  if (!std::regex_search(header, m, std::regex(R"('shape'\s*:\s*\(([^)]*)\))")))
    bad("no 'shape' in its header");
  std::vector<long long> shape;
  const std::string dims = m[1];
  const std::regex number(R"(\d+)");
  for (std::sregex_iterator it(dims.begin(), dims.end(), number), end; it != end; ++it)
    shape.push_back(std::stoll(it->str()));
  if (shape.size() != 2) bad("an array of " + std::to_string(shape.size()) + " dimensions");
  if (shape[0] < 2 || shape[1] < 2 || shape[0] * shape[1] > 40000000LL)
    bad("shape (" + std::to_string(shape[0]) + ", " + std::to_string(shape[1]) +
        "), at least 2 x 2 and at most 4e7 heights");
  HeightGrid g;
  g.ny = static_cast<int>(shape[0]);
  g.nx = static_cast<int>(shape[1]);
  const std::size_t n = static_cast<std::size_t>(g.ny) * g.nx, item = f8 ? 8 : 4;
  const std::size_t data = start + header_len;
  if (b.size() - data != n * item)
    bad(std::to_string(b.size() - data) + " bytes of data for " + std::to_string(n) + " heights");
  g.z.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    // Fortran order: element (i, j) at j * ny + i.
    const std::size_t i = fortran ? k % g.ny : k / g.nx, j = fortran ? k / g.ny : k % g.nx;
    double v = 0.0;
    if (f8) {
      std::memcpy(&v, b.data() + data + k * 8, 8);
    } else {
      float f = 0.0f;
      std::memcpy(&f, b.data() + data + k * 4, 4);
      v = f;
    }
    g.z[i * g.nx + j] = v;
  }
  return g;
}

/// A 2-D dataset of an HDF5 file image.
HeightGrid read_h5(const std::string& b, const std::string& dataset, const std::string& what) {
  const auto bad = [&](const std::string& why) {
    throw ConfigError(what + ": " + why + ", expected an HDF5 file with a 2-D dataset '" + dataset +
                      "' of heights (terrain.height_map.dataset)");
  };
  H5E_auto2_t func = nullptr;
  void* data = nullptr;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  struct Restore {
    H5E_auto2_t f;
    void* d;
    ~Restore() { H5Eset_auto2(H5E_DEFAULT, f, d); }
  } restore{func, data};
  // Flags 0: the library copies the image and frees its copy; `b` stays the caller's.
  const hid_t file = H5LTopen_file_image(const_cast<char*>(b.data()), b.size(), 0);
  if (file < 0) bad("not an HDF5 file");
  struct Closer {
    hid_t f = -1, d = -1, s = -1;
    ~Closer() {
      if (s >= 0) H5Sclose(s);
      if (d >= 0) H5Dclose(d);
      if (f >= 0) H5Fclose(f);
    }
  } c{file};
  if (H5Lexists(file, dataset.c_str(), H5P_DEFAULT) <= 0) bad("no dataset '" + dataset + "'");
  c.d = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  if (c.d < 0) bad("'" + dataset + "' is no dataset");
  c.s = H5Dget_space(c.d);
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_ndims(c.s);
  if (rank != 2) bad("'" + dataset + "' has " + std::to_string(rank) + " dimensions");
  H5Sget_simple_extent_dims(c.s, dims, nullptr);
  if (dims[0] < 2 || dims[1] < 2 || dims[0] * dims[1] > 40000000ULL)
    bad("shape (" + std::to_string(dims[0]) + ", " + std::to_string(dims[1]) +
        "), at least 2 x 2 and at most 4e7 heights");
  HeightGrid g;
  g.ny = static_cast<int>(dims[0]);
  g.nx = static_cast<int>(dims[1]);
  g.z.resize(static_cast<std::size_t>(dims[0] * dims[1]));
  if (H5Dread(c.d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, g.z.data()) < 0)
    bad("'" + dataset + "' cannot be read as numbers");
  return g;
}

}  // namespace

HeightGrid read_height_grid(const std::string& bytes, const std::string& path,
                            const std::string& dataset, const std::string& what) {
  if (ends_with(path, ".npy")) return read_npy(bytes, what);
  if (ends_with(path, ".h5") || ends_with(path, ".hdf5")) return read_h5(bytes, dataset, what);
  throw ConfigError(what + ": got '" + path +
                    "', expected a file whose name ends in .npy, .h5 or .hdf5");
}

}  // namespace hexdyn
