#include "hexdyn/sweep/journal.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "hexdyn/core/bytes.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/sweep/record.hpp"

namespace hexdyn {
namespace {

constexpr char kJournalMagic[8] = {'H', 'X', 'D', 'J', 'R', 'N', '0', '2'};
constexpr char kJournalMagicV1[8] = {'H', 'X', 'D', 'J', 'R', 'N', '0', '1'};
constexpr std::size_t kJournalHeaderV1Bytes = 64;
/// Magic, H, I, id, base_scene, build, scenarios, keep_runs.
constexpr std::size_t kHeaderFixedBytes = 8 + 4 + 4 + 5 * 8;
constexpr std::uint32_t kRecordMagic = 0x31525848u;  // "HXR1" in little-endian memory order
/// Largest payload accepted when reading (a kept run is a few MB).
constexpr std::uint64_t kMaxPayload = std::uint64_t{1} << 34;

std::string padded(std::uint64_t index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%06llu", static_cast<unsigned long long>(index));
  return buf;
}

void put_text(std::vector<char>& b, const std::string& s) {
  put_pod(b, static_cast<std::uint32_t>(s.size()));
  b.insert(b.end(), s.begin(), s.end());
}

/// Reads a text written by put_text from [at, end); false when it does not fit.
bool get_text(const char* data, std::size_t end, std::size_t& at, std::string& out) {
  if (end - at < 4) return false;
  const auto n = get_pod<std::uint32_t>(data + at);
  at += 4;
  if (n > end - at) return false;
  out.assign(data + at, n);
  at += n;
  return true;
}

std::string short_hash(const std::string& hex) { return hex.substr(0, 12) + "..."; }

/// The header of a journal (format 2) at `data`, when it is intact: its size, else 0.
std::size_t read_header(const char* data, std::size_t size, SweepIdentity& h) {
  if (size < kHeaderFixedBytes + 4 || std::memcmp(data, kJournalMagic, 8) != 0) return 0;
  const auto total = get_pod<std::uint32_t>(data + 8);
  if (total < kHeaderFixedBytes + 4 || total > size || total > kMaxJournalHeaderBytes) return 0;
  if (get_pod<std::uint32_t>(data + total - 4) != crc32(data, total - 4)) return 0;
  const auto count = get_pod<std::uint32_t>(data + 12);
  h.id = get_pod<std::uint64_t>(data + 16);
  h.base_scene = get_pod<std::uint64_t>(data + 24);
  h.build = get_pod<std::uint64_t>(data + 32);
  h.scenarios = get_pod<std::uint64_t>(data + 40);
  h.keep_runs = get_pod<std::uint64_t>(data + 48) != 0;
  std::size_t at = kHeaderFixedBytes;
  const std::size_t end = total - 4;
  for (std::uint32_t i = 0; i < count; ++i) {
    InputFile f;
    if (!get_text(data, end, at, f.role) || !get_text(data, end, at, f.path) ||
        !get_text(data, end, at, f.sha256))
      return 0;
    f.absolute = f.path;
    h.inputs.push_back(std::move(f));
  }
  return at == end ? total : 0;
}

}  // namespace

std::string SweepIdentity::difference(const SweepIdentity& o) const {
  if (o.format != format)
    return "it was made by an older hexdyn (checkpoint format " + std::to_string(o.format) +
           ", which records no input file's content)";
  for (const InputFile& then : o.inputs) {
    const auto now = std::find_if(inputs.begin(), inputs.end(),
                                  [&](const InputFile& f) { return f.absolute == then.absolute; });
    if (now == inputs.end())
      return "the " + then.role + " " + then.absolute +
             " was an input of the checkpoint's sweep and is not one now";
    if (now->sha256 != then.sha256)
      return "the " + now->role + " " + now->absolute +
             " changed since the checkpoint was made (SHA-256 " + short_hash(then.sha256) +
             " then, " + short_hash(now->sha256) + " now)";
  }
  for (const InputFile& now : inputs) {
    const bool known = std::any_of(o.inputs.begin(), o.inputs.end(),
                                   [&](const InputFile& f) { return f.absolute == now.absolute; });
    if (!known)
      return "the " + now.role + " " + now.absolute +
             " is an input now and was not one of the checkpoint's sweep";
  }
  if (base_scene != o.base_scene) return "the resolved base scene differs";
  if (keep_runs != o.keep_runs)
    return std::string("it was made ") + (o.keep_runs ? "with" : "without") + " --keep-runs";
  if (build != o.build) return "it was made by another build of hexdyn (version or commit)";
  if (scenarios != o.scenarios) return "the number of scenarios differs";
  if (id != o.id) return "its identity differs";
  return {};
}

SweepIdentity make_identity(const std::vector<InputFile>& inputs,
                            const std::string& base_config_yaml, const std::string& build,
                            std::uint64_t scenarios, bool keep_runs) {
  SweepIdentity s;
  for (const InputFile& f : inputs) {
    InputFile id;  // role, absolute path and digest: what identifies the sweep
    id.role = f.role;
    id.path = id.absolute = f.absolute;
    id.sha256 = f.sha256;
    s.inputs.push_back(std::move(id));
  }
  s.base_scene = fnv1a64(base_config_yaml);
  s.build = fnv1a64(build);
  s.scenarios = scenarios;
  s.keep_runs = keep_runs;
  std::string all;
  for (std::uint64_t v :
       {s.base_scene, s.build, s.scenarios, static_cast<std::uint64_t>(keep_runs ? 1 : 0)})
    all.append(reinterpret_cast<const char*>(&v), sizeof v);
  for (const InputFile& f : s.inputs) all += f.role + '\0' + f.absolute + '\0' + f.sha256 + '\0';
  s.id = fnv1a64(all);
  return s;
}

std::vector<char> journal_header(const SweepIdentity& s) {
  std::vector<char> b(kJournalMagic, kJournalMagic + 8);
  put_pod(b, std::uint32_t{0});  // H, set below
  put_pod(b, static_cast<std::uint32_t>(s.inputs.size()));
  for (std::uint64_t v : {s.id, s.base_scene, s.build, s.scenarios}) put_pod(b, v);
  put_pod(b, static_cast<std::uint64_t>(s.keep_runs ? 1 : 0));
  for (const InputFile& f : s.inputs) {
    put_text(b, f.role);
    put_text(b, f.absolute);
    put_text(b, f.sha256);
  }
  const auto total = static_cast<std::uint32_t>(b.size() + 4);
  std::memcpy(b.data() + 8, &total, sizeof total);
  put_pod(b, crc32(b.data(), b.size()));
  return b;
}

void append_journal_record(std::vector<char>& out, RecordKind kind, std::uint64_t index,
                           const SweepIdentity& identity, const char* payload, std::size_t size) {
  const std::size_t start = out.size();
  out.reserve(start + kRecordHeaderBytes + size + kRecordTrailerBytes);
  put_pod(out, kRecordMagic);
  put_pod(out, static_cast<std::uint32_t>(kind));
  put_pod(out, index);
  put_pod(out, identity.id);
  put_pod(out, static_cast<std::uint64_t>(size));
  out.insert(out.end(), payload, payload + size);
  put_pod(out, crc32(out.data() + start + 4, out.size() - start - 4));
}

BuiltRecord check_built_record(const char* record, std::size_t size, RecordKind kind,
                               std::uint64_t index, const SweepIdentity& identity) {
  const auto bad = [&](const char* what) {
    return Error("sweep: the journal record of scenario " + padded(index) + " from a worker " +
                 what);
  };
  if (size < kRecordHeaderBytes + kRecordTrailerBytes ||
      get_pod<std::uint32_t>(record) != kRecordMagic)
    throw bad("is not a record");
  if (get_pod<std::uint32_t>(record + 4) != static_cast<std::uint32_t>(kind))
    throw bad("is of another kind");
  if (get_pod<std::uint64_t>(record + 8) != index) throw bad("names another scenario");
  if (get_pod<std::uint64_t>(record + 16) != identity.id) throw bad("is of another sweep");
  const auto payload = get_pod<std::uint64_t>(record + 24);
  if (payload != size - kRecordHeaderBytes - kRecordTrailerBytes) throw bad("has the wrong length");
  return {record + kRecordHeaderBytes, static_cast<std::size_t>(payload)};
}

namespace {

/// Reads the journal's header into scan (a damaged one reported in scan.damage); returns
/// the offset of the first record, 0 when the header is damaged. A header of the older
/// format: its identity is reported, its records are foreign.
std::size_t scan_header(const char* data, std::size_t size, const std::string& name,
                        JournalScan& scan) {
  const bool v1 = size >= kJournalHeaderV1Bytes && std::memcmp(data, kJournalMagicV1, 8) == 0 &&
                  get_pod<std::uint32_t>(data + 56) == crc32(data, 56);
  if (v1) {
    scan.header_ok = true;
    scan.header.format = 1;
    scan.header.id = get_pod<std::uint64_t>(data + 8);
    return kJournalHeaderV1Bytes;
  }
  if (const std::size_t h = read_header(data, size, scan.header)) {
    scan.header_ok = true;
    return h;
  }
  scan.header = SweepIdentity{};
  scan.damage.push_back(name + ": damaged header (" +
                        (size < kHeaderFixedBytes + 4
                             ? std::string("file of ") + std::to_string(size) + " bytes"
                             : std::string("checksum mismatch")) +
                        "); its records are read by their own checksums");
  return 0;
}

/// The damaged stretches of a journal named `name`: one stretch [bad_from, next good
/// record) is reported once, into `damage`.
struct DamageReport {
  const std::string& name;
  std::vector<std::string>& damage;
  /// Bytes before the first intact record of a journal whose header is damaged are the
  /// header's remains, reported with it, not as a damaged record.
  bool header_remains = false;
  std::size_t bad_from = SIZE_MAX;
  std::string bad_what;

  /// A stretch starts at pos (unless one is open), `what` naming it.
  void mark_bad(std::size_t pos, const std::string& what) {
    if (bad_from == SIZE_MAX) {
      bad_from = pos;
      bad_what = what;
    }
  }
  /// The open stretch, if any, ends at upto.
  void end_damage(std::size_t upto) {
    if (bad_from == SIZE_MAX) return;
    if (header_remains) {
      bad_from = SIZE_MAX;
      return;
    }
    damage.push_back(name + ": " + bad_what + " at byte " + std::to_string(bad_from) +
                     (upto > bad_from ? " (" + std::to_string(upto - bad_from) + " bytes skipped)"
                                      : std::string()) +
                     "; its scenario is computed again");
    bad_from = SIZE_MAX;
  }
};

}  // namespace

JournalScan scan_journal(const char* data, std::size_t size, const std::string& name,
                         const SweepIdentity& expected) {
  JournalScan scan;
  std::size_t at = scan_header(data, size, name, scan);
  DamageReport report{name, scan.damage, !scan.header_ok, SIZE_MAX, std::string()};
  while (at < size) {
    if (size - at < 4 || get_pod<std::uint32_t>(data + at) != kRecordMagic) {
      if (report.bad_from == SIZE_MAX) report.mark_bad(at, "unreadable record");
      ++at;
      continue;
    }
    if (size - at < kRecordHeaderBytes + kRecordTrailerBytes) {
      report.mark_bad(at, "truncated record (" + std::to_string(size - at) + " bytes)");
      break;
    }
    const auto kind = get_pod<std::uint32_t>(data + at + 4);
    const auto index = get_pod<std::uint64_t>(data + at + 8);
    const auto ident = get_pod<std::uint64_t>(data + at + 16);
    const auto psize = get_pod<std::uint64_t>(data + at + 24);
    const std::string which = "record of scenario " + padded(index);
    if (psize > kMaxPayload || psize > size - at - kRecordHeaderBytes - kRecordTrailerBytes) {
      // A length past the end: a cut-off last record, or a damaged length field.
      report.mark_bad(at, (psize > kMaxPayload ? "damaged " : "truncated ") + which);
      ++at;
      continue;
    }
    const std::size_t body = kRecordHeaderBytes + static_cast<std::size_t>(psize);
    const auto crc = get_pod<std::uint32_t>(data + at + body);
    if (crc != crc32(data + at + 4, body - 4)) {
      report.mark_bad(at, "damaged " + which + " (checksum mismatch)");
      ++at;
      continue;
    }
    report.end_damage(at);
    report.header_remains = false;
    if (ident != expected.id) {
      scan.foreign_record = true;
    } else if (kind == static_cast<std::uint32_t>(RecordKind::kRow) ||
               kind == static_cast<std::uint32_t>(RecordKind::kCrashAttempt)) {
      scan.entries.push_back({static_cast<RecordKind>(kind), index, at + kRecordHeaderBytes,
                              static_cast<std::size_t>(psize)});
    }
    at += body + kRecordTrailerBytes;
  }
  report.end_damage(size);
  return scan;
}

}  // namespace hexdyn
