#include <mr/cli/run_tool.h>
#include <mr/core/errors.h>

#include <algorithm>
#include <fstream>
#include <new>
#include <ostream>

namespace mr::cli {

std::string version_string() { return MR_VERSION; }

std::vector<std::string> arguments(int argc, char** argv) {
  return std::vector<std::string>(argv + std::min(argc, 1), argv + argc);
}

int run_tool(const ToolSpec& spec, const std::vector<std::string>& args, std::ostream& out,
             std::ostream& err, const std::function<void(const std::vector<std::string>&)>& body) {
  if (std::any_of(args.begin(), args.end(), [](const std::string& a) { return a == "-h" || a == "--help"; })) {
    out << help_text(spec);
    return exit_ok;
  }
  if (std::find(args.begin(), args.end(), "--version") != args.end()) {
    out << spec.name << " " << version_string() << "\n";
    return exit_ok;
  }
  try {
    body(parse_arguments(spec, args));
    return exit_ok;
  } catch (const UsageError& e) {
    err << spec.name << ": " << e.what() << "\n";
    return exit_bad_input;
  } catch (const InputError& e) {
    err << spec.name << ": error: " << e.what() << "\n";
    return exit_bad_input;
  } catch (const std::bad_alloc&) {
    err << spec.name << ": error: out of memory\n";
    return exit_failure;
  } catch (const std::exception& e) {
    err << spec.name << ": error: " << e.what() << "\n";
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
