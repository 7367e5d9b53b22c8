#pragma once
// Command-line options declared once in a table that drives both parsing and
// --help, so the two never disagree.

#include <cstddef>
#include <functional>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

namespace mr::cli {

struct Option {
  std::string long_name;   ///< "--epsilon"
  std::string short_name;  ///< "-e", or "" for none
  std::string value_name;  ///< "EPS" for an option taking a value, "" for a flag
  std::string help;
  /// Called with the value (or "" for a flag); throws mr::UsageError on a bad value.
  std::function<void(const std::string& value)> apply;
};

struct ToolSpec {
  std::string name;                      ///< "format-convert"
  std::string summary;                   ///< one line
  std::vector<std::string> positionals;  ///< names of the required positional arguments
  std::string description;               ///< paragraphs printed after usage
  std::vector<Option> options;
};

/// Parses `args` (without the program name). Returns the positional
/// arguments. Throws UsageError on an unknown option, a missing value or a
/// wrong number of positionals. --help and --version are handled by run_tool.
std::vector<std::string> parse_arguments(const ToolSpec& spec, std::span<const std::string> args);

std::string help_text(const ToolSpec& spec);

/// The options every tool of the family spells the same way: what one tool
/// accepts, the others accept too wherever it means anything.
Option quiet_option(bool& quiet);                                 ///< -q, --quiet
Option verbose_option(bool& verbose, const std::string& help);    ///< -v, --verbose
Option threads_option(int& threads);                              ///< -j, --threads N (0: all)
Option stats_option(std::string& path, const std::string& help);  ///< --stats FILE
Option ascii_option(bool& binary);                                ///< --ascii: binary = false
Option max_memory_option(std::size_t& bytes);                     ///< --max-memory MB

/// Most of this machine's memory (80% of physical): the default of --max-memory.
std::size_t default_max_memory();

/// Value parsers for Option::apply; throw UsageError naming the option.
double parse_double(const std::string& option, const std::string& value);
int parse_int(const std::string& option, const std::string& value, int min, int max);

}  // namespace mr::cli
