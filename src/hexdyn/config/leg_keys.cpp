#include "hexdyn/config/leg_keys.hpp"

#include <algorithm>
#include <cmath>

namespace hexdyn {

using scene_keys::Reader;

LegKeyShape point_legs() {
  LegKeyShape s;
  for (int leg = 0; leg < kMaxLegs; ++leg) {
    s.names[leg] = leg_name(leg);
    s.sizes[leg] = 3;
  }
  return s;
}

namespace {

/// Legs whose names a map may use: the robot's, or L1 … L8 before the robot is read.
int named_legs(const LegKeyShape& shape) { return shape.legs > 0 ? shape.legs : kMaxLegs; }

/// "[coxa, femur, tibia]", "[j1, …, j4]" or "[x, y, z]".
std::string vector_words(const LegKeyShape& shape, int size) {
  if (!shape.joints) return "[x, y, z]";
  if (size == 3) return "[coxa, femur, tibia]";
  return "[j1, …, j" + std::to_string(size) + "]";
}

/// "[coxa, femur, tibia] rad, each a number in [...]" for leg `leg`.
std::string one_vector(const LegVectorKey& key, const LegKeyShape& shape, int leg) {
  return vector_words(shape, shape.sizes[leg]) + " " + key.unit + ", each " + key.range.describe();
}

/// The one length every leg's vector has, or 0 when the legs differ.
int common_size(const LegKeyShape& shape) {
  for (int leg = 1; leg < named_legs(shape); ++leg)
    if (shape.sizes[leg] != shape.sizes[0]) return 0;
  return shape.sizes[0];
}

/// "L1, L2, L3, L4"; "L1 … Ln of the robot's n legs" before the robot is read.
std::string name_list(const LegKeyShape& shape) {
  if (shape.legs == 0) return "L1 … Ln of the robot's n legs";
  std::string names;
  for (int leg = 0; leg < named_legs(shape); ++leg) names += (leg ? ", " : "") + shape.names[leg];
  return names;
}

/// One vector: `size` finite numbers in range; none otherwise.
std::optional<LegVector> decode_vector(const YAML::Node& item, int size,
                                       const scene_keys::Range& range) {
  if (!item.IsSequence() || static_cast<int>(item.size()) != size) return std::nullopt;
  LegVector v(size);
  for (int i = 0; i < size; ++i) {
    double x = 0.0;
    if (!item[i].IsScalar() || !YAML::convert<double>::decode(item[i], x) || !std::isfinite(x) ||
        !range.contains(x))
      return std::nullopt;
    v[i] = x;
  }
  return v;
}

/// KEY: [[...] × n]: one vector per leg in leg order.
LegKeyValues read_list(Reader& r, const LegVectorKey& key, const LegKeyShape& shape,
                       const YAML::Node& node) {
  (void)r.node(key.path);  // asked for: read below
  const int n = static_cast<int>(node.size());
  if (shape.legs > 0 ? n != shape.legs : n < kMinLegs || n > kMaxLegs)
    r.fail_value(key.path, node, leg_key_forms(key, shape));
  LegKeyValues out;
  out.given = true;
  out.count = n;
  YAML::Node resolved(YAML::NodeType::Sequence);
  for (int leg = 0; leg < n; ++leg) {
    out.by_leg[leg] = decode_vector(node[leg], shape.sizes[leg], key.range);
    if (!out.by_leg[leg])
      r.fail(key.path, "item " + std::to_string(leg + 1) + " (" + shape.names[leg] + "): got " +
                           yaml_for_message(node[leg]) + ", expected " +
                           one_vector(key, shape, leg));
    YAML::Node item(YAML::NodeType::Sequence);
    for (double x : *out.by_leg[leg]) item.push_back(x);
    item.SetStyle(YAML::EmitterStyle::Flow);
    resolved.push_back(item);
  }
  r.record(key.path, resolved);
  return out;
}

/// KEY: {L1: [...], ...}: the legs it names, each read as KEY.L<i>.
LegKeyValues read_map(Reader& r, const LegVectorKey& key, const LegKeyShape& shape,
                      const YAML::Node& node) {
  if (node.size() == 0) {
    (void)r.node(key.path);
    r.fail_value(key.path, node, leg_key_forms(key, shape));
  }
  const int legs = named_legs(shape);
  int last = -1;
  for (const auto& entry : node) {
    const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : "";
    const int leg = static_cast<int>(
        std::find(shape.names.begin(), shape.names.begin() + legs, name) - shape.names.begin());
    if (leg == legs)
      r.fail(key.path, "got the key " + yaml_for_message(entry.first) + ", expected leg names (" +
                           name_list(shape) + ")");
    last = std::max(last, leg);
  }
  LegKeyValues out;
  out.given = true;
  // Every leg the robot has, or (legs not known yet) every leg up to the last one named.
  out.count = shape.legs > 0 ? shape.legs : std::max(last + 1, kMinLegs);
  for (int leg = 0; leg < out.count; ++leg) {
    const std::string path = key.path + "." + shape.names[leg];
    if (r.has(path)) {
      const int m = shape.sizes[leg];
      const std::vector<double> v = r.numbers(path, m, m, key.range);
      out.by_leg[leg] = Eigen::Map<const LegVector>(v.data(), m);
    } else if (key.every_leg) {
      r.fail(key.path, "got " + yaml_for_message(node) + ", expected a map naming every leg (" +
                           name_list(shape) + "), " + shape.names[leg] + " missing");
    }
  }
  return out;
}

}  // namespace

std::string leg_key_forms(const LegVectorKey& key, const LegKeyShape& shape) {
  const int m = common_size(shape);
  const int legs = named_legs(shape);
  const std::string range = ", each " + key.range.describe();
  const std::string count =
      shape.legs > 0 ? std::to_string(shape.legs) + " of them" : "one per leg";
  const std::string order =
      shape.legs > 0 ? shape.names[0] + " … " + shape.names[legs - 1] : std::string("L1 … Ln");
  const std::string lists = ": a list in leg order " + order + ", or a " +
                            (key.every_leg ? "map naming every leg " : "map by leg name ") + order;
  if (m > 0)
    return vector_words(shape, m) + " " + key.unit + range + " (every leg); or " + count + lists;
  std::string each;
  for (int leg = 0; leg < legs; ++leg)
    each += (leg ? ", " : "") + shape.names[leg] + " " + vector_words(shape, shape.sizes[leg]);
  return "one vector per leg of its joints' angles in " + key.unit + " (" + each + ")" + range +
         lists;
}

LegKeyValues read_leg_vectors(Reader& r, const LegVectorKey& key, const LegKeyShape& shape) {
  if (!r.given(key.path)) {
    (void)r.has(key.path);  // counted as asked for
    return {};
  }
  const YAML::Node node = r.peek(key.path);
  if (node.IsMap()) return read_map(r, key, shape, node);  // its entries asked for one by one
  r.refuse_quoted_numbers(key.path, node, key.range.describe());
  if (node.IsSequence() && node.size() > 0 && node[0].IsSequence())
    return read_list(r, key, shape, node);
  const int m = common_size(shape);
  bool scalars = m > 0 && node.IsSequence() && static_cast<int>(node.size()) == m;
  for (std::size_t i = 0; scalars && i < node.size(); ++i) scalars = node[i].IsScalar();
  if (!scalars) {
    (void)r.node(key.path);
    r.fail_value(key.path, node, leg_key_forms(key, shape));
  }
  const std::vector<double> v = r.numbers(key.path, m, m, key.range);
  LegKeyValues out;
  out.given = true;
  out.count = 1;
  for (int leg = 0; leg < named_legs(shape); ++leg)
    out.by_leg[leg] = Eigen::Map<const LegVector>(v.data(), m);
  return out;
}

}  // namespace hexdyn
