#pragma once
/// \file h5_detail.hpp
/// Internal helpers of io/h5io.cpp (not installed, not part of the public surface): an
/// owning HDF5 identifier, error text from HDF5's error stack, and reading strings from a
/// dataset or an attribute.
#include <hdf5.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace hexdyn::h5detail {

/// Owns one HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  ~Handle() { reset(); }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, -1)), closer_(other.closer_) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, -1);
      closer_ = other.closer_;
    }
    return *this;
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0) closer_(id_);
    id_ = -1;
  }

 private:
  hid_t id_;
  Closer closer_;
};

/// The most specific message on HDF5's error stack (empty if none); clears the stack.
std::string hdf5_error_detail();

/// Throws IoError "HDF5 file 'FILE': cannot WHAT 'OBJECT': DETAIL", DETAIL being `reason`
/// or else the innermost message of HDF5's error stack (which is cleared).
[[noreturn]] void fail(const std::string& file, const std::string& what, const std::string& object,
                       const std::string& reason = {});

/// "(d0,d1,...)".
std::string join_dims(const std::vector<std::size_t>& dims);
/// Product of the dims (1 for a scalar).
std::size_t element_count(const std::vector<std::size_t>& dims);
/// Prefixes "/a", "/a/b", ... of an absolute path "/a/b/c", without the path itself.
std::vector<std::string> parent_prefixes(const std::string& path);
/// True when every link of `path` exists in `file` ("/" always).
bool link_chain_exists(hid_t file, const std::string& path);
/// A simple dataspace of `dims` ({}: scalar).
Handle make_space(const std::vector<std::size_t>& dims);
/// A variable-length UTF-8 string type (invalid on failure).
Handle make_utf8_vlen_type();

/// A dataset or an attribute, read through the same calls.
struct Source {
  hid_t id;
  bool attribute;
  hid_t type() const { return attribute ? H5Aget_type(id) : H5Dget_type(id); }
  hid_t space() const { return attribute ? H5Aget_space(id) : H5Dget_space(id); }
  herr_t read(hid_t mem_type, void* buf) const {
    return attribute ? H5Aread(id, mem_type, buf)
                     : H5Dread(id, mem_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf);
  }
};

/// All strings of a string dataset or attribute (variable- or fixed-length). `file` and
/// `where` name the object in error messages.
std::vector<std::string> read_string_values(const Source& src, const std::string& file,
                                            const std::string& where);

}  // namespace hexdyn::h5detail
