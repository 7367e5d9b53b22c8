#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace mr::tools {

/// `meshrepair IN OUT [-e EPS] [--stats FILE] [-j N] [-q]`: any surface in,
/// a watertight surface out (closed, manifold, oriented outward, free of
/// self-intersections and zero-area faces, within epsilon of the input
/// except where holes were filled). Exit 0 on success, 2 on bad usage or
/// unreadable input, 1 on a failed run.
int meshrepair(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

}  // namespace mr::tools
