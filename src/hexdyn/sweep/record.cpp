#include "hexdyn/sweep/record.hpp"

#include <unistd.h>

#include <array>
#include <atomic>
#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <system_error>

#include "hexdyn/core/bytes.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/io/h5io.hpp"
#include "hexdyn/io/output.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

/// Slicing-by-8 tables of the reflected polynomial 0xEDB88320.
struct CrcTables {
  std::array<std::array<std::uint32_t, 256>, 8> t{};
  CrcTables() {
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[0][i] = c;
    }
    for (std::uint32_t i = 0; i < 256; ++i)
      for (int s = 1; s < 8; ++s) t[s][i] = (t[s - 1][i] >> 8) ^ t[0][t[s - 1][i] & 0xFFu];
  }
};
const CrcTables kCrc;
static_assert(std::endian::native == std::endian::little,
              "crc32's slicing reads words in little-endian order");

void put_bytes(std::vector<char>& b, const char* data, std::size_t n) {
  put_pod(b, static_cast<std::uint64_t>(n));
  b.insert(b.end(), data, data + n);
}

class Reader {
 public:
  Reader(const char* data, std::size_t size) : d_(data), n_(size) {}
  template <class T>
  T get() {
    need(sizeof(T));
    const T v = get_pod<T>(d_ + at_);
    at_ += sizeof v;
    return v;
  }
  std::size_t length() {
    const auto n = get<std::uint64_t>();
    need(n);
    return static_cast<std::size_t>(n);
  }
  std::size_t at() const { return at_; }
  void skip(std::size_t n) { at_ += n; }
  const char* here() const { return d_ + at_; }
  bool done() const { return at_ == n_; }

 private:
  void need(std::uint64_t k) const {
    if (k > n_ - at_) throw IoError("scenario record: truncated payload");
  }
  const char* d_;
  std::size_t n_, at_ = 0;
};

std::atomic<unsigned> scratch_counter{0};

}  // namespace

std::uint32_t crc32(const void* data, std::size_t size, std::uint32_t crc) {
  const auto* p = static_cast<const unsigned char*>(data);
  std::uint32_t c = ~crc;
  while (size >= 8) {
    std::uint32_t lo, hi;
    std::memcpy(&lo, p, 4);
    std::memcpy(&hi, p + 4, 4);
    lo ^= c;  // little-endian hosts (x86-64, aarch64): bytes in memory order
    c = kCrc.t[7][lo & 0xFF] ^ kCrc.t[6][(lo >> 8) & 0xFF] ^ kCrc.t[5][(lo >> 16) & 0xFF] ^
        kCrc.t[4][lo >> 24] ^ kCrc.t[3][hi & 0xFF] ^ kCrc.t[2][(hi >> 8) & 0xFF] ^
        kCrc.t[1][(hi >> 16) & 0xFF] ^ kCrc.t[0][hi >> 24];
    p += 8;
    size -= 8;
  }
  while (size-- > 0) c = kCrc.t[0][(c ^ *p++) & 0xFF] ^ (c >> 8);
  return ~c;
}

std::uint64_t fnv1a64(std::string_view text, std::uint64_t h) {
  for (unsigned char ch : text) {
    h ^= ch;
    h *= 0x100000001b3ULL;
  }
  return h;
}

/// The summary's numbers in record order: one list for writing and reading (S is
/// ScenarioSummary or const ScenarioSummary).
template <class S>
auto double_fields(S& s) {
  return std::array{&s.duration_s,
                    &s.distance_m,
                    &s.energy_J,
                    &s.cost_of_transport,
                    &s.peak_impact_force_N,
                    &s.peak_power_W,
                    &s.peak_contact_force_N,
                    &s.grid_energy_error,
                    &s.grid_peak_error,
                    &s.wall_time_s,
                    &s.energy_electrical_J,
                    &s.energy_copper_loss_J,
                    &s.energy_friction_loss_J,
                    &s.energy_regenerated_J,
                    &s.cost_of_transport_electrical,
                    &s.peak_electrical_power_W,
                    &s.thermal_load,
                    &s.peak_winding_temperature_max_degC,
                    &s.time_to_winding_limit_min_s,
                    &s.required_friction_support,
                    &s.required_friction_support_time_s,
                    &s.required_friction_transient,
                    &s.required_friction_transient_time_s,
                    &s.peak_utilized_friction,
                    &s.positive_work_J,
                    &s.negative_work_J,
                    &s.p_success,
                    &s.p_success_low,
                    &s.p_success_high};
}

/// The summary's integer fields after the sample counts, in record order.
template <class S>
auto int_fields(S& s) {
  return std::array{&s.required_friction_support_leg,
                    &s.required_friction_transient_leg,
                    &s.no_friction_samples,
                    &s.slip_samples,
                    &s.robust_replays,
                    &s.replays_slipped,
                    &s.replays_stubbed,
                    &s.replays_saturated,
                    &s.replays_fell,
                    &s.replays_drifted};
}

void append_record(std::vector<char>& b, const ScenarioRecord& r) {
  const ScenarioSummary& s = r.summary;
  put_pod(b, static_cast<std::uint64_t>(s.index));
  put_pod(b, static_cast<std::int8_t>(s.status));
  put_bytes(b, s.message.data(), s.message.size());
  put_pod(b, static_cast<std::int32_t>(s.samples));
  put_pod(b, static_cast<std::int32_t>(s.relaxed_samples));
  put_pod(b, static_cast<std::int32_t>(s.failed_samples));
  put_pod(b, static_cast<std::int32_t>(s.relaxed_gait_samples));
  for (const int* v : int_fields(s)) put_pod(b, static_cast<std::int32_t>(*v));
  for (const double* v : double_fields(s)) put_pod(b, *v);
  if (s.joints < 0 || s.joints > kMaxJoints)
    throw IoError("scenario record: " + std::to_string(s.joints) + " joints, expected 0 to " +
                  std::to_string(kMaxJoints));
  put_pod(b, static_cast<std::int32_t>(s.joints));
  for (const auto* a : per_joint_metrics(s))
    for (int k = 0; k < s.joints; ++k) put_pod(b, (*a)[static_cast<std::size_t>(k)]);
  put_bytes(b, r.run_image.data(), r.run_image.size());
}

std::vector<char> encode_record(const ScenarioRecord& record) {
  std::vector<char> b;
  b.reserve(1200 + record.summary.message.size() + record.run_image.size());
  append_record(b, record);
  return b;
}

ScenarioRecord decode_record(const char* data, std::size_t size, bool with_image,
                             std::size_t* image_offset, std::size_t* image_size) {
  Reader u(data, size);
  ScenarioRecord r;
  ScenarioSummary& s = r.summary;
  s.index = static_cast<std::size_t>(u.get<std::uint64_t>());
  const auto status = u.get<std::int8_t>();
  if (status < 0 || status > static_cast<int>(kLastScenarioStatus))
    throw IoError("scenario record: status " + std::to_string(status) + " out of range");
  s.status = static_cast<ScenarioStatus>(status);
  const std::size_t m = u.length();
  s.message.assign(u.here(), m);
  u.skip(m);
  s.samples = u.get<std::int32_t>();
  s.relaxed_samples = u.get<std::int32_t>();
  s.failed_samples = u.get<std::int32_t>();
  s.relaxed_gait_samples = u.get<std::int32_t>();
  for (int* v : int_fields(s)) *v = u.get<std::int32_t>();
  for (double* v : double_fields(s)) *v = u.get<double>();
  s.joints = u.get<std::int32_t>();
  if (s.joints < 0 || s.joints > kMaxJoints)
    throw IoError("scenario record: " + std::to_string(s.joints) + " joints, expected 0 to " +
                  std::to_string(kMaxJoints));
  for (auto* a : per_joint_metrics(s)) {
    a->fill(std::numeric_limits<double>::quiet_NaN());  // the capacity beyond the robot's
    for (int k = 0; k < s.joints; ++k) (*a)[static_cast<std::size_t>(k)] = u.get<double>();
  }
  const std::size_t k = u.length();
  if (image_offset) *image_offset = u.at();
  if (image_size) *image_size = k;
  if (with_image) r.run_image.assign(u.here(), u.here() + k);
  u.skip(k);
  if (!u.done()) throw IoError("scenario record: bytes after the payload");
  return r;
}

std::vector<char> encode_run_image(const RunResult& run, const std::string& scratch_dir) {
  const std::string tmp =
      (fs::path(scratch_dir) / (".hexdyn-run-" + std::to_string(::getpid()) + "-" +
                                std::to_string(scratch_counter++) + ".h5"))
          .string();
  try {
    {
      H5Writer w(tmp, run.compress);
      write_result_layout(w, run, kRunImageGroup, false);  // scales: once copied
      w.close();
    }
    std::ifstream in(tmp, std::ios::binary);
    if (!in) throw IoError("cannot read '" + tmp + "'");
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    fs::remove(tmp);
    return bytes;
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace hexdyn
