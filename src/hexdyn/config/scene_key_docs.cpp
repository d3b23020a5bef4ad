#include "hexdyn/config/scene_key_docs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <utility>

#include "hexdyn/config/actuators.hpp"
#include "hexdyn/config/scene_key_table.hpp"

namespace hexdyn {
namespace {

/// The shortest "%.Ng" or "%.Ne" text that reads back to x, with at least `from` digits.
std::string shortest(double x, char conversion, int from = 1) {
  char buf[40];
  for (int digits = from; digits <= 17; ++digits) {
    const char format[] = {'%', '.', '*', conversion, '\0'};
    std::snprintf(buf, sizeof buf, format, digits - (conversion == 'e' ? 1 : 0), x);
    if (std::strtod(buf, nullptr) == x) break;
  }
  return buf;
}

/// "1.5e-05" → "1.5e-5", "1e+06" → "1e6".
std::string clean_exponent(std::string text) {
  const std::size_t e = text.find('e');
  if (e == std::string::npos) return text;
  std::string mantissa = text.substr(0, e), exponent = text.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

std::string unit_text(std::string_view unit) {
  if (unit.empty() || unit == "1") return "";
  std::string u(unit);
  for (std::size_t at; (at = u.find("^2")) != std::string::npos;) u.replace(at, 2, "²");
  return " " + u;
}

std::string range_text(const scene_keys::Range& r, bool integer = false) {
  const auto number = [&](double x) {
    return integer ? std::to_string(static_cast<long long>(x)) : doc_number(x);
  };
  return std::string(r.lo_open ? "(" : "[") + number(r.lo) + ", " + number(r.hi) +
         (r.hi_open ? ")" : "]");
}

std::string choices_text(std::string_view choices) {
  std::string out;
  for (const auto& w : key_words(choices)) out += (out.empty() ? "`" : ", `") + w + "`";
  return out;
}

std::string allowed(const SceneKey& k) {
  std::string text(k.allowed_text);
  if (text.empty()) {
    switch (k.kind) {
      case KeyKind::kNumber:
        text = range_text(k.range) + unit_text(k.unit);
        break;
      case KeyKind::kInteger:
        text = "integer in " + range_text(k.range, true);
        break;
      case KeyKind::kNumbers:
        text = std::to_string(k.min_count) +
               (k.max_count == k.min_count ? "" : " to " + std::to_string(k.max_count)) +
               " numbers in " + range_text(k.range) + unit_text(k.unit);
        break;
      case KeyKind::kChoice:
        text = choices_text(k.choices);
        break;
      case KeyKind::kText:
        break;
    }
  }
  return k.when.empty() ? text : std::string(k.when) + ": " + text;
}

std::string default_cell(const SceneKey& k) {
  if (!k.default_text.empty()) return std::string(k.default_text);
  if (k.required) return "required";
  Scene d;
  if (k.field.number) return "`" + doc_number(*k.field.number(d)) + "`";
  if (k.field.integer) return "`" + std::to_string(*k.field.integer(d)) + "`";
  const auto words = key_words(k.choices);
  if (k.kind == KeyKind::kChoice && !words.empty())
    return "`" + words.at(k.field.get_choice ? k.field.get_choice(d) : 0) + "`";
  return "—";
}

std::string key_cell(const SceneKey& k) {
  const auto words = key_words(k.instances);
  if (words.empty()) return "`" + std::string(k.path) + "`";
  std::string others;
  for (std::size_t i = 1; i < words.size(); ++i) others += (i > 1 ? ", " : "") + words[i];
  return "`" + key_path(k, words[0]) + "` (same for " + others + ")";
}

/// `meaning` with its links written from the repository's root (as code cites docs:
/// `[x](docs/theory/model.md#sphere-feet)`) made relative to docs/user/, the page's folder.
std::string page_links(std::string_view meaning) {
  std::string text(meaning);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"](docs/user/", "]("},
                                 std::pair<std::string, std::string>{"](docs/", "](../"}})
    for (std::size_t at; (at = text.find(from)) != std::string::npos;)
      text.replace(at, from.size(), to);
  return text;
}

}  // namespace

std::string doc_number(double x) {
  if (std::isinf(x)) return x > 0 ? "∞" : "−∞";
  if (x < 0) return "−" + doc_number(-x);
  if (x == 0) return "0";
  for (int d : {1, 2, 3}) {  // π, π/2, π/3 and their multiples
    const double k = x * d / M_PI;
    if (std::abs(k - std::round(k)) < 1e-12 && std::round(k) >= 1) {
      const long n = std::lround(k);
      return (n == 1 ? "" : std::to_string(n)) + "π" + (d == 1 ? "" : "/" + std::to_string(d));
    }
  }
  const double exponent = std::log10(x);
  if (exponent == std::round(exponent) && (exponent >= 4 || exponent <= -3))
    return clean_exponent(shortest(x, 'e'));
  // Enough digits for the integer part: 10, not 1e1.
  return clean_exponent(shortest(x, 'g', std::max(1, static_cast<int>(std::floor(exponent)) + 1)));
}

std::vector<std::string> scene_key_sections() {
  std::vector<std::string> sections;
  for (const SceneKey& k : scene_key_table()) {
    const std::string s(k.section);
    if (!s.empty() && std::find(sections.begin(), sections.end(), s) == sections.end())
      sections.push_back(s);
  }
  return sections;
}

std::string scene_key_markdown(std::string_view section) {
  std::string out = "| key | allowed | default | meaning |\n|---|---|---|---|\n";
  for (const SceneKey& k : scene_key_table()) {
    if (k.section != section) continue;
    out += "| " + key_cell(k) + " | " + allowed(k) + " | " + default_cell(k) + " | " +
           page_links(k.meaning) + " |\n";
  }
  return out;
}

std::string actuator_key_markdown() {
  std::string out = "| key | allowed | default | meaning |\n|---|---|---|---|\n";
  for (const scene_keys::ActuatorKey& k : scene_keys::actuator_keys()) {
    const std::string allowed = !k.allowed_text.empty() ? std::string(k.allowed_text)
                                : k.key == "model"      ? "a name of the servo table"
                                                        : range_text(k.range) + unit_text(k.unit);
    out += "| `" + std::string(k.key) + "` | " + allowed + " | " + std::string(k.default_text) +
           " | " + page_links(k.meaning) + " |\n";
  }
  return out;
}

std::string scene_key_regions() {
  std::string out;
  const auto region = [&](const std::string& name, const std::string& table) {
    out += "<!-- BEGIN GENERATED: " + name + " -->\n" + table + "<!-- END GENERATED -->\n";
  };
  for (const auto& s : scene_key_sections()) region(s, scene_key_markdown(s));
  region("actuators", actuator_key_markdown());
  return out;
}

}  // namespace hexdyn
