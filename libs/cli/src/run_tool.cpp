#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>

#include <tbb/task_arena.h>

#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <new>
#include <ostream>

namespace mr::cli {

std::string version_string() { return MR_VERSION; }

void run_with_threads(int threads, const std::function<void()>& body) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute(body);
}

double peak_memory_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

std::vector<std::string> arguments(int argc, char** argv) {
  return std::vector<std::string>(argv + std::min(argc, 1), argv + argc);
}

namespace {

// "IN -> OUT: " for a tool's files, so a failure no message of ours foresaw
// still says what was being worked on.
std::string files_prefix(const std::vector<std::string>& files) {
  std::string prefix;
  for (const std::string& file : files) {
    if (!prefix.empty()) prefix += " -> ";
    prefix += file;
  }
  return prefix.empty() ? prefix : prefix + ": ";
}

}  // namespace

int run_tool(const ToolSpec& spec, const std::vector<std::string>& args, std::ostream& out, std::ostream& err,
             const std::function<void(const std::vector<std::string>&)>& body) {
  if (std::any_of(args.begin(), args.end(),
                  [](const std::string& a) { return a == "-h" || a == "--help"; })) {
    out << help_text(spec);
    return exit_ok;
  }
  if (std::find(args.begin(), args.end(), "--version") != args.end()) {
    out << spec.name << " " << version_string() << "\n";
    return exit_ok;
  }
  std::vector<std::string> files;
  try {
    files = parse_arguments(spec, args);
    body(files);
    return exit_ok;
  } catch (const UsageError& e) {
    err << spec.name << ": " << e.what() << "\n";
    return exit_bad_input;
  } catch (const InputError& e) {
    err << spec.name << ": error: " << e.what() << "\n";
    return exit_bad_input;
  } catch (const Error& e) {
    err << spec.name << ": error: " << e.what() << "\n";
    return exit_failure;
  } catch (const std::bad_alloc&) {
    err << spec.name << ": error: " << files_prefix(files) << "out of memory\n";
    return exit_failure;
  } catch (const std::exception& e) {
    // Not one of ours: a library's exception that no reader, writer or stage
    // turned into a message. Its text is kept as the detail, after what failed.
    err << spec.name << ": error: " << files_prefix(files)
        << "the run failed on an unexpected library error: " << library_error_text(e) << "\n";
    return exit_failure;
  }
}

}  // namespace mr::cli

namespace mr::cli {

void write_stats_file(const std::string& path, const std::string& json_text) {
  std::ofstream file(path);
  file << json_text << "\n";
  if (!file) throw RunError(path + ": cannot write the statistics file");
}

}  // namespace mr::cli
