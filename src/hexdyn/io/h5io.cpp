#include "hexdyn/io/h5io.hpp"

#include <fcntl.h>
#include <hdf5.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <type_traits>
#include <utility>

#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5_detail.hpp"
#include "hexdyn/process/interrupt.hpp"

namespace hexdyn {

static_assert(std::is_same_v<hid_t, std::int64_t>, "h5io.hpp stores hid_t as std::int64_t");

namespace {
/// Growth step of a file built in memory (HDF5 core driver) [bytes].
constexpr std::size_t kCoreIncrement = std::size_t{4} << 20;
/// Bytes per write(2) of a finished file: a signal is looked at between chunks.
constexpr std::size_t kWriteChunk = std::size_t{8} << 20;
}  // namespace

using namespace h5detail;

void silence_hdf5_errors() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

std::int64_t file_access_properties() {
  const hid_t fapl = H5Pcreate(H5P_FILE_ACCESS);
  H5Pset_libver_bounds(fapl, H5F_LIBVER_EARLIEST, H5F_LIBVER_V18);
  return fapl;
}

// ------------------------------------------------------------------ H5Writer

H5Writer::H5Writer(const std::string& file_path, bool compress)
    : file_path_(file_path), compress_(compress) {
  silence_hdf5_errors();
  // The bytes go to disk through this descriptor, at close(); HDF5 writes to memory.
  fd_ = ::open(file_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd_ < 0) throw IoError("cannot create '" + file_path_ + "': " + std::strerror(errno));
  // Chunk B-tree nodes of 2·kChunkIndexK entries: HDF5's default (32) spends 2.5 kB on
  // each chunked dataset, most of a small kept run's metadata.
  Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  Handle fapl(file_access_properties(), H5Pclose);
  if (!fcpl.valid() || !fapl.valid() || H5Pset_istore_k(fcpl.get(), kChunkIndexK) < 0 ||
      H5Pset_link_creation_order(fcpl.get(), H5P_CRT_ORDER_TRACKED) < 0 ||
      H5Pset_fapl_core(fapl.get(), kCoreIncrement, 0) < 0 ||
      H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG) < 0)
    fail(file_path_, "set up the in-memory file for", file_path_);
  file_ = H5Fcreate(file_path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get());
  if (file_ < 0) {
    ::close(fd_);
    fd_ = -1;
    fail(file_path_, "create file", file_path_);
  }
}

H5Writer::~H5Writer() {
  // Memory only: closing cannot fail for want of disk space. H5F_CLOSE_STRONG closes any
  // object left open, so H5_term_library at exit finds nothing half-closed.
  if (file_ >= 0) H5Fclose(file_);
  H5Eclear2(H5E_DEFAULT);
  if (fd_ >= 0) ::close(fd_);
}

void H5Writer::close() {
  if (file_ < 0) return;
  // The finished file as bytes, then the in-memory file closed (its memory freed) before
  // the bytes are written.
  std::vector<char> image;
  herr_t flushed = H5Fflush(file_, H5F_SCOPE_GLOBAL);
  const ssize_t size = flushed < 0 ? -1 : H5Fget_file_image(file_, nullptr, 0);
  if (size >= 0) {
    image.resize(static_cast<std::size_t>(size));
    if (H5Fget_file_image(file_, image.data(), image.size()) != size) flushed = -1;
  }
  const herr_t closed = H5Fclose(file_);
  file_ = -1;
  if (flushed < 0 || size < 0 || closed < 0) {
    ::close(fd_);
    fd_ = -1;
    fail(file_path_, "finish file", file_path_);
  }
  // write(2) tells why the disk refused (No space left on device, Disk quota exceeded).
  const auto io_fail = [&](const char* what, int err) {
    ::close(fd_);
    fd_ = -1;
    throw IoError("cannot write '" + file_path_ + "': " + what + std::strerror(err));
  };
  std::size_t done = 0;
  while (done < image.size()) {
    check_interrupt();
    const std::size_t chunk = std::min<std::size_t>(image.size() - done, kWriteChunk);
    const ssize_t w = ::write(fd_, image.data() + done, chunk);
    if (w < 0) {
      if (errno == EINTR) continue;
      io_fail("", errno);
    }
    done += static_cast<std::size_t>(w);
  }
  if (::fsync(fd_) != 0) io_fail("fsync failed: ", errno);
  if (::close(fd_) != 0) {
    fd_ = -1;
    throw IoError("cannot write '" + file_path_ + "': close failed: " + std::strerror(errno));
  }
  fd_ = -1;
}

void H5Writer::create_group(const std::string& group_path) {
  if (file_ < 0) fail(file_path_, "create group", group_path, "file is closed");
  if (group_path.empty() || group_path[0] != '/')
    fail(file_path_, "create group", group_path, "path must be absolute");
  if (group_path == "/") return;
  std::vector<std::string> chain = parent_prefixes(group_path);
  chain.push_back(group_path);
  for (const std::string& g : chain) {
    const htri_t exists = H5Lexists(file_, g.c_str(), H5P_DEFAULT);
    if (exists > 0) continue;
    if (exists < 0) fail(file_path_, "look up group", g);
    Handle gcpl(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
    if (!gcpl.valid() || H5Pset_link_creation_order(gcpl.get(), H5P_CRT_ORDER_TRACKED) < 0)
      fail(file_path_, "set up group", g);
    Handle h(H5Gcreate2(file_, g.c_str(), H5P_DEFAULT, gcpl.get(), H5P_DEFAULT), H5Gclose);
    if (!h.valid()) fail(file_path_, "create group", g);
  }
}

namespace {

void write_units(const std::string& file, hid_t dset, const std::string& path,
                 const std::string& units) {
  if (units.empty()) return;  // text and flags: no units (schema.hpp)
  Handle type = make_utf8_vlen_type();
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(dset, "units", type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  const char* ptr = units.c_str();
  if (!attr.valid() || H5Awrite(attr.get(), type.get(), &ptr) < 0)
    fail(file, "write attribute 'units' of", path);
}

/// Creation properties: chunked along the first axis with shuffle + deflate for a numeric
/// dataset of at least kChunkMinBytes, else the default (contiguous).
Handle creation_properties(const std::vector<std::size_t>& dims, hid_t file_type, bool compress) {
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  const std::size_t element = H5Tget_size(file_type);
  if (!compress || dims.empty() || H5Tget_class(file_type) == H5T_STRING ||
      element_count(dims) * element < kChunkMinBytes)
    return dcpl;
  std::vector<hsize_t> chunk(dims.begin(), dims.end());
  const std::size_t row = element_count(dims) / dims[0] * element;
  // As many chunks as kChunkBytes asks for, of equal rows (no mostly empty last chunk).
  const std::size_t chunks = (dims[0] * row + kChunkBytes - 1) / kChunkBytes;
  chunk[0] = std::max<hsize_t>((dims[0] + chunks - 1) / chunks, 1);
  if (H5Pset_chunk(dcpl.get(), static_cast<int>(chunk.size()), chunk.data()) < 0 ||
      H5Pset_shuffle(dcpl.get()) < 0 || H5Pset_deflate(dcpl.get(), kDeflateLevel) < 0)
    dcpl.reset();
  return dcpl;
}

/// Parent groups of `path` must exist; `count` elements of `mem_type` at `data`.
void write_dataset(const std::string& file, hid_t file_id, const std::string& path,
                   const std::vector<std::size_t>& dims, hid_t file_type, hid_t mem_type,
                   const void* data, std::size_t count, const std::string& units, bool compress) {
  if (count != element_count(dims))
    fail(file, "write dataset", path,
         "got " + std::to_string(count) + " values for shape " + join_dims(dims) + " (" +
             std::to_string(element_count(dims)) + " expected)");
  Handle space = make_space(dims);
  if (!space.valid()) fail(file, "create dataspace for", path);
  Handle dcpl = creation_properties(dims, file_type, compress);
  if (!dcpl.valid()) fail(file, "set the chunks and filters of", path);
  Handle dset(H5Dcreate2(file_id, path.c_str(), file_type, space.get(), H5P_DEFAULT, dcpl.get(),
                         H5P_DEFAULT),
              H5Dclose);
  if (!dset.valid()) fail(file, "create dataset", path);
  if (count > 0 && H5Dwrite(dset.get(), mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(file, "write dataset", path);
  write_units(file, dset.get(), path, units);
}

std::string parent_of(const std::string& path) {
  const std::size_t pos = path.rfind('/');
  return (pos == 0 || pos == std::string::npos) ? "/" : path.substr(0, pos);
}

}  // namespace

void H5Writer::write_doubles(const std::string& path, const std::vector<std::size_t>& dims,
                             std::span<const double> values, const std::string& units) {
  create_group(parent_of(path));
  write_dataset(file_path_, file_, path, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, values.data(),
                values.size(), units, compress_);
}

void H5Writer::write_scalar(const std::string& path, double value, const std::string& units) {
  write_doubles(path, {}, std::span<const double>(&value, 1), units);
}

void H5Writer::write_int8(const std::string& path, const std::vector<std::size_t>& dims,
                          std::span<const std::int8_t> values, const std::string& units) {
  create_group(parent_of(path));
  write_dataset(file_path_, file_, path, dims, H5T_STD_I8LE, H5T_NATIVE_INT8, values.data(),
                values.size(), units, compress_);
}

void H5Writer::write_int32(const std::string& path, const std::vector<std::size_t>& dims,
                           std::span<const std::int32_t> values, const std::string& units) {
  create_group(parent_of(path));
  write_dataset(file_path_, file_, path, dims, H5T_STD_I32LE, H5T_NATIVE_INT32, values.data(),
                values.size(), units, compress_);
}

void H5Writer::write_string(const std::string& path, const std::string& value,
                            const std::string& units) {
  create_group(parent_of(path));
  Handle type = make_utf8_vlen_type();
  if (!type.valid()) fail(file_path_, "create string type for", path);
  const char* ptr = value.c_str();
  write_dataset(file_path_, file_, path, {}, type.get(), type.get(), &ptr, 1, units, compress_);
}

void H5Writer::write_strings(const std::string& path, const std::vector<std::string>& values,
                             const std::string& units) {
  write_strings(path, {values.size()}, values, units);
}

void H5Writer::write_strings(const std::string& path, const std::vector<std::size_t>& dims,
                             const std::vector<std::string>& values, const std::string& units) {
  create_group(parent_of(path));
  Handle type = make_utf8_vlen_type();
  if (!type.valid()) fail(file_path_, "create string type for", path);
  std::vector<const char*> ptrs;
  ptrs.reserve(values.size());
  for (const std::string& s : values) ptrs.push_back(s.c_str());
  write_dataset(file_path_, file_, path, dims, type.get(), type.get(), ptrs.data(), ptrs.size(),
                units, compress_);
}

namespace {

void write_attribute(const std::string& file, hid_t file_id, const std::string& object_path,
                     const std::string& name, hid_t file_type, hid_t mem_type, const void* buf) {
  const std::string where = object_path + "@" + name;
  if (!link_chain_exists(file_id, object_path))
    fail(file, "write attribute", where, "object does not exist");
  Handle obj(H5Oopen(file_id, object_path.c_str(), H5P_DEFAULT), H5Oclose);
  if (!obj.valid()) fail(file, "open object for attribute", where);
  const htri_t exists = H5Aexists(obj.get(), name.c_str());
  if (exists < 0 || (exists > 0 && H5Adelete(obj.get(), name.c_str()) < 0))
    fail(file, "replace attribute", where);
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attr(H5Acreate2(obj.get(), name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  if (!attr.valid()) fail(file, "create attribute", where);
  if (H5Awrite(attr.get(), mem_type, buf) < 0) fail(file, "write attribute", where);
}

}  // namespace

void H5Writer::set_string_attribute(const std::string& object_path, const std::string& name,
                                    const std::string& value) {
  Handle type = make_utf8_vlen_type();
  if (!type.valid()) fail(file_path_, "create string type for", object_path);
  const char* ptr = value.c_str();
  write_attribute(file_path_, file_, object_path, name, type.get(), type.get(), &ptr);
}

void H5Writer::set_text_attribute(const std::string& object_path, const std::string& name,
                                  const std::string& value) {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  if (!type.valid() || H5Tset_size(type.get(), std::max<std::size_t>(value.size(), 1)) < 0 ||
      H5Tset_cset(type.get(), H5T_CSET_UTF8) < 0 || H5Tset_strpad(type.get(), H5T_STR_NULLTERM) < 0)
    fail(file_path_, "create string type for", object_path);
  write_attribute(file_path_, file_, object_path, name, type.get(), type.get(), value.c_str());
}

void H5Writer::set_double_attribute(const std::string& object_path, const std::string& name,
                                    double value) {
  write_attribute(file_path_, file_, object_path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void H5Writer::set_int_attribute(const std::string& object_path, const std::string& name,
                                 std::int64_t value) {
  write_attribute(file_path_, file_, object_path, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void H5Writer::set_int_array_attribute_like(const std::string& object_path, const std::string& name,
                                            const std::vector<std::int64_t>& values) {
  const std::string where = object_path + "@" + name;
  Handle d = Handle(H5Dopen2(file_, object_path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) fail(file_path_, "open dataset for attribute", where);
  Handle type(H5Dget_type(d.get()), H5Tclose);
  const hsize_t n = values.size();
  Handle space(H5Screate_simple(1, &n, nullptr), H5Sclose);
  if (H5Aexists(d.get(), name.c_str()) > 0) H5Adelete(d.get(), name.c_str());
  Handle attr(H5Acreate2(d.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose);
  if (!attr.valid() || H5Awrite(attr.get(), H5T_NATIVE_INT64, values.data()) < 0)
    fail(file_path_, "write attribute", where);
}

// ------------------------------------------------------------------ H5Reader

H5Reader::H5Reader(const std::string& file_path) : file_path_(file_path) {
  silence_hdf5_errors();
  file_ = H5Fopen(file_path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file_ < 0) fail(file_path_, "open file", file_path_);
}

H5Reader::~H5Reader() {
  if (file_ >= 0) H5Fclose(file_);
}

bool H5Reader::exists(const std::string& path) const {
  const bool found = !path.empty() && path[0] == '/' && link_chain_exists(file_, path);
  H5Eclear2(H5E_DEFAULT);
  return found;
}

namespace {

H5I_type_t object_kind(hid_t file, const std::string& path) {
  if (!link_chain_exists(file, path)) return H5I_BADID;
  Handle obj(H5Oopen(file, path.c_str(), H5P_DEFAULT), H5Oclose);
  return obj.valid() ? H5Iget_type(obj.get()) : H5I_BADID;
}

Handle open_dataset(const std::string& file, hid_t file_id, const std::string& path) {
  if (!link_chain_exists(file_id, path)) fail(file, "open dataset", path, "no such dataset");
  Handle d(H5Dopen2(file_id, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!d.valid()) fail(file, "open dataset", path);
  return d;
}

Handle open_attribute(const std::string& file, hid_t file_id, const std::string& object_path,
                      const std::string& name) {
  const std::string where = object_path + "@" + name;
  if (!link_chain_exists(file_id, object_path))
    fail(file, "read attribute", where, "object does not exist");
  Handle obj(H5Oopen(file_id, object_path.c_str(), H5P_DEFAULT), H5Oclose);
  if (!obj.valid()) fail(file, "open object of attribute", where);
  if (H5Aexists(obj.get(), name.c_str()) <= 0)
    fail(file, "read attribute", where, "no such attribute");
  Handle attr(H5Aopen(obj.get(), name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attr.valid()) fail(file, "open attribute", where);
  return attr;
}

std::vector<std::size_t> space_dims(hid_t space) {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank <= 0) return {};
  std::vector<hsize_t> h(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space, h.data(), nullptr);
  return std::vector<std::size_t>(h.begin(), h.end());
}

}  // namespace

bool H5Reader::is_dataset(const std::string& path) const {
  const bool r = object_kind(file_, path) == H5I_DATASET;
  H5Eclear2(H5E_DEFAULT);
  return r;
}

bool H5Reader::is_group(const std::string& path) const {
  const bool r = object_kind(file_, path) == H5I_GROUP;
  H5Eclear2(H5E_DEFAULT);
  return r;
}

std::vector<std::size_t> H5Reader::dims(const std::string& path) const {
  Handle d = open_dataset(file_path_, file_, path);
  Handle space(H5Dget_space(d.get()), H5Sclose);
  if (!space.valid()) fail(file_path_, "read shape of", path);
  return space_dims(space.get());
}

std::string H5Reader::element_type(const std::string& path) const {
  Handle d = open_dataset(file_path_, file_, path);
  Handle type(H5Dget_type(d.get()), H5Tclose);
  if (!type.valid()) fail(file_path_, "read type of", path);
  const std::size_t size = H5Tget_size(type.get());
  switch (H5Tget_class(type.get())) {
    case H5T_FLOAT:
      return size == 8 ? "float64" : "other";
    case H5T_INTEGER:
      if (H5Tget_sign(type.get()) != H5T_SGN_2) return "other";
      return size == 1 ? "int8" : size == 4 ? "int32" : size == 8 ? "int64" : "other";
    case H5T_STRING:
      return "string";
    default:
      return "other";
  }
}

H5DoubleArray H5Reader::read_doubles(const std::string& path) const {
  Handle d = open_dataset(file_path_, file_, path);
  Handle type(H5Dget_type(d.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    fail(file_path_, "read numbers from", path, "not numeric");
  Handle space(H5Dget_space(d.get()), H5Sclose);
  H5DoubleArray out;
  out.dims = space_dims(space.get());
  out.values.resize(element_count(out.dims));
  if (!out.values.empty() &&
      H5Dread(d.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data()) < 0)
    fail(file_path_, "read dataset", path);
  return out;
}

std::vector<std::int64_t> H5Reader::read_ints(const std::string& path) const {
  Handle d = open_dataset(file_path_, file_, path);
  Handle type(H5Dget_type(d.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_INTEGER)
    fail(file_path_, "read integers from", path, "not an integer dataset");
  Handle space(H5Dget_space(d.get()), H5Sclose);
  std::vector<std::int64_t> out(element_count(space_dims(space.get())));
  if (!out.empty() &&
      H5Dread(d.get(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.data()) < 0)
    fail(file_path_, "read dataset", path);
  return out;
}

std::string H5Reader::read_string(const std::string& path) const {
  const std::vector<std::string> all = read_strings(path);
  if (all.size() != 1)
    fail(file_path_, "read string", path, "holds " + std::to_string(all.size()) + " strings");
  return all.front();
}

std::vector<std::string> H5Reader::read_strings(const std::string& path) const {
  Handle d = open_dataset(file_path_, file_, path);
  return read_string_values(Source{d.get(), false}, file_path_, path);
}

bool H5Reader::has_attribute(const std::string& object_path, const std::string& name) const {
  bool found = false;
  if (link_chain_exists(file_, object_path)) {
    Handle obj(H5Oopen(file_, object_path.c_str(), H5P_DEFAULT), H5Oclose);
    found = obj.valid() && H5Aexists(obj.get(), name.c_str()) > 0;
  }
  H5Eclear2(H5E_DEFAULT);
  return found;
}

std::string H5Reader::string_attribute(const std::string& object_path,
                                       const std::string& name) const {
  const std::string where = object_path + "@" + name;
  Handle attr = open_attribute(file_path_, file_, object_path, name);
  std::vector<std::string> all = read_string_values(Source{attr.get(), true}, file_path_, where);
  if (all.size() != 1)
    fail(file_path_, "read string attribute", where,
         "holds " + std::to_string(all.size()) + " strings");
  return all.front();
}

double H5Reader::double_attribute(const std::string& object_path, const std::string& name) const {
  Handle attr = open_attribute(file_path_, file_, object_path, name);
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  double value = 0.0;
  if ((cls != H5T_FLOAT && cls != H5T_INTEGER) || H5Sget_simple_extent_npoints(space.get()) != 1 ||
      H5Aread(attr.get(), H5T_NATIVE_DOUBLE, &value) < 0)
    fail(file_path_, "read number attribute", object_path + "@" + name, "not a numeric scalar");
  return value;
}

std::int64_t H5Reader::int_attribute(const std::string& object_path,
                                     const std::string& name) const {
  Handle attr = open_attribute(file_path_, file_, object_path, name);
  Handle type(H5Aget_type(attr.get()), H5Tclose);
  Handle space(H5Aget_space(attr.get()), H5Sclose);
  std::int64_t value = 0;
  if (H5Tget_class(type.get()) != H5T_INTEGER || H5Sget_simple_extent_npoints(space.get()) != 1 ||
      H5Aread(attr.get(), H5T_NATIVE_INT64, &value) < 0)
    fail(file_path_, "read integer attribute", object_path + "@" + name, "not an integer scalar");
  return value;
}

}  // namespace hexdyn
