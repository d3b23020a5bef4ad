// The one option parser and the help written from the tables (cli/command.hpp).
#include <array>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>

#include "hexdyn/cli/command.hpp"
#include "hexdyn/core/errors.hpp"
#include "hexdyn/core/progress.hpp"

namespace hexdyn::cli {
namespace {

constexpr std::array kOptions{
    OptionSpec{kOutput, "-o", "--output", "FILE"},
    OptionSpec{kSet, "--set", nullptr, "key.path=value", true},
    OptionSpec{kAllowLarge, "--allow-large", nullptr, nullptr},
    OptionSpec{kKeepRuns, "--keep-runs", nullptr, nullptr},
    OptionSpec{kResume, "--resume", nullptr, nullptr},
    OptionSpec{kVerbose, "-v", "--verbose", nullptr},
    OptionSpec{kProgress, "--progress", nullptr, "SECONDS"},
    OptionSpec{kJobs, "-j", "--jobs", "N"},
};

bool is_help(const char* arg) { return !std::strcmp(arg, "--help") || !std::strcmp(arg, "-h"); }

/// The option `arg` names: its name or alias, or "--set=VALUE" (the value given inline,
/// `*inline_value` set); nullptr for none.
const OptionSpec* match(const std::string& arg, std::optional<std::string>* inline_value) {
  for (const OptionSpec& o : kOptions) {
    if (arg == o.name || (o.alias && arg == o.alias)) return &o;
    const std::string eq = std::string(o.name) + "=";
    if (o.repeatable && arg.rfind(eq, 0) == 0) {
      *inline_value = arg.substr(eq.size());
      return &o;
    }
  }
  return nullptr;
}

/// "validate: --keep-runs belongs to 'hexdyn sweep'", from the rows that take it.
ConfigError refusal(const Command& c, const OptionSpec& o) {
  if (o.option == kSet && *c.set_refusal)
    return ConfigError(std::string(c.name) + ": --set is not available; " + c.set_refusal);
  std::vector<std::string> owners;
  for (const Command& other : commands())
    if (other.options & o.option) owners.push_back(std::string("'hexdyn ") + other.name + "'");
  std::string list;
  for (std::size_t i = 0; i < owners.size(); ++i)
    list += (i == 0 ? "" : i + 1 == owners.size() ? " and " : ", ") + owners[i];
  return ConfigError(std::string(c.name) + ": " + o.name + " belongs" + " to " + list);
}

void apply(Args& a, Option option, const std::string& value) {
  switch (option) {
    case kOutput:
      a.output = value;
      break;
    case kSet:
      a.overrides.push_back(parse_override(value));
      break;
    case kAllowLarge:
      a.allow_large = true;
      break;
    case kKeepRuns:
      a.keep_runs = true;
      break;
    case kResume:
      a.resume = true;
      break;
    case kVerbose:
      a.verbose = true;
      break;
    case kProgress:
      a.progress_s = parse_progress_interval(value);
      break;
    case kJobs: {
      char* end = nullptr;
      const long n = std::strtol(value.c_str(), &end, 10);
      if (value.empty() || *end != '\0' || n < 1 || n > 1024)
        throw ConfigError("--jobs: got " + value +
                          ", expected a whole number of threads in [1, 1024]");
      a.jobs = static_cast<int>(n);
      break;
    }
  }
}

/// "-o FILE", "[--set key.path=value ...]", "[-v]" for a usage line.
std::string option_usage(const OptionSpec& o, bool required) {
  std::string s = o.name;
  if (o.value_name) s += std::string(" ") + o.value_name;
  if (o.repeatable) s += " ...";
  return required ? s : "[" + s + "]";
}

/// "hexdyn run CONFIG -o FILE [--set key.path=value ...] ...", wrapped at `width` columns
/// with continuation lines indented by `indent`.
std::string synopsis(const Command& c, std::size_t lead, std::size_t width) {
  std::string out = std::string("hexdyn ") + c.name + " " + c.operand;
  std::size_t column = lead + out.size();
  const std::string indent(lead + std::strlen("hexdyn ") + std::strlen(c.name) + 1, ' ');
  for (const OptionSpec& o : kOptions) {
    if (!(c.options & o.option)) continue;
    const std::string word = option_usage(o, c.required & o.option);
    if (column + 1 + word.size() > width) {
      out += "\n" + indent + word;
      column = indent.size() + word.size();
    } else {
      out += " " + word;
      column += 1 + word.size();
    }
  }
  return out;
}

}  // namespace

std::span<const OptionSpec> options() { return kOptions; }

const Command* find_command(const std::string& name) {
  for (const Command& c : commands())
    if (name == c.name) return &c;
  return nullptr;
}

Args parse_args(const Command& c, int argc, char** argv) {
  Args a;
  a.command = &c;
  a.argc = argc;
  a.argv = argv;
  for (int i = 2; i < argc; ++i) {
    const std::string arg = argv[i];
    std::optional<std::string> value;
    const OptionSpec* o = match(arg, &value);
    if (!o && !arg.empty() && arg[0] == '-')
      throw ConfigError("unknown option " + arg + "; run 'hexdyn " + c.name + " --help'");
    if (!o && a.input.empty()) {
      a.input = arg;
      continue;
    }
    if (!o)
      throw ConfigError("unexpected argument " + arg + "; run 'hexdyn " + c.name + " --help'");
    if (!(c.options & o->option)) throw refusal(c, *o);
    if (o->value_name && !value) {
      if (i + 1 >= argc) throw ConfigError(std::string(o->name) + ": missing value");
      value = argv[++i];
    }
    apply(a, o->option, value.value_or(""));
  }
  if (a.input.empty()) throw ConfigError(std::string(c.name) + ": missing " + c.operand + " file");
  if ((c.required & kOutput) && a.output.empty())
    throw ConfigError(std::string(c.name) + ": missing -o FILE");
  return a;
}

bool asks_for_help(int argc, char** argv) {
  for (int i = 2; i < argc; ++i) {
    std::optional<std::string> inline_value;
    const OptionSpec* o = match(argv[i], &inline_value);
    if (o && o->value_name && !inline_value) {
      ++i;  // a flag's value is not a request for help
      continue;
    }
    if (is_help(argv[i])) return true;
  }
  return false;
}

std::string usage(const Command& c) {
  return "usage: " + synopsis(c, std::strlen("usage: "), 92) + "\n" + c.help;
}

std::string overview() {
  std::ostringstream s;
  s << "hexdyn — inverse dynamics of a legged robot on stairs\n\nusage:\n";
  for (const Command& c : commands())
    s << "  " << synopsis(c, 2, 92) << "\n      " << c.summary << "\n";
  s << "  hexdyn COMMAND --help\n      help on one command\n"
    << "  hexdyn --help | --version\n\n"
    << "Exit status: 0 success, 2 bad input (config, arguments, output path), 3 a scene that\n"
       "cannot be computed (unreachable foothold, ...), 4 an internal error. Configuration\n"
       "files must be regular files of at most 1 MiB, without duplicate keys.\n";
  for (const Command& c : commands()) s << "\n" << usage(c);
  return s.str();
}

}  // namespace hexdyn::cli
