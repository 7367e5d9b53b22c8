#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mr::tools {

/// `mesh-check FILE [options]`: verifies a surface or tet mesh and prints a
/// JSON report. Exit 0 if it meets the expectation, 1 if not, 2 if unreadable.
int mesh_check(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace mr::tools
