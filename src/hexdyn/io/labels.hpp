#pragma once
/// \file labels.hpp
/// Labels the datasets of a file for netCDF-4 readers (xarray, ncdump;
/// docs/user/output.md#dimensions-and-coordinates): a `long_name` on each, CF
/// `flag_values` and `flag_meanings` on the datasets of codes (schema::kFlags), and an
/// HDF5 dimension scale per axis. The dimensions of a dataset are those of its shape
/// (schema::dimension_names); dimension D has its coordinate variable at ROOT/D, ROOT being
/// the file root or the group of a kept run, and a copy of it (values, storage, `units`,
/// `long_name`) at G/D in every group G below ROOT whose datasets use D: the datasets of G
/// are attached to G/D, so that a group opened alone (xarray.open_dataset(file, group=G))
/// has its coordinates (schema.hpp, "group coordinates"). A dataset declared at G/D on the
/// dimension D alone (an envelope's /axes/tread_depth) is that coordinate itself. A
/// coordinate of indices (/impact, /message, /scenario, /probe, ...) is created 0..n−1 at
/// ROOT when missing; labelled ones (/leg, /joint, an axis's values, ...) are written by the
/// file's writer and recorded here.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/schema.hpp"

namespace hexdyn {

/// The long name of a sweep axis's datasets: the quantity its key sweeps, the key's last
/// word with spaces ("terrain.riser_height" → "riser height"; a cases axis's name as it is),
/// so that labelled readers write "riser height [m]".
std::string swept_quantity(const std::string& key);

class Labeller {
 public:
  /// Labels datasets below `root` ("" the file root, "/runs/000012" a kept run);
  /// `dimension_scales` false writes long names, flags and index coordinates only.
  Labeller(H5Writer& w, std::string root, bool dimension_scales = true)
      : w_(w), root_(std::move(root)), scales_(dimension_scales) {}

  /// Records the written dataset of `spec` at root + `path` (default: spec.path); `key`
  /// names the dimension that stands for "{key}" (a sweep axis), and the dataset's long name
  /// is then the quantity it sweeps (swept_quantity: "riser height").
  void add(const schema::DatasetSpec& spec, const std::string& path = {},
           const std::string& key = {});

  /// Writes long names and flags, creates the missing index coordinates and the groups'
  /// copies, makes every coordinate a dimension scale and attaches it to each recorded
  /// dataset's axis. Throws IoError naming the dataset when an axis's length differs from its
  /// coordinate's, a dimension has no coordinate variable, or G/D holds other data.
  void finish();

 private:
  struct Entry {
    const schema::DatasetSpec* spec;
    std::string path;  ///< absolute in the file
    std::vector<std::string> dims;
    std::string key;                      ///< the sweep axis's key, or empty
    std::vector<std::uint64_t> extent{};  ///< length of each axis, as written
  };
  void write_long_names_and_flags();
  /// The length of each dimension; throws unless every dataset agrees with it.
  std::map<std::string, std::uint64_t> check_extents();
  void create_root_coordinate(const std::string& dim, std::uint64_t n);
  void create_group_coordinate(const std::string& group, const std::string& dim);

  H5Writer& w_;
  std::string root_;
  bool scales_;
  std::vector<Entry> entries_;
};

/// Labels the result below `root` of an open file (a kept run copied into a sweep file,
/// whose object references HDF5 cannot copy): each dataset's declaration is looked up by
/// its path in the result lists of schema.hpp. Throws IoError for an undeclared dataset.
void label_result_group(H5Writer& w, const std::string& root);

}  // namespace hexdyn
