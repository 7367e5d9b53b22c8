#include <mr/cli/options.h>
#include <mr/core/errors.h>

#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

#include <unistd.h>

namespace mr::cli {
namespace {

const Option* find_option(const ToolSpec& spec, const std::string& name) {
  for (const Option& option : spec.options)
    if (option.long_name == name || (!option.short_name.empty() && option.short_name == name)) return &option;
  return nullptr;
}

bool looks_like_option(const std::string& arg) {
  // "-" alone and negative numbers are values, not options.
  if (arg.size() < 2 || arg[0] != '-') return false;
  return !(std::isdigit(static_cast<unsigned char>(arg[1])) || arg[1] == '.');
}

}  // namespace

std::vector<std::string> parse_arguments(const ToolSpec& spec, std::span<const std::string> args) {
  std::vector<std::string> positionals;
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string arg = args[i];
    if (arg == "--") {
      positionals.insert(positionals.end(), args.begin() + i + 1, args.end());
      break;
    }
    if (!looks_like_option(arg)) {
      positionals.push_back(arg);
      continue;
    }
    std::string inline_value;
    bool has_inline_value = false;
    if (auto eq = arg.find('='); arg.starts_with("--") && eq != std::string::npos) {
      inline_value = arg.substr(eq + 1);
      arg = arg.substr(0, eq);
      has_inline_value = true;
    }
    const Option* option = find_option(spec, arg);
    if (!option) throw UsageError("unknown option '" + arg + "' (see --help)");
    if (option->value_name.empty()) {
      if (has_inline_value) throw UsageError("option " + arg + " takes no value");
      option->apply("");
      continue;
    }
    if (!has_inline_value) {
      if (i + 1 >= args.size()) throw UsageError("option " + arg + " needs a value " + option->value_name);
      inline_value = args[++i];
    }
    option->apply(inline_value);
  }
  if (positionals.size() != spec.positionals.size()) {
    std::ostringstream message;
    message << spec.name << " expects " << spec.positionals.size() << " argument(s)";
    for (const std::string& name : spec.positionals) message << ' ' << name;
    message << ", got " << positionals.size() << " (see --help)";
    throw UsageError(message.str());
  }
  return positionals;
}

std::string help_text(const ToolSpec& spec) {
  std::ostringstream out;
  out << "Usage: " << spec.name;
  for (const std::string& name : spec.positionals) out << ' ' << name;
  out << " [options]\n\n" << spec.summary << "\n";
  if (!spec.description.empty()) out << "\n" << spec.description << "\n";
  out << "\nOptions:\n";
  std::vector<std::pair<std::string, std::string>> rows;
  rows.emplace_back("-h, --help", "print this help and exit");
  rows.emplace_back("--version", "print the version and exit");
  for (const Option& option : spec.options) {
    std::string names = option.short_name.empty() ? "    " : option.short_name + ", ";
    names += option.long_name;
    if (!option.value_name.empty()) names += " " + option.value_name;
    rows.emplace_back(names, option.help);
  }
  std::size_t width = 0;
  for (const auto& row : rows) width = std::max(width, row.first.size());
  for (const auto& [names, help] : rows)
    out << "  " << names << std::string(width - names.size() + 2, ' ') << help << "\n";
  return out.str();
}

Option quiet_option(bool& quiet) {
  return {"--quiet", "-q", "", "print nothing on success", [&quiet](const std::string&) { quiet = true; }};
}

Option verbose_option(bool& verbose, const std::string& help) {
  return {"--verbose", "-v", "", help, [&verbose](const std::string&) { verbose = true; }};
}

Option threads_option(int& threads) {
  return {"--threads", "-j", "N", "worker threads (default: all)",
          [&threads](const std::string& v) { threads = parse_int("--threads", v, 1, 1024); }};
}

Option stats_option(std::string& path, const std::string& help) {
  return {"--stats", "", "FILE", help, [&path](const std::string& v) { path = v; }};
}

std::size_t default_max_memory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return std::numeric_limits<std::size_t>::max();
  return static_cast<std::size_t>(pages) / 10 * 8 * static_cast<std::size_t>(page_size);
}

Option max_memory_option(std::size_t& bytes) {
  return {"--max-memory", "", "MB",
          "refuse (exit 2) an input whose run would need more memory than this, before allocating "
          "for it (default: 80% of this machine's memory)",
          [&bytes](const std::string& v) {
            bytes = static_cast<std::size_t>(parse_int("--max-memory", v, 1, 1 << 30)) << 20;
          }};
}

Option ascii_option(bool& binary) {
  return {"--ascii", "", "", "write the text variant of STL, PLY and MSH (default: binary)",
          [&binary](const std::string&) { binary = false; }};
}

double parse_double(const std::string& option, const std::string& value) {
  double result = 0;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, result);
  if (ec != std::errc() || ptr != end || !std::isfinite(result))
    throw UsageError("option " + option + " needs a number, got '" + value + "'");
  return result;
}

int parse_int(const std::string& option, const std::string& value, int min, int max) {
  int result = 0;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, result);
  if (ec != std::errc() || ptr != end || result < min || result > max)
    throw UsageError("option " + option + " needs an integer in [" + std::to_string(min) + ", " +
                     std::to_string(max) + "], got '" + value + "'");
  return result;
}

}  // namespace mr::cli
