#include "hexdyn/io/h5_detail.hpp"

#include "hexdyn/core/errors.hpp"

namespace hexdyn::h5detail {

namespace {

herr_t innermost_error(unsigned n, const H5E_error2_t* err, void* client_data) {
  if (n == 0 && err != nullptr && err->desc != nullptr)
    *static_cast<std::string*>(client_data) = err->desc;
  return 0;
}

}  // namespace

std::string hdf5_error_detail() {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, innermost_error, &detail);
  H5Eclear2(H5E_DEFAULT);
  return detail;
}

void fail(const std::string& file, const std::string& what, const std::string& object,
          const std::string& reason) {
  std::string msg = "HDF5 file '" + file + "': cannot " + what + " '" + object + "'";
  const std::string hdf5_detail = hdf5_error_detail();  // also clears the stack
  const std::string detail = reason.empty() ? hdf5_detail : reason;
  if (!detail.empty()) msg += ": " + detail;
  throw IoError(msg);
}

std::string join_dims(const std::vector<std::size_t>& dims) {
  std::string s = "(";
  for (std::size_t i = 0; i < dims.size(); ++i) {
    if (i > 0) s += ',';
    s += std::to_string(dims[i]);
  }
  return s + ")";
}

std::size_t element_count(const std::vector<std::size_t>& dims) {
  std::size_t n = 1;
  for (std::size_t d : dims) n *= d;
  return n;
}

/// Prefixes "/a", "/a/b", ... of an absolute path "/a/b/c", without the path itself.
std::vector<std::string> parent_prefixes(const std::string& path) {
  std::vector<std::string> out;
  for (std::size_t pos = path.find('/', 1); pos != std::string::npos; pos = path.find('/', pos + 1))
    out.push_back(path.substr(0, pos));
  return out;
}

bool link_chain_exists(hid_t file, const std::string& path) {
  if (path == "/") return true;
  for (const std::string& prefix : parent_prefixes(path))
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  return H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0;
}

Handle make_space(const std::vector<std::size_t>& dims) {
  if (dims.empty()) return Handle(H5Screate(H5S_SCALAR), H5Sclose);
  std::vector<hsize_t> h(dims.begin(), dims.end());
  return Handle(H5Screate_simple(static_cast<int>(h.size()), h.data(), nullptr), H5Sclose);
}

Handle make_utf8_vlen_type() {
  Handle t(H5Tcopy(H5T_C_S1), H5Tclose);
  if (t.valid() &&
      (H5Tset_size(t.get(), H5T_VARIABLE) < 0 || H5Tset_cset(t.get(), H5T_CSET_UTF8) < 0))
    t.reset();
  return t;
}

namespace {

herr_t reclaim_vlen(hid_t mem_type, hid_t space, void* buf) {
#if H5_VERSION_GE(1, 12, 0)
  return H5Treclaim(mem_type, space, H5P_DEFAULT, buf);
#else
  return H5Dvlen_reclaim(mem_type, space, H5P_DEFAULT, buf);
#endif
}

}  // namespace

std::vector<std::string> read_string_values(const Source& src, const std::string& file,
                                            const std::string& where) {
  Handle ftype(src.type(), H5Tclose);
  Handle space(src.space(), H5Sclose);
  if (!ftype.valid() || !space.valid()) fail(file, "query type of", where);
  if (H5Tget_class(ftype.get()) != H5T_STRING)
    fail(file, "read strings from", where, "not a string");
  const hssize_t n_signed = H5Sget_simple_extent_npoints(space.get());
  if (n_signed < 0) fail(file, "query size of", where);
  const auto n = static_cast<std::size_t>(n_signed);
  std::vector<std::string> out;
  out.reserve(n);
  const H5T_cset_t cset = H5Tget_cset(ftype.get());
  Handle mtype(H5Tcopy(H5T_C_S1), H5Tclose);
  if (H5Tis_variable_str(ftype.get()) > 0) {
    H5Tset_size(mtype.get(), H5T_VARIABLE);
    H5Tset_cset(mtype.get(), cset);
    std::vector<char*> ptrs(n, nullptr);
    if (n > 0 && src.read(mtype.get(), ptrs.data()) < 0) fail(file, "read strings from", where);
    for (char* p : ptrs) out.emplace_back(p ? p : "");
    if (n > 0) reclaim_vlen(mtype.get(), space.get(), ptrs.data());
  } else {
    const std::size_t size = H5Tget_size(ftype.get());
    H5Tset_size(mtype.get(), size);
    H5Tset_cset(mtype.get(), cset);
    H5Tset_strpad(mtype.get(), H5T_STR_NULLPAD);
    std::vector<char> buf(n * size + 1, '\0');
    if (n > 0 && src.read(mtype.get(), buf.data()) < 0) fail(file, "read strings from", where);
    for (std::size_t i = 0; i < n; ++i) {
      const char* begin = buf.data() + i * size;
      std::size_t len = 0;
      while (len < size && begin[len] != '\0') ++len;
      out.emplace_back(begin, len);
    }
  }
  return out;
}

}  // namespace hexdyn::h5detail
