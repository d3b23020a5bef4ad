#include "hexdyn/config/leg_keys.hpp"

#include <cmath>

namespace hexdyn {

using scene_keys::Reader;

namespace {

/// "[coxa, femur, tibia] rad, each a number in [...]".
std::string one_vector(const LegVectorKey& key) {
  return key.meaning + ", each " + key.range.describe();
}

/// Everything the key may hold, for a value of the wrong shape.
std::string every_form(const LegVectorKey& key) {
  return one_vector(key) + " (every leg); or six of them: a list in leg order L1 … L6, or a " +
         (key.every_leg ? "map naming every leg" : "map by leg name") + " L1 … L6";
}

/// One list item: three finite numbers in range; none otherwise.
std::optional<Vec3> decode_vector(const YAML::Node& item, const scene_keys::Range& range) {
  if (!item.IsSequence() || item.size() != 3) return std::nullopt;
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    double x = 0.0;
    if (!item[i].IsScalar() || !YAML::convert<double>::decode(item[i], x) || !std::isfinite(x) ||
        !range.contains(x))
      return std::nullopt;
    v[i] = x;
  }
  return v;
}

/// KEY: [[...] × 6]: one vector per leg in leg order.
std::array<std::optional<Vec3>, kLegs> read_list(Reader& r, const LegVectorKey& key) {
  const YAML::Node node = r.node(key.path);
  std::array<std::optional<Vec3>, kLegs> out;
  YAML::Node resolved(YAML::NodeType::Sequence);
  for (int leg = 0; leg < kLegs; ++leg) {
    out[leg] = decode_vector(node[leg], key.range);
    if (!out[leg])
      r.fail(key.path, "item " + std::to_string(leg + 1) + " (" + leg_name(leg) + "): got " +
                           yaml_for_message(node[leg]) + ", expected " + one_vector(key));
    YAML::Node item(YAML::NodeType::Sequence);
    for (int i = 0; i < 3; ++i) item.push_back((*out[leg])[i]);
    item.SetStyle(YAML::EmitterStyle::Flow);
    resolved.push_back(item);
  }
  r.record(key.path, resolved);
  return out;
}

/// KEY: {L1: [...], ...}: the legs it names, each read as KEY.L<i>.
std::array<std::optional<Vec3>, kLegs> read_map(Reader& r, const LegVectorKey& key,
                                                const YAML::Node& node) {
  std::string names;
  for (int leg = 0; leg < kLegs; ++leg) names += (leg ? ", " : "") + leg_name(leg);
  if (node.size() == 0) {
    (void)r.node(key.path);
    r.fail_value(key.path, node, every_form(key));
  }
  for (const auto& entry : node) {
    const std::string name = entry.first.IsScalar() ? entry.first.Scalar() : "";
    bool known = false;
    for (int leg = 0; leg < kLegs; ++leg) known = known || name == leg_name(leg);
    if (!known)
      r.fail(key.path, "got the key " + yaml_for_message(entry.first) + ", expected leg names (" +
                           names + ")");
  }
  std::array<std::optional<Vec3>, kLegs> out;
  for (int leg = 0; leg < kLegs; ++leg) {
    const std::string path = key.path + "." + leg_name(leg);
    if (r.has(path)) {
      out[leg] = r.vec3(path, key.range);
    } else if (key.every_leg) {
      r.fail(key.path, "got " + yaml_for_message(node) + ", expected a map naming every leg (" +
                           names + "), " + leg_name(leg) + " missing");
    }
  }
  return out;
}

}  // namespace

std::array<std::optional<Vec3>, kLegs> read_leg_vectors(Reader& r, const LegVectorKey& key) {
  if (!r.given(key.path)) {
    (void)r.has(key.path);  // counted as asked for
    return {};
  }
  const YAML::Node node = r.peek(key.path);
  if (node.IsMap()) return read_map(r, key, node);  // its entries asked for one by one
  r.refuse_quoted_numbers(key.path, node, key.range.describe());
  if (node.IsSequence() && node.size() == kLegs) return read_list(r, key);
  bool scalars = node.IsSequence() && node.size() == 3;
  for (std::size_t i = 0; scalars && i < 3; ++i) scalars = node[i].IsScalar();
  if (!scalars) {
    (void)r.node(key.path);
    r.fail_value(key.path, node, every_form(key));
  }
  std::array<std::optional<Vec3>, kLegs> out;
  out.fill(r.vec3(key.path, key.range));
  return out;
}

}  // namespace hexdyn
