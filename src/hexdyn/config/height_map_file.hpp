#pragma once
/// \file height_map_file.hpp
/// Internal to config/: the grid of a height map file (docs/theory/stages.md#height-maps):
/// a NumPy .npy array or a dataset of an HDF5 file, 2-D, rows along y and columns along x.
#include <string>
#include <vector>

namespace hexdyn {

/// A grid as read: ny rows (y) × nx columns (x), row-major.
struct HeightGrid {
  int ny = 0, nx = 0;
  std::vector<double> z;
};

/// The grid in `bytes`, the content of the file `path`: a .npy file (version 1 to 3, a 2-D array
/// of little-endian float64 or float32, C or Fortran order) when its name ends in .npy, an HDF5
/// file (.h5, .hdf5) whose 2-D dataset `dataset` is read as float64 otherwise. Throws
/// ConfigError "what: ..." (`what` names the key) for any other file, shape or type; holes are
/// the caller's to find.
HeightGrid read_height_grid(const std::string& bytes, const std::string& path,
                            const std::string& dataset, const std::string& what);

}  // namespace hexdyn
