#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mr::tools {

/// `hole-fill IN OUT [--max-boundary N] [--max-diameter D] [--fair 0|1|2]
/// [--density keep|coarse] [--stats FILE] [-j N] [-q] [-v] [--ascii]`: closes
/// the holes of a surface, every input face kept. Exit 0 when every hole
/// selected by the limits is filled, 1 when some could not be (the output
/// is written with the others filled), 2 on bad usage or unreadable input.
int hole_fill(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace mr::tools
