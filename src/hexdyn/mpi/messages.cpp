#include "hexdyn/mpi/messages.hpp"

#include <cstdint>
#include <cstring>

#include "hexdyn/core/errors.hpp"

namespace hexdyn {
namespace {

void put_raw(std::vector<char>& b, const void* data, std::size_t n) {
  const std::size_t at = b.size();
  b.resize(at + n);
  if (n > 0) std::memcpy(b.data() + at, data, n);
}
void put_i64(std::vector<char>& b, std::int64_t v) { put_raw(b, &v, sizeof v); }
void put_f64(std::vector<char>& b, double v) { put_raw(b, &v, sizeof v); }
void put_bytes(std::vector<char>& b, const char* data, std::size_t n) {
  put_i64(b, static_cast<std::int64_t>(n));
  put_raw(b, data, n);
}

class Unpacker {
 public:
  explicit Unpacker(const std::vector<char>& b) : b_(b) {}
  std::int64_t i64() { return pod<std::int64_t>(); }
  double f64() { return pod<double>(); }
  std::string text() {
    const auto n = static_cast<std::size_t>(i64());
    need(n);
    std::string s(b_.data() + at_, n);
    at_ += n;
    return s;
  }
  std::vector<char> bytes() {
    const auto n = static_cast<std::size_t>(i64());
    need(n);
    std::vector<char> v(b_.begin() + static_cast<std::ptrdiff_t>(at_),
                        b_.begin() + static_cast<std::ptrdiff_t>(at_ + n));
    at_ += n;
    return v;
  }

 private:
  template <class T>
  T pod() {
    need(sizeof(T));
    T v;
    std::memcpy(&v, b_.data() + at_, sizeof v);
    at_ += sizeof v;
    return v;
  }
  void need(std::size_t n) const {
    if (at_ + n > b_.size()) throw Error("sweep: truncated message between ranks");
  }
  const std::vector<char>& b_;
  std::size_t at_ = 0;
};

}  // namespace

std::vector<char> pack_work(const ScenarioInput& in, bool keep_runs) {
  std::vector<char> b;
  put_i64(b, static_cast<std::int64_t>(in.index));
  put_i64(b, keep_runs ? 1 : 0);
  put_bytes(b, in.id.data(), in.id.size());
  put_bytes(b, in.yaml.data(), in.yaml.size());
  return b;
}

std::vector<char> pack_stop() {
  std::vector<char> b;
  put_i64(b, -1);
  return b;
}

std::vector<char> pack_result(const Finished& f) {
  std::vector<char> b;
  put_i64(b, static_cast<std::int64_t>(f.index));
  put_i64(b, static_cast<std::int64_t>(f.status));
  put_f64(b, f.wall_time_s);
  put_bytes(b, f.message.data(), f.message.size());
  put_bytes(b, f.checkpoint.data(), f.checkpoint.size());
  return b;
}

Finished unpack_result(const std::vector<char>& bytes, int rank) {
  Unpacker u(bytes);
  Finished f;
  f.index = static_cast<std::size_t>(u.i64());
  f.status = static_cast<ScenarioStatus>(u.i64());
  f.wall_time_s = u.f64();
  f.message = u.text();
  f.checkpoint = u.bytes();
  f.rank = rank;
  return f;
}

std::optional<Work> unpack_work(const std::vector<char>& bytes) {
  Unpacker u(bytes);
  const std::int64_t index = u.i64();
  if (index < 0) return std::nullopt;
  Work w;
  w.input.index = static_cast<std::size_t>(index);
  w.keep_runs = u.i64() != 0;
  w.input.id = u.text();
  w.input.yaml = u.text();
  return w;
}

}  // namespace hexdyn
