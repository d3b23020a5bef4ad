#include "hexdyn/config/yaml_load.hpp"

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <regex>
#include <sstream>
#include <vector>

#include "hexdyn/config/config.hpp"
#include "hexdyn/config/inputs.hpp"
#include "hexdyn/config/robot_config.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/process/paths.hpp"

namespace hexdyn {
namespace {

namespace fs = std::filesystem;

/// The tag of a scalar given as !!str.
const char* const kStringTag = "tag:yaml.org,2002:str";

/// Whether hexdyn reads `text` as a number where one is expected: a YAML int or float
/// (yaml-cpp's conversion), or p/q.
bool reads_as_number(const std::string& text) {
  double v = 0.0;
  return YAML::convert<double>::decode(YAML::Node(text), v) || parse_fraction(text).has_value();
}

/// Checks the event stream of one YAML text (no tree is built, aliases are not
/// expanded, so the check is linear in the text). It counts the nodes and scalar bytes the
/// text stands for once every alias is expanded (an alias counts as its anchor's whole
/// node), and stops at the first event past kMaxYamlNodes or kMaxYamlBytes.
class StructureCheck : public YAML::EventHandler {
 public:
  explicit StructureCheck(std::string source) : source_(std::move(source)) {}

  enum class Top { kNone, kNull, kScalar, kSequence, kMap };
  Top top() const { return top_; }
  const std::string& top_scalar() const { return top_scalar_; }
  /// Whether a quoted scalar's text is a number (is_quoted_number).
  bool quoted_numbers() const { return quoted_numbers_; }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    count(mark, {1, 0}, anchor);
    node(mark, "null", Top::kNull);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    if (key_expected()) fail_key(mark, "an alias (*name)");
    if (anchor >= anchors_.size() || anchors_[anchor].nodes == 0)  // its node is still open
      throw ConfigError(source_ + ":" + std::to_string(mark.line + 1) + ": " + here() +
                        ": got an alias inside the node it names (a cycle), expected an alias "
                        "of a complete node");
    count(mark, anchors_[anchor], 0);
    node(mark, "", Top::kNull);
  }
  void OnScalar(const YAML::Mark& mark, const std::string& tag, YAML::anchor_t anchor,
                const std::string& value) override {
    if (top_ == Top::kNone) top_scalar_ = value;
    if (tag == "!" && !quoted_numbers_) quoted_numbers_ = reads_as_number(value);
    count(mark, {1, value.size()}, anchor);
    node(mark, value, Top::kScalar);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, false, anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, true, anchor);
  }
  void OnMapEnd() override { close(); }

 private:
  /// A node's size once every alias in it is expanded.
  struct Expanded {
    std::uint64_t nodes = 0;  ///< scalars, nulls, lists and maps (keys included)
    std::uint64_t bytes = 0;  ///< the text of its scalars
  };

  struct Frame {
    bool is_map = false;
    std::string path;                 ///< dotted path of this container ("" at the top)
    bool want_key = true;             ///< maps: the next node is a key
    std::string key;                  ///< maps: the key whose value comes next
    std::map<std::string, int> seen;  ///< maps: key → 1-based line of its first use
    std::size_t index = 0;            ///< lists: index of the next item
    Expanded at_open;                 ///< the document's expanded size when it opened
    YAML::anchor_t anchor = 0;        ///< its anchor (&name), 0 when none
  };

  bool key_expected() const {
    return !stack_.empty() && stack_.back().is_map && stack_.back().want_key;
  }

  std::string where() const {
    return stack_.empty() || stack_.back().path.empty() ? "top level" : stack_.back().path;
  }

  [[noreturn]] void fail_key(const YAML::Mark& mark, const std::string& what) const {
    throw ConfigError(source_ + ":" + std::to_string(mark.line + 1) + ": " + where() + ": got " +
                      what + " as a key, expected a plain name");
  }

  /// Path of the node that comes next in the innermost container (a value, not a key).
  std::string child_path() {
    Frame& f = stack_.back();
    if (f.is_map) {
      f.want_key = true;
      return f.path.empty() ? f.key : f.path + "." + f.key;
    }
    return f.path + "[" + std::to_string(f.index++) + "]";
  }

  /// A scalar, null or alias: a map key (checked against the map's earlier keys) or a value.
  void node(const YAML::Mark& mark, const std::string& key_text, Top kind) {
    if (stack_.empty()) {
      if (top_ == Top::kNone) top_ = kind;
      return;
    }
    Frame& f = stack_.back();
    if (f.is_map && f.want_key) {
      const int line = mark.line + 1;
      const auto [it, fresh] = f.seen.emplace(key_text, line);
      if (!fresh) {
        const std::string path = f.path.empty() ? key_text : f.path + "." + key_text;
        throw ConfigError(source_ + ": " + path + ": duplicate key, first at line " +
                          std::to_string(it->second) + ", again at line " + std::to_string(line));
      }
      f.key = key_text;
      f.want_key = false;
      return;
    }
    child_path();
  }

  /// Where the next node goes, for messages: "a.b", "a.list[3]" or "top level".
  std::string here() const {
    if (stack_.empty()) return "top level";
    const Frame& f = stack_.back();
    std::string p;
    if (!f.is_map)
      p = f.path + "[" + std::to_string(f.index) + "]";
    else if (f.want_key)
      p = f.path;
    else
      p = f.path.empty() ? f.key : f.path + "." + f.key;
    return p.empty() ? "top level" : p;
  }

  /// Adds a node of `size` (expanded) to the document's count; records an anchor's size.
  void count(const YAML::Mark& mark, Expanded size, YAML::anchor_t anchor) {
    total_.nodes += size.nodes;  // each term is at most the limit: no overflow
    total_.bytes += size.bytes;
    if (total_.nodes > kMaxYamlNodes || total_.bytes > kMaxYamlBytes) {
      const bool by_nodes = total_.nodes > kMaxYamlNodes;
      throw ConfigError(
          source_ + ":" + std::to_string(mark.line + 1) + ": " + here() + ": got more than " +
          (by_nodes ? std::to_string(kMaxYamlNodes) + " YAML nodes"
                    : std::to_string(kMaxYamlBytes) + " bytes of values") +
          " once aliases (*name) are expanded, expected at most that many (each alias repeats "
          "its anchor's whole node)");
    }
    if (anchor != 0) {
      if (anchors_.size() <= anchor) anchors_.resize(anchor + 1);
      anchors_[anchor] = size;
    }
  }

  void close() {
    const Frame& f = stack_.back();
    const Expanded size{total_.nodes - f.at_open.nodes, total_.bytes - f.at_open.bytes};
    if (f.anchor != 0) {
      if (anchors_.size() <= f.anchor) anchors_.resize(f.anchor + 1);
      anchors_[f.anchor] = size;
    }
    stack_.pop_back();
  }

  void open(const YAML::Mark& mark, bool is_map, YAML::anchor_t anchor) {
    if (key_expected()) fail_key(mark, is_map ? "a map" : "a list");
    count(mark, {1, 0}, 0);
    if (stack_.empty() && top_ == Top::kNone) top_ = is_map ? Top::kMap : Top::kSequence;
    std::string path = stack_.empty() ? std::string() : child_path();
    if (static_cast<int>(stack_.size()) >= kMaxYamlDepth) {
      std::string at = path.substr(0, std::min(path.find('['), std::size_t{60}));
      if (at.empty())
        at = "top level";
      else if (at.size() < path.size())
        at += "...";
      throw ConfigError(source_ + ":" + std::to_string(mark.line + 1) + ": " + at +
                        ": maps and lists nested deeper than " + std::to_string(kMaxYamlDepth) +
                        " levels, expected at most " + std::to_string(kMaxYamlDepth));
    }
    Frame f;
    f.is_map = is_map;
    f.path = std::move(path);
    f.at_open = total_;
    f.at_open.nodes -= 1;  // the container itself is part of its size
    f.anchor = anchor;
    stack_.push_back(std::move(f));
  }

  std::string source_;
  std::vector<Frame> stack_;
  Expanded total_;                 ///< the document so far, aliases expanded
  std::vector<Expanded> anchors_;  ///< by anchor id: its node's size (0 nodes: still open)
  Top top_ = Top::kNone;
  std::string top_scalar_;
  bool quoted_numbers_ = false;
};

/// Runs the structure check over `text`; returns the top-level kind and whether a quoted
/// scalar's text is a number.
std::pair<StructureCheck::Top, bool> check_structure(const std::string& text,
                                                     const std::string& source_name,
                                                     std::string* top_scalar) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  StructureCheck check(source_name);
  parser.HandleNextDocument(check);
  struct Second : YAML::EventHandler {
    int line = 0;
    void OnDocumentStart(const YAML::Mark& m) override {
      line = m.line + 1;
      throw std::runtime_error("second document");
    }
    void OnDocumentEnd() override {}
    void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
    void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
    void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  const std::string&) override {}
    void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                         YAML::EmitterStyle::value) override {}
    void OnSequenceEnd() override {}
    void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                    YAML::EmitterStyle::value) override {}
    void OnMapEnd() override {}
  } second;
  try {
    parser.HandleNextDocument(second);
  } catch (const std::runtime_error&) {
    if (second.line == 0) throw;
  }
  if (second.line > 0)
    throw ConfigError(source_name + ":" + std::to_string(second.line) +
                      ": a second YAML document (after '---'), expected one document per file");
  if (top_scalar) *top_scalar = check.top_scalar();
  return {check.top(), check.quoted_numbers()};
}

/// Tags every quoted scalar whose text is a number !!str (is_quoted_number): yaml-cpp writes
/// a quoted scalar (tag "!") without its quotes, and an explicit tag with it.
void tag_quoted_numbers(const YAML::Node& node) {
  if (node.IsScalar()) {
    if (node.Tag() == "!" && reads_as_number(node.Scalar())) YAML::Node(node).SetTag(kStringTag);
  } else if (node.IsSequence()) {
    for (const YAML::Node& item : node) tag_quoted_numbers(item);
  } else if (node.IsMap()) {
    for (const auto& kv : node) tag_quoted_numbers(kv.second);
  }
}

YAML::Node parse_checked(const std::string& text, const std::string& source_name,
                         StructureCheck::Top* top, std::string* top_scalar) {
  try {
    const auto [t, quoted_numbers] = check_structure(text, source_name, top_scalar);
    if (top) *top = t;
    YAML::Node root = YAML::Load(text);
    if (quoted_numbers) tag_quoted_numbers(root);
    return root;
  } catch (const YAML::DeepRecursion& e) {
    throw ConfigError(source_name + ":" + std::to_string(e.mark.line + 1) + ":" +
                      std::to_string(e.mark.column + 1) +
                      ": maps and lists nested too deeply, expected at most " +
                      std::to_string(kMaxYamlDepth) + " levels");
  } catch (const YAML::ParserException& e) {
    throw ConfigError(source_name + ":" + std::to_string(e.mark.line + 1) + ":" +
                      std::to_string(e.mark.column + 1) + ": YAML syntax error: " + e.msg);
  }
}

/// `text` cut to one short line for a message.
std::string short_text(const std::string& text) {
  std::string s = text.substr(0, 40);
  for (char& c : s)
    if (c == '\n' || c == '\r' || c == '\t') c = ' ';
  return s.size() < text.size() ? s + "..." : s;
}

/// A path for messages: relative to the working directory when that is shorter.
std::string display_path(const fs::path& p) {
  std::error_code ec;
  const fs::path rel = p.lexically_proximate(fs::current_path(ec));
  return !ec && !rel.empty() && rel.native().size() < p.native().size() ? rel.string() : p.string();
}

/// Deep merge: maps merge key by key, anything else in `top` replaces `base`.
YAML::Node merge_nodes(const YAML::Node& base, const YAML::Node& top) {
  if (!base.IsMap() || !top.IsMap()) return YAML::Clone(top);
  YAML::Node out = YAML::Clone(base);
  for (const auto& kv : top) {
    const std::string key = kv.first.Scalar();
    out[key] = out[key].IsDefined() ? merge_nodes(out[key], kv.second) : YAML::Clone(kv.second);
  }
  return out;
}

/// One file of an inheritance chain: as named (for messages) and its canonical path.
struct ChainLink {
  std::string path;
  fs::path canonical;
};

YAML::Node load_with_inheritance(const std::string& path, std::vector<ChainLink>& chain) {
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(path, ec);
  if (ec) canonical = fs::absolute(path, ec).lexically_normal();
  for (std::size_t i = 0; i < chain.size(); ++i) {
    if (chain[i].canonical != canonical) continue;
    std::string cycle;
    for (std::size_t k = i; k < chain.size(); ++k)
      cycle += display_path(chain[k].canonical) + " -> ";
    cycle += display_path(canonical);
    throw ConfigError(display_path(chain.back().canonical) + ": inherit: cycle " + cycle);
  }
  chain.push_back({path, canonical});
  YAML::Node root = parse_yaml_text(read_text_file(path), path);
  resolve_file_relative_keys(root, path);  // robot.urdf names a file beside this one
  const YAML::Node parent = root["inherit"];
  if (!parent.IsDefined()) return root;
  if (!parent.IsScalar() || parent.Scalar().empty())
    throw ConfigError(path + ": inherit: got " + yaml_inline(parent) +
                      ", expected the path of a scene file");
  const std::string& name = parent.Scalar();
  const std::string parent_path = path_beside(path, name);
  if (const auto why = why_not_regular_file(parent_path))
    throw ConfigError(path + ": inherit: got " + name + ", which " + *why + " (" + parent_path +
                      "), expected the path of a scene file relative to this file");
  root.remove("inherit");
  return merge_nodes(load_with_inheritance(parent_path, chain), root);
}

}  // namespace

bool is_quoted_number(const YAML::Node& node) {
  if (!node.IsDefined() || !node.IsScalar()) return false;  // also a missing key's node
  const std::string& tag = node.Tag();
  return (tag == "!" || tag == kStringTag) && reads_as_number(node.Scalar());
}

std::string quoted_number_message(const YAML::Node& node, const std::string& expected) {
  return "got the string " + yaml_for_message(node) + ", expected " + expected +
         " (write it unquoted)";
}

namespace {

/// `node` into `out` on one line: every list and map in flow style (as given in block style,
/// yaml-cpp would write lines), aliases written out, quoted numbers in quotes.
void put_inline(YAML::Emitter& out, const YAML::Node& node) {
  if (node.IsScalar()) {
    if (is_quoted_number(node)) out << YAML::DoubleQuoted;
    out << node.Scalar();
  } else if (node.IsSequence()) {
    out << YAML::Flow << YAML::BeginSeq;
    for (const YAML::Node& item : node) put_inline(out, item);
    out << YAML::EndSeq;
  } else if (node.IsMap()) {
    out << YAML::Flow << YAML::BeginMap;
    for (const auto& kv : node) {
      out << YAML::Key;
      put_inline(out, kv.first);
      out << YAML::Value;
      put_inline(out, kv.second);
    }
    out << YAML::EndMap;
  } else {
    out << YAML::Null;
  }
}

}  // namespace

std::string yaml_inline(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "null";
  if (node.IsScalar() && !is_quoted_number(node)) return node.Scalar();
  YAML::Emitter out;
  put_inline(out, node);
  return out.c_str();
}

std::string yaml_for_message(const YAML::Node& node) {
  std::string text = yaml_inline(node);
  if (text.size() <= kMaxMessageValueChars) return text;
  const std::size_t whole = text.size();
  text.resize(kMaxMessageValueChars);
  return text + "... (" + std::to_string(whole) + " characters)";
}

std::string read_text_file(const std::string& path) {
  // config/inputs.hpp: type and size checked before reading, UTF-8, kept while a command runs.
  return *read_input_text(path, kMaxConfigBytes, "a configuration file (a regular YAML file)").text;
}

YAML::Node parse_yaml_checked(const std::string& text, const std::string& source_name) {
  if (text.size() > kMaxConfigBytes)  // a value given outside a file (--set, Python)
    throw ConfigError(source_name.substr(0, 80) + (source_name.size() > 80 ? "...: " : ": ") +
                      "got a value of " + std::to_string(text.size()) +
                      " bytes, expected at most " + std::to_string(kMaxConfigBytes) +
                      " (1 MiB, the size of a whole configuration file)");
  return parse_checked(text, source_name, nullptr, nullptr);
}

YAML::Node parse_yaml_text(const std::string& text, const std::string& source_name) {
  StructureCheck::Top top = StructureCheck::Top::kNone;
  std::string scalar;
  YAML::Node root = parse_checked(text, source_name, &top, &scalar);
  if (root.IsMap()) return root;
  std::string got = "an empty document";
  if (top == StructureCheck::Top::kSequence) got = "a list";
  if (top == StructureCheck::Top::kScalar) got = "a single value '" + short_text(scalar) + "'";
  throw ConfigError(source_name + ": top level: got " + got + ", expected a map of sections");
}

YAML::Node load_scene_tree(const std::string& path, std::vector<std::string>* files) {
  std::vector<ChainLink> chain;
  YAML::Node root = load_with_inheritance(path, chain);
  if (files) {
    files->clear();
    for (const ChainLink& link : chain) files->push_back(link.path);
  }
  return root;
}

std::optional<double> parse_fraction(const std::string& text) {
  static const std::regex fraction(R"(^\s*([+-]?[0-9]+)\s*/\s*([0-9]+)\s*$)");
  std::smatch m;
  if (!std::regex_match(text, m, fraction)) return std::nullopt;
  // strtod, not stod: a 400-digit integer gives inf here, not an exception.
  const double p = std::strtod(m[1].str().c_str(), nullptr);
  const double q = std::strtod(m[2].str().c_str(), nullptr);
  if (q == 0.0 || !std::isfinite(p / q)) return std::nullopt;
  return p / q;
}

std::string fraction_to_number_text(const std::string& text) {
  const auto q = parse_fraction(text);
  if (!q) return text;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", *q);
  return buf;
}

}  // namespace hexdyn
