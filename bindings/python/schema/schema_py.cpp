// Prints the Python module hexdyn/_schema.py: every declaration of the HDF5 contracts of
// io/schema.hpp (and the headers it includes) as Python data, so that the package's readers
// take the layout from the compiled declarations, the ones the writers use, and parse no
// header text. Built and run at build time (cmake/python.cmake):
//     hexdyn_schema_py OUT.py      (writes OUT.py atomically; exit 1 with one line on error)
// The declarations come from the fragment HEXDYN_SCHEMA_NAMES (cmake/schema_names.cmake: one
// HEXDYN_SCHEMA_DECLARATION(kName) per declaration of the headers); their values, types and
// lists are what the compiler sees. A declaration of a type this program does not know fails
// to compile. Shapes are given by their netCDF dimensions (dimension_names) and the size symbol
// of each dimension (kSizeOfDimension below): a dimension without a size stops the program.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

// The headers (the fragment's #include lines; its declaration lines expand to nothing here).
#define HEXDYN_SCHEMA_DECLARATION(name)
#include HEXDYN_SCHEMA_NAMES  // NOLINT
#undef HEXDYN_SCHEMA_DECLARATION

namespace {

namespace schema = hexdyn::schema;

/// Size symbol of each netCDF dimension name (schema.hpp's file comment and the comments of
/// `Shape`): T output samples, L legs and J joints of the robot (a reader takes them from
/// the file's /model/leg_names and /model/joint_names, a sweep's J from its /joint_names),
/// n touchdowns, m solver messages, Y gait cycles, K vertices of
/// the terrain profile or keys of a cases axis, N scenarios, A axes, V values of an axis; an
/// envelope's W tread depths, B duty factors, S peak speeds, C criteria, P probes, D cases,
/// R risers of a friction search; a height map's MX columns and MY rows; a robustness study's RP
/// replays, ST stair steps, LK leg links and PT perturbations searched.
/// A number is a fixed size.
constexpr std::array<std::pair<const char*, const char*>, 28> kSizeOfDimension{{
    {"time", "T"},          {"joint", "J"},       {"leg", "L"},           {"xyz", "3"},
    {"wxyz", "4"},          {"impact", "n"},      {"message", "m"},       {"gait_cycle", "Y"},
    {"terrain_point", "K"}, {"scenario", "N"},    {"axis", "A"},          {"{key}", "V"},
    {"{key}_key", "K"},     {"tread_depth", "W"}, {"duty_factor", "B"},   {"peak_speed", "S"},
    {"criterion", "C"},     {"probe", "P"},       {"case", "D"},          {"case_key", "K"},
    {"riser", "R"},         {"map_x", "MX"},      {"map_y", "MY"},        {"replay", "RP"},
    {"step", "ST"},         {"link", "LK"},       {"failure_class", "6"}, {"perturbation", "PT"},
}};

/// A Python string literal of `text` (UTF-8 passed through; quotes, backslashes and control
/// characters escaped).
std::string py_str(const char* text) {
  std::string out = "\"";
  for (const char* p = text; *p != '\0'; ++p) {
    const auto c = static_cast<unsigned char>(*p);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

/// A Python tuple literal of the strings `items` (or, not `quoted`, of the numbers).
std::string py_tuple(const std::vector<std::string>& items, bool quoted = true) {
  std::string out = "(";
  for (const std::string& s : items) out += (quoted ? py_str(s.c_str()) : s) + ", ";
  return out + ")";
}

std::vector<std::string> words(const char* text) {
  std::istringstream in(text);
  std::vector<std::string> out;
  for (std::string w; in >> w;) out.push_back(w);
  return out;
}

const char* element_name(schema::Element e) {
  switch (e) {
    case schema::Element::kFloat64:
      return "float64";
    case schema::Element::kInt8:
      return "int8";
    case schema::Element::kInt32:
      return "int32";
    case schema::Element::kInt64:
      return "int64";
    case schema::Element::kString:
      return "string";
  }
  throw std::runtime_error("an Element without a name");
}

/// The shape of `shape` as a Python tuple of sizes: numbers, or the quoted size symbols.
std::string shape_tuple(schema::Shape shape) {
  std::string out = "(";
  for (const std::string& dim : words(schema::dimension_names(shape))) {
    const char* size = nullptr;
    for (const auto& [name, s] : kSizeOfDimension)
      if (dim == name) size = s;
    if (size == nullptr)
      throw std::runtime_error("dimension '" + dim +
                               "' has no size symbol: add it to kSizeOfDimension in " __FILE__);
    out += (size[0] >= '0' && size[0] <= '9') ? std::string(size) : py_str(size);
    out += ", ";
  }
  return out + ")";
}

bool same(const char* a, const char* b) { return std::strcmp(a, b) == 0; }
bool same(const schema::DatasetSpec& a, const schema::DatasetSpec& b) {
  return same(a.path, b.path) && same(a.units, b.units) && a.shape == b.shape &&
         a.element == b.element && same(a.long_name, b.long_name);
}
bool same(const schema::AttributeSpec& a, const schema::AttributeSpec& b) {
  return same(a.object, b.object) && same(a.name, b.name) && a.element == b.element;
}
bool same(const schema::FlagSpec& a, const schema::FlagSpec& b) {
  return same(a.path, b.path) && same(a.meanings, b.meanings);
}

/// Every declaration, by kind, in the order of the headers.
struct Declarations {
  std::vector<std::pair<std::string, std::string>> texts;      ///< const char*
  std::vector<std::pair<std::string, std::int64_t>> integers;  ///< std::int64_t
  std::vector<std::pair<std::string, schema::DatasetSpec>> datasets;
  std::vector<std::pair<std::string, schema::AttributeSpec>> attributes;
  std::vector<std::pair<std::string, schema::FlagSpec>> flags;
  std::vector<std::pair<std::string, std::vector<std::string>>> text_lists;
  /// A list of declarations: its name, the kind of its items and the items (resolved to the
  /// names of the declarations they equal when printed).
  struct SpecList {
    std::string name;
    std::vector<schema::DatasetSpec> datasets;
    std::vector<schema::AttributeSpec> attributes;
    std::vector<schema::FlagSpec> flags;
  };
  std::vector<SpecList> spec_lists;
  std::vector<std::string> order;  ///< every name, in the order of the headers

  /// Position of `name` in `order`.
  std::size_t position(const std::string& name) const {
    for (std::size_t i = 0; i < order.size(); ++i)
      if (order[i] == name) return i;
    return order.size();
  }
};

void add(Declarations& d, const char* name, const char* value) {
  d.texts.emplace_back(name, value);
}
void add(Declarations& d, const char* name, std::int64_t value) {
  d.integers.emplace_back(name, value);
}
void add(Declarations& d, const char* name, const schema::DatasetSpec& value) {
  d.datasets.emplace_back(name, value);
}
void add(Declarations& d, const char* name, const schema::AttributeSpec& value) {
  d.attributes.emplace_back(name, value);
}
void add(Declarations& d, const char* name, const schema::FlagSpec& value) {
  d.flags.emplace_back(name, value);
}
template <std::size_t N>
void add(Declarations& d, const char* name, const std::array<const char*, N>& value) {
  d.text_lists.emplace_back(name, std::vector<std::string>(value.begin(), value.end()));
}
template <std::size_t N>
void add(Declarations& d, const char* name, const std::array<schema::DatasetSpec, N>& value) {
  d.spec_lists.push_back({name, {value.begin(), value.end()}, {}, {}});
}
template <std::size_t N>
void add(Declarations& d, const char* name, const std::array<schema::AttributeSpec, N>& value) {
  d.spec_lists.push_back({name, {}, {value.begin(), value.end()}, {}});
}
template <std::size_t N>
void add(Declarations& d, const char* name, const std::array<schema::FlagSpec, N>& value) {
  d.spec_lists.push_back({name, {}, {}, {value.begin(), value.end()}});
}

Declarations declarations() {
  Declarations d;
  using namespace hexdyn::schema;
#define HEXDYN_SCHEMA_DECLARATION(name) \
  d.order.emplace_back(#name);          \
  add(d, #name, name);
#include HEXDYN_SCHEMA_NAMES  // NOLINT
#undef HEXDYN_SCHEMA_DECLARATION
  return d;
}

/// The name of the declaration an item of the list `list` is (lists hold copies of named
/// declarations): of those equal to `item`, the last declared before the list (two file kinds
/// may declare equal attributes or datasets, each in its own section, e.g. /meta
/// base_config_yaml of a sweep and of an envelope). Throws when none is equal.
template <class Spec>
std::string name_of(const Declarations& d, const std::vector<std::pair<std::string, Spec>>& named,
                    const Spec& item, const std::string& list) {
  const std::size_t end = d.position(list);
  std::string found;
  for (const auto& [name, spec] : named)
    if (same(spec, item) && (found.empty() || d.position(name) < end)) found = name;
  if (found.empty())
    throw std::runtime_error("an item of " + list + " equals no named declaration");
  return found;
}

std::string module_text(const Declarations& d) {
  std::ostringstream out;
  out << "\"\"\"The HDF5 contracts of hexdyn (src/hexdyn/io/schema.hpp), generated at build time "
         "by\n"
         "bindings/python/schema/schema_py.cpp from the compiled declarations: do not edit.\n\n"
         "CONSTANTS   {name: str or int}: schema names and versions, group paths, attribute names\n"
         "DATASETS    {name: (path, units, shape, element, long_name, dims)}; shape a tuple of\n"
         "            sizes (int) and size symbols (\"T\", \"n\", \"N\", ...), dims the netCDF\n"
         "            dimension names of its axes\n"
         "ATTRIBUTES  {name: (object, attribute name, element)}\n"
         "FLAGS       {name: (path, flag meanings)}\n"
         "LISTS       {name: (kind, names)}: the std::array lists of declarations, kind\n"
         "            \"datasets\", \"attributes\" or \"flags\", each item the name of the\n"
         "            declaration it is\n"
         "TEXT_LISTS  {name: (str, ...)}\n"
         "ORDER       every name in the order of the headers\n"
         "\"\"\"\n\n";
  std::vector<std::string> order;
  out << "CONSTANTS = {\n";
  for (const auto& [name, value] : d.texts)
    out << "    " << py_str(name.c_str()) << ": " << py_str(value.c_str()) << ",\n";
  for (const auto& [name, value] : d.integers)
    out << "    " << py_str(name.c_str()) << ": " << value << ",\n";
  out << "}\n\nDATASETS = {\n";
  for (const auto& [name, s] : d.datasets)
    out << "    " << py_str(name.c_str()) << ": (" << py_str(s.path) << ", " << py_str(s.units)
        << ", " << shape_tuple(s.shape) << ", " << py_str(element_name(s.element)) << ", "
        << py_str(s.long_name) << ", " << py_tuple(words(schema::dimension_names(s.shape)))
        << "),\n";
  out << "}\n\nATTRIBUTES = {\n";
  for (const auto& [name, a] : d.attributes)
    out << "    " << py_str(name.c_str()) << ": (" << py_str(a.object) << ", " << py_str(a.name)
        << ", " << py_str(element_name(a.element)) << "),\n";
  out << "}\n\nFLAGS = {\n";
  for (const auto& [name, f] : d.flags)
    out << "    " << py_str(name.c_str()) << ": (" << py_str(f.path) << ", "
        << py_tuple(words(f.meanings)) << "),\n";
  out << "}\n\nLISTS = {\n";
  for (const Declarations::SpecList& l : d.spec_lists) {
    std::vector<std::string> names;
    const char* kind = "datasets";
    for (const auto& s : l.datasets) names.push_back(name_of(d, d.datasets, s, l.name));
    if (!l.attributes.empty()) kind = "attributes";
    for (const auto& a : l.attributes) names.push_back(name_of(d, d.attributes, a, l.name));
    if (!l.flags.empty()) kind = "flags";
    for (const auto& f : l.flags) names.push_back(name_of(d, d.flags, f, l.name));
    out << "    " << py_str(l.name.c_str()) << ": (" << py_str(kind) << ", " << py_tuple(names)
        << "),\n";
  }
  out << "}\n\nTEXT_LISTS = {\n";
  for (const auto& [name, items] : d.text_lists)
    out << "    " << py_str(name.c_str()) << ": " << py_tuple(items) << ",\n";
  out << "}\n\nORDER = (\n";
#define HEXDYN_SCHEMA_DECLARATION(name) out << "    " << py_str(#name) << ",\n";
#include HEXDYN_SCHEMA_NAMES  // NOLINT
#undef HEXDYN_SCHEMA_DECLARATION
  out << ")\n";
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " OUT.py\n";
    return 2;
  }
  const std::string path = argv[1];
  const std::string tmp = path + ".tmp";
  try {
    const std::string text = module_text(declarations());
    {
      std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
      f << text;
      f.close();
      if (!f) throw std::runtime_error("cannot write " + tmp);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw std::runtime_error("cannot rename " + tmp + " to " + path);
  } catch (const std::exception& e) {
    std::remove(tmp.c_str());
    std::cerr << "hexdyn_schema_py: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
