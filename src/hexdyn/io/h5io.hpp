#pragma once
/// \file h5io.hpp
/// A small RAII layer over the HDF5 C API: write a file of plain datasets (each with a
/// `units` attribute unless its units string is empty) and read it back. Paths are absolute HDF5
/// paths
/// ("/joints/torque"); parent groups are created on demand. Arrays are contiguous and
/// row-major (C order), shapes given as `dims` (outermost first; {} is a scalar).
/// Strings are variable-length UTF-8. Numeric datasets of at least kChunkMinBytes are
/// chunked along their first axis and compressed with shuffle + deflate (level
/// kDeflateLevel), which every HDF5 and netCDF-4 reader decodes; smaller ones, scalars
/// and strings are contiguous (docs/user/output.md#compression).
///
/// Every HDF5 failure throws `IoError` naming the file and the object path; HDF5's own
/// error printing is switched off. Not thread-safe (neither is serial HDF5).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace hexdyn {

/// Datasets of fewer bytes stay contiguous; larger numeric ones are chunked and compressed.
inline constexpr std::size_t kChunkMinBytes = 4096;
/// Target size of one chunk [bytes] (whole rows along the first axis).
inline constexpr std::size_t kChunkBytes = 1024 * 1024;
/// zlib level of the deflate filter.
inline constexpr int kDeflateLevel = 4;
/// Half the entries of a chunk-index B-tree node (HDF5's istore_k; its default is 32).
inline constexpr unsigned kChunkIndexK = 2;

/// Switches off HDF5's automatic error-stack printing (idempotent).
void silence_hdf5_errors();

/// A new file-access property list (hid_t; the caller closes it) for writing: objects in
/// the oldest format that holds them, at most HDF5 1.8's, as netCDF-4 writes them; groups
/// track link creation order (as netCDF-4's do), which makes them compact 1.8 groups without
/// B-trees. The low bound stays the earliest: a 1.8 superblock (version 2) carries
/// status flags that an in-memory file's image (H5Writer::close) leaves set, and such an
/// image fails its checksum when read.
std::int64_t file_access_properties();

/// Creates (truncates) an HDF5 file and writes datasets and attributes into it.
/// The file is closed by `close()` (which reports errors) or by the destructor.
///
/// Write path (docs/user/faults.md#full-disk): the file is built in memory (HDF5 core
/// driver, no backing store) and close() writes its image with write(2) through a
/// descriptor opened at construction. HDF5 hides the OS's errno behind its error
/// stack, and a failed H5Fclose on a full disk leaves a half-closed file that crashed
/// H5_term_library at exit; in memory HDF5 never meets the disk, and write(2) reports
/// ENOSPC or EDQUOT as the OS's words. The cost is memory: the file's size, twice for a
/// moment at close(). Objects are closed with H5F_CLOSE_STRONG, so an object left open by
/// an error never keeps the file half-open.
class H5Writer {
 public:
  /// Creates `file_path` (O_NOFOLLOW: a symbolic link is refused), replacing an existing
  /// regular file. Throws IoError. `compress` false writes every dataset contiguous and
  /// uncompressed.
  explicit H5Writer(const std::string& file_path, bool compress = true);
  ~H5Writer();
  H5Writer(const H5Writer&) = delete;
  H5Writer& operator=(const H5Writer&) = delete;

  const std::string& file_path() const { return file_path_; }
  /// hid_t of the open (in-memory) file, for the HDF5 calls this class does not wrap
  /// (io/labels.cpp; H5Ocopy of kept runs into a sweep file); -1 when closed.
  std::int64_t id() const { return file_; }

  /// Creates the group and any missing parents; no-op if it exists.
  void create_group(const std::string& group_path);

  /// Double array of shape `dims` from `values` (row-major, size = product of dims).
  void write_doubles(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                     std::span<const double> values, const std::string& units);
  /// Scalar double (dataspace rank 0).
  void write_scalar(const std::string& dataset_path, double value, const std::string& units);
  void write_int8(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                  std::span<const std::int8_t> values, const std::string& units);
  void write_int32(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                   std::span<const std::int32_t> values, const std::string& units);
  /// Scalar variable-length UTF-8 string.
  void write_string(const std::string& dataset_path, const std::string& value,
                    const std::string& units);
  /// 1-D array of variable-length UTF-8 strings (may be empty).
  void write_strings(const std::string& dataset_path, const std::vector<std::string>& values,
                     const std::string& units);
  /// Array of variable-length UTF-8 strings of shape `dims` (row-major).
  void write_strings(const std::string& dataset_path, const std::vector<std::size_t>& dims,
                     const std::vector<std::string>& values, const std::string& units);

  /// Attributes on an existing group or dataset ("/" is the root); replaced if present.
  void set_string_attribute(const std::string& object_path, const std::string& name,
                            const std::string& value);
  /// A fixed-length UTF-8 string, stored in the object header (netCDF: a text attribute);
  /// faster to read than a variable-length one, which lives in the file's global heap.
  void set_text_attribute(const std::string& object_path, const std::string& name,
                          const std::string& value);
  void set_double_attribute(const std::string& object_path, const std::string& name, double value);
  void set_int_attribute(const std::string& object_path, const std::string& name,
                         std::int64_t value);
  /// 1-D attribute of integers stored in the element type of the dataset `object_path`
  /// (CF `flag_values` must have the variable's type).
  void set_int_array_attribute_like(const std::string& object_path, const std::string& name,
                                    const std::vector<std::int64_t>& values);

  /// Finishes the file and writes it to disk (write(2), fsync); throws IoError naming the
  /// file and the OS's reason ("No space left on device"), or Interrupted when a SIGTERM
  /// or SIGINT arrives meanwhile (interrupt.hpp). The file is closed in any case.
  void close();

 private:
  std::int64_t file_ = -1;  ///< hid_t of the open file, -1 when closed
  int fd_ = -1;             ///< descriptor of `file_path_` on disk, until close()
  std::string file_path_;
  bool compress_ = true;
};

/// Values of a numeric dataset converted to double, with its shape.
struct H5DoubleArray {
  std::vector<std::size_t> dims;  ///< {} for a scalar
  std::vector<double> values;     ///< row-major
};

/// Opens an HDF5 file read-only (for tests and tools).
class H5Reader {
 public:
  /// Throws IoError if the file cannot be opened as HDF5.
  explicit H5Reader(const std::string& file_path);
  ~H5Reader();
  H5Reader(const H5Reader&) = delete;
  H5Reader& operator=(const H5Reader&) = delete;

  /// True if a group or dataset exists at the path (parents may be missing).
  bool exists(const std::string& object_path) const;
  bool is_dataset(const std::string& object_path) const;
  bool is_group(const std::string& object_path) const;
  /// Shape of a dataset; {} for a scalar.
  std::vector<std::size_t> dims(const std::string& dataset_path) const;
  /// Stored element type: "float64", "int8", "int32", "int64", "string" or "other".
  std::string element_type(const std::string& dataset_path) const;

  /// Any numeric dataset, converted to double.
  H5DoubleArray read_doubles(const std::string& dataset_path) const;
  /// Any integer dataset, converted to int64.
  std::vector<std::int64_t> read_ints(const std::string& dataset_path) const;
  /// Scalar string dataset (variable- or fixed-length).
  std::string read_string(const std::string& dataset_path) const;
  /// 1-D string dataset (variable- or fixed-length).
  std::vector<std::string> read_strings(const std::string& dataset_path) const;

  bool has_attribute(const std::string& object_path, const std::string& name) const;
  std::string string_attribute(const std::string& object_path, const std::string& name) const;
  double double_attribute(const std::string& object_path, const std::string& name) const;
  std::int64_t int_attribute(const std::string& object_path, const std::string& name) const;

 private:
  std::int64_t file_ = -1;  ///< hid_t
  std::string file_path_;
};

}  // namespace hexdyn
