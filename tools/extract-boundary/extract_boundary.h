#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mr::tools {

/// `extract-boundary IN OUT [--label N | --interfaces] [-q] [-v] [-j N] [--stats FILE]`: the boundary
/// surface of a tet mesh, oriented outward. Exit 0 on success, 2 on bad
/// usage or unreadable input, 1 on a failed run (e.g. unwritable output).
int extract_boundary(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace mr::tools
