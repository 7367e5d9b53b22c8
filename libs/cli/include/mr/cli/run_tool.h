#pragma once
// The frame every tool's main() runs in: --help, --version, and the mapping
// of exceptions to messages and exit codes (0 ok, 1 run failure, 2 bad usage
// or unreadable input). Tools are callable in-process from an argv vector.

#include <mr/cli/options.h>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace mr::cli {

enum ExitCode : int { exit_ok = 0, exit_failure = 1, exit_bad_input = 2 };

/// Parses `args` with `spec` and calls `body(positionals)`. `args` excludes the program name.
int run_tool(const ToolSpec& spec, const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
             const std::function<void(const std::vector<std::string>&)>& body);

/// Runs `body` on at most `threads` worker threads (0: all), for tools whose
/// library calls have no thread option of their own.
void run_with_threads(int threads, const std::function<void()>& body);

/// The process's peak resident memory so far, in MB (for --stats).
double peak_memory_mb();

/// argv to a vector, without argv[0].
std::vector<std::string> arguments(int argc, char** argv);

std::string version_string();

}  // namespace mr::cli

namespace mr::cli {

/// Writes a tool's statistics (JSON text) to `path`; mr::RunError naming
/// the file when it cannot be written.
void write_stats_file(const std::string& path, const std::string& json_text);

}  // namespace mr::cli
