#include "hexdyn/mpi/messages.hpp"

#include <cstdint>
#include <cstring>
#include <memory>

#include "hexdyn/core/bytes.hpp"
#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

void put_raw(std::vector<char>& b, const void* data, std::size_t n) {
  const std::size_t at = b.size();
  b.resize(at + n);
  if (n > 0) std::memcpy(b.data() + at, data, n);
}
void put_i64(std::vector<char>& b, std::int64_t v) { put_pod(b, v); }
void put_f64(std::vector<char>& b, double v) { put_pod(b, v); }
void put_bytes(std::vector<char>& b, const char* data, std::size_t n) {
  put_i64(b, static_cast<std::int64_t>(n));
  put_raw(b, data, n);
}
void put_text(std::vector<char>& b, const std::string& s) { put_bytes(b, s.data(), s.size()); }

class Unpacker {
 public:
  explicit Unpacker(const std::vector<char>& b) : b_(b) {}
  std::int64_t i64() { return pod<std::int64_t>(); }
  double f64() { return pod<double>(); }
  std::size_t length() {
    const std::int64_t n = i64();
    if (n < 0) throw Error("sweep: malformed message between ranks");
    need(static_cast<std::size_t>(n));
    return static_cast<std::size_t>(n);
  }
  std::string text() {
    const std::size_t n = length();
    std::string s(b_.data() + at_, n);
    at_ += n;
    return s;
  }
  std::vector<char> bytes() {
    const std::size_t n = length();
    std::vector<char> v(b_.begin() + static_cast<std::ptrdiff_t>(at_),
                        b_.begin() + static_cast<std::ptrdiff_t>(at_ + n));
    at_ += n;
    return v;
  }
  bool done() const { return at_ == b_.size(); }

 private:
  template <class T>
  T pod() {
    need(sizeof(T));
    const T v = get_pod<T>(b_.data() + at_);
    at_ += sizeof v;
    return v;
  }
  void need(std::size_t n) const {
    if (n > b_.size() - at_) throw Error("sweep: truncated message between ranks");
  }
  const std::vector<char>& b_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<char> pack_spec(const SweepSpec& spec, const SweepIdentity& identity) {
  std::vector<char> b;
  for (std::uint64_t v : {identity.id, identity.base_scene, identity.build, identity.scenarios})
    put_pod(b, v);
  put_i64(b, identity.keep_runs ? 1 : 0);
  // The inputs: the identity's (absolute paths) and the spec's (/meta input_sha256 of a
  // kept run), each role, path, absolute path, SHA-256, and the spec's with the bytes rank 0
  // read, which every rank's scenarios use (config/inputs.hpp keep_input).
  for (const std::vector<InputFile>* list : {&identity.inputs, &spec.inputs}) {
    put_i64(b, static_cast<std::int64_t>(list->size()));
    for (const InputFile& f : *list) {
      for (const std::string* t : {&f.role, &f.path, &f.absolute, &f.sha256}) put_text(b, *t);
      put_i64(b, f.text ? 1 : 0);
      if (f.text) put_text(b, *f.text);
    }
  }
  put_text(b, spec.name);
  put_text(b, spec.base_path);
  put_text(b, spec.base_tree_yaml);
  put_i64(b, static_cast<std::int64_t>(spec.axes.size()));
  for (const SweepAxis& a : spec.axes) {
    put_text(b, a.key);
    put_i64(b, static_cast<std::int64_t>(a.size()));
    for (std::size_t v = 0; v < a.size(); ++v) {
      put_text(b, a.values[v]);
      put_text(b, a.labels[v]);
    }
    put_i64(b, static_cast<std::int64_t>(a.case_keys.size()));
    for (const std::string& k : a.case_keys) put_text(b, k);
    for (const auto& values : a.case_values)
      for (const std::string& v : values) put_text(b, v);
  }
  return b;
}

SweepSpec unpack_spec(const std::vector<char>& bytes, SweepIdentity& identity) {
  Unpacker u(bytes);
  SweepSpec spec;
  for (std::uint64_t* v :
       {&identity.id, &identity.base_scene, &identity.build, &identity.scenarios})
    *v = static_cast<std::uint64_t>(u.i64());
  identity.keep_runs = u.i64() != 0;
  for (std::vector<InputFile>* list : {&identity.inputs, &spec.inputs}) {
    const std::int64_t n = u.i64();
    if (n < 0) throw Error("sweep: malformed message between ranks");
    for (std::int64_t i = 0; i < n; ++i) {
      InputFile f;
      for (std::string* t : {&f.role, &f.path, &f.absolute, &f.sha256}) *t = u.text();
      if (u.i64() != 0) f.text = std::make_shared<const std::string>(u.text());
      list->push_back(std::move(f));
    }
  }
  spec.name = u.text();
  spec.base_path = u.text();
  spec.base_tree_yaml = u.text();
  const std::int64_t axes = u.i64();
  for (std::int64_t i = 0; i < axes; ++i) {
    SweepAxis a;
    a.key = u.text();
    const std::int64_t n = u.i64();
    for (std::int64_t v = 0; v < n; ++v) {
      a.values.push_back(u.text());
      a.labels.push_back(u.text());
    }
    const std::int64_t keys = u.i64();
    if (keys < 0) throw Error("sweep: malformed message between ranks");
    for (std::int64_t k = 0; k < keys; ++k) a.case_keys.push_back(u.text());
    if (keys > 0)
      for (std::int64_t v = 0; v < n; ++v) {
        std::vector<std::string> values;
        for (std::int64_t k = 0; k < keys; ++k) values.push_back(u.text());
        a.case_values.push_back(std::move(values));
      }
    spec.axes.push_back(std::move(a));
  }
  return spec;
}

std::vector<char> pack_work(const std::vector<std::size_t>& indices) {
  std::vector<char> b;
  b.reserve(8 * (indices.size() + 1));
  put_i64(b, static_cast<std::int64_t>(indices.size()));
  for (std::size_t i : indices) put_i64(b, static_cast<std::int64_t>(i));
  return b;
}

std::vector<char> pack_stop() {
  std::vector<char> b;
  put_i64(b, -1);
  return b;
}

std::optional<std::vector<std::size_t>> unpack_work(const std::vector<char>& bytes) {
  Unpacker u(bytes);
  const std::int64_t n = u.i64();
  if (n < 0) return std::nullopt;
  std::vector<std::size_t> indices(static_cast<std::size_t>(n));
  for (auto& i : indices) i = static_cast<std::size_t>(u.i64());
  return indices;
}

std::vector<char> pack_interrupted(int signal) {
  std::vector<char> b;
  put_i64(b, signal);
  return b;
}

int unpack_interrupted(const std::vector<char>& bytes) {
  Unpacker u(bytes);
  return static_cast<int>(u.i64());
}

void append_result(std::vector<char>& b, const Finished& f) {
  put_i64(b, static_cast<std::int64_t>(f.index));
  put_f64(b, f.cost_s);
  put_i64(b, f.crashed ? 1 : 0);
  put_text(b, f.reason);
  put_bytes(b, f.payload.data(), f.payload.size());
}

void check_row_joints(const ScenarioSummary& row, int joints, const std::string& id, int rank) {
  if (joints == 0 || row.joints == 0 || row.joints == joints) return;
  throw Error("sweep: scenario " + id + ": the result from rank " + std::to_string(rank) + " has " +
              std::to_string(row.joints) + " joints, the sweep's robot " + std::to_string(joints));
}

std::vector<Finished> unpack_results(const std::vector<char>& bytes) {
  Unpacker u(bytes);
  std::vector<Finished> out;
  while (!u.done()) {
    Finished f;
    f.index = static_cast<std::size_t>(u.i64());
    f.cost_s = u.f64();
    f.crashed = u.i64() != 0;
    f.reason = u.text();
    f.payload = u.bytes();
    out.push_back(std::move(f));
  }
  return out;
}

}  // namespace hexdyn
