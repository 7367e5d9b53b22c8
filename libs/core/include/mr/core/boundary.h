#pragma once
// The boundary surface of a set of tets.

#include <mr/core/tet_mesh.h>
#include <mr/core/triangle_soup.h>

#include <functional>

namespace mr {

/// Which tets form the solid whose boundary is taken.
using TetSelector = std::function<bool(std::size_t tet)>;

/// Faces of the selected tets that are not shared with another selected tet,
/// oriented outward (tets are assumed positively oriented). The result keeps
/// only the vertices it references. With `keep_tet_labels`, each face gets the
/// label of its tet as region id.
TriangleSoup extract_boundary(const TetMesh& mesh, const TetSelector& selected = {},
                              bool keep_tet_labels = false);

/// Faces between tets of different labels and faces on the outer boundary,
/// each once, oriented outward from the tet with the smaller label; region id
/// is that smaller label.
TriangleSoup extract_interfaces(const TetMesh& mesh);

}  // namespace mr
