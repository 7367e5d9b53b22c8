#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mr::tools {

/// `tetrahedralize IN OUT [options]`: a valid tet mesh of the solid the input
/// surface describes, the input embedded. Exit 0 on success, 2 on bad usage
/// or unreadable input, 1 on a failed run.
int tetrahedralize(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace mr::tools
