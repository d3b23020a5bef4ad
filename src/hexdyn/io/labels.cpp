#include "hexdyn/io/labels.hpp"

#include <hdf5.h>
#include <hdf5_hl.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <sstream>
#include <string_view>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5_detail.hpp"

namespace hexdyn {
namespace {

namespace s = schema;

[[noreturn]] void fail(const H5Writer& w, const std::string& what) {
  H5Eclear2(H5E_DEFAULT);
  throw IoError("cannot write '" + w.file_path() + "': " + what);
}

std::vector<std::string> split(const char* words) {
  std::istringstream in(words);
  std::vector<std::string> out;
  for (std::string word; in >> word;) out.push_back(word);
  return out;
}

/// The coordinate of indices declared for dimension `dim`, or nullptr.
const s::DatasetSpec* index_coordinate(const std::string& dim) {
  for (const s::DatasetSpec& c : s::kResultIndexCoordinates)
    if (dim == c.path + 1) return &c;
  for (const s::DatasetSpec* c : {&s::kScenarioCoordinate, &s::kProbeCoordinate})
    if (dim == c->path + 1) return c;
  return nullptr;
}

/// Length of each axis of the dataset at `path`.
std::vector<std::uint64_t> extent(const H5Writer& w, const std::string& path) {
  const hid_t d = H5Dopen2(w.id(), path.c_str(), H5P_DEFAULT);
  if (d < 0) fail(w, "cannot open '" + path + "' to label it");
  const hid_t space = H5Dget_space(d);
  const int rank = H5Sget_simple_extent_ndims(space);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank > 0) H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  H5Sclose(space);
  H5Dclose(d);
  return {dims.begin(), dims.end()};
}

/// Number of words of a space-separated list.
std::int64_t word_count(const char* words) {
  return static_cast<std::int64_t>(split(words).size());
}

/// The group holding the object at `path` ("" for one directly below the file root).
std::string parent_of(const std::string& path) { return path.substr(0, path.rfind('/')); }

}  // namespace

void Labeller::add(const s::DatasetSpec& spec, const std::string& path, const std::string& key) {
  std::vector<std::string> dims = split(s::dimension_names(spec.shape));
  for (std::string& d : dims)
    if (const auto p = d.find("{key}"); p != std::string::npos) d.replace(p, 5, key);
  entries_.push_back(
      {&spec, root_ + (path.empty() ? std::string(spec.path) : path), dims, key, {}});
}

std::string swept_quantity(const std::string& key) {
  std::string name = key.substr(key.rfind('.') + 1);  // the whole key when it has no dot
  std::replace(name.begin(), name.end(), '_', ' ');
  return name;
}

void Labeller::write_long_names_and_flags() {
  for (const Entry& e : entries_) {
    // An axis's values are named by the quantity they sweep; its other datasets (labels,
    // case keys) lead their own long name with it.
    const std::string_view own = e.spec->long_name;
    const std::string name = e.key.empty() ? std::string(own)
                             : own == s::kSweptQuantityName
                                 ? swept_quantity(e.key)
                                 : swept_quantity(e.key) + ": " + std::string(own);
    w_.set_text_attribute(e.path, s::kLongNameAttribute, name);
    for (const s::FlagSpec& f : s::kFlags) {
      if (std::string_view(f.path) != e.spec->path) continue;
      std::vector<std::int64_t> codes;
      for (std::int64_t c = 0; c < word_count(f.meanings); ++c) codes.push_back(c);
      w_.set_int_array_attribute_like(e.path, "flag_values", codes);
      w_.set_text_attribute(e.path, "flag_meanings", f.meanings);
    }
  }
}

std::map<std::string, std::uint64_t> Labeller::check_extents() {
  std::map<std::string, std::uint64_t> length;  // from the first dataset that uses the dimension
  for (Entry& e : entries_) {
    e.extent = extent(w_, e.path);
    if (e.extent.size() != e.dims.size())
      fail(w_, e.path + " has " + std::to_string(e.extent.size()) + " axes, its shape " +
                   std::to_string(e.dims.size()));
    for (std::size_t k = 0; k < e.dims.size(); ++k) length.emplace(e.dims[k], e.extent[k]);
  }
  for (const Entry& e : entries_)
    for (std::size_t k = 0; k < e.dims.size(); ++k)
      if (e.extent[k] != length[e.dims[k]])
        fail(w_, e.path + " axis " + std::to_string(k) + " has " + std::to_string(e.extent[k]) +
                     " entries, dimension '" + e.dims[k] + "' " +
                     std::to_string(length[e.dims[k]]));
  return length;
}

void Labeller::create_root_coordinate(const std::string& dim, std::uint64_t n) {
  const std::string path = root_ + "/" + dim;
  if (H5Lexists(w_.id(), path.c_str(), H5P_DEFAULT) > 0) return;  // written by the writer
  const s::DatasetSpec* c = index_coordinate(dim);
  if (c == nullptr) fail(w_, "dimension '" + dim + "' has no coordinate variable " + path);
  std::vector<std::int32_t> index(n);
  for (std::uint64_t i = 0; i < n; ++i) index[i] = static_cast<std::int32_t>(i);
  w_.write_int32(path, {static_cast<std::size_t>(n)}, index, c->units);
  w_.set_text_attribute(path, s::kLongNameAttribute, c->long_name);
}

void Labeller::create_group_coordinate(const std::string& group, const std::string& dim) {
  const std::string path = group + "/" + dim;
  if (H5Lexists(w_.id(), path.c_str(), H5P_DEFAULT) <= 0) {
    if (H5Ocopy(w_.id(), (root_ + "/" + dim).c_str(), w_.id(), path.c_str(), H5P_DEFAULT,
                H5P_DEFAULT) < 0)
      fail(w_, "cannot copy the coordinate " + root_ + "/" + dim + " to " + path);
    return;
  }
  for (const Entry& e : entries_)  // a declared dataset that is the coordinate itself
    if (e.path == path && e.dims == std::vector<std::string>{dim}) return;
  fail(w_, path + " is not the coordinate variable of dimension '" + dim + "'");
}

void Labeller::finish() {
  write_long_names_and_flags();
  const std::map<std::string, std::uint64_t> length = check_extents();
  if (!scales_) return;
  // Every dimension's coordinate at the root, then in each group whose datasets use it
  // (copies of the root's, made before it becomes a scale).
  std::map<std::string, std::string> coordinates;  // path -> dimension
  for (const auto& [dim, n] : length) {
    create_root_coordinate(dim, n);
    coordinates[root_ + "/" + dim] = dim;
  }
  for (const Entry& e : entries_)
    for (const std::string& dim : e.dims)
      if (const std::string group = parent_of(e.path); group != root_) {
        if (coordinates.emplace(group + "/" + dim, dim).second) create_group_coordinate(group, dim);
      }
  std::map<std::string, h5detail::Handle> scales;
  for (const auto& [path, dim] : coordinates) {
    const std::vector<std::uint64_t> own = extent(w_, path);
    if (own.size() != 1 || own[0] != length.at(dim))
      fail(w_, path + " is not a coordinate of length " + std::to_string(length.at(dim)));
    h5detail::Handle id(H5Dopen2(w_.id(), path.c_str(), H5P_DEFAULT), H5Dclose);
    if (!id.valid() || H5DSset_scale(id.get(), dim.c_str()) < 0)
      fail(w_, "cannot make " + path + " a dimension scale");
    scales.emplace(path, std::move(id));
  }
  for (const Entry& e : entries_) {
    const std::string group = parent_of(e.path);
    if (e.dims.empty() || coordinates.count(e.path) > 0) continue;  // a scale itself
    const h5detail::Handle d(H5Dopen2(w_.id(), e.path.c_str(), H5P_DEFAULT), H5Dclose);
    for (std::size_t k = 0; k < e.dims.size(); ++k)
      if (!d.valid() || H5DSattach_scale(d.get(), scales.at(group + "/" + e.dims[k]).get(),
                                         static_cast<unsigned>(k)) < 0)
        fail(w_, "cannot attach dimension '" + e.dims[k] + "' to " + e.path);
  }
}

namespace {

/// The declaration of a result dataset by its path below the result's root, or nullptr.
const s::DatasetSpec* result_spec(const std::string& path) {
  const s::DatasetSpec* found = nullptr;
  const auto find = [&](const auto& list) {
    for (const s::DatasetSpec& d : list)
      if (path == d.path) found = &d;
  };
  find(s::kModelDatasets);
  find(s::kUrdfRobotDatasets);
  find(s::kSphereFootDatasets);
  find(s::kHeightMapDatasets);
  find(s::kKinematicDatasets);
  find(s::kDynamicsDatasets);
  find(s::kRequiredFrictionDatasets);
  find(s::kDriveTrainDatasets);
  find(s::kThermalDatasets);
  find(s::kResultCoordinates);
  find(s::kResultIndexCoordinates);
  return found;
}

herr_t collect_dataset(hid_t, const char* name, const H5O_info_t* info, void* out) {
  if (info->type == H5O_TYPE_DATASET)
    static_cast<std::vector<std::string>*>(out)->push_back(std::string("/") + name);
  return 0;
}

}  // namespace

void label_result_group(H5Writer& w, const std::string& root) {
  std::vector<std::string> paths;
  const hid_t g = H5Gopen2(w.id(), root.c_str(), H5P_DEFAULT);
  const herr_t visited =
      g < 0 ? -1 : H5Ovisit(g, H5_INDEX_NAME, H5_ITER_NATIVE, collect_dataset, &paths);
  if (g >= 0) H5Gclose(g);
  if (visited < 0) fail(w, "cannot list the datasets of " + root);
  Labeller labels(w, root);
  for (const std::string& p : paths) {
    const s::DatasetSpec* spec = result_spec(p);
    if (spec == nullptr) fail(w, root + p + " is not declared in io/schema.hpp's result lists");
    labels.add(*spec);
  }
  labels.finish();
}

}  // namespace hexdyn
