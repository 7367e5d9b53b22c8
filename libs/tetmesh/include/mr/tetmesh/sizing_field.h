#pragma once
// Sizing fields for mesh improvement (`tetrahedralize --sizing`): a target
// edge length that varies in space. A tet mesh with one value per vertex
// is fTetWild's convention (its --bg-mesh: a .msh whose $NodeData is named
// "values") and gmsh's background mesh; a float grid comes from the VDB
// plugin (io::Format::read_field).

#include <mr/core/scalar_field.h>
#include <mr/core/tet_mesh.h>
#include <mr/spatial/box_grid.h>

#include <memory>
#include <string>
#include <vector>

namespace mr::tetmesh {

/// Linear interpolation of one value per vertex over the tets of a mesh.
/// NaN outside every tet, and in a tet with a NaN corner value.
class TetMeshField : public ScalarField {
 public:
  /// `values` has one entry per vertex of `mesh`; flat tets are ignored.
  TetMeshField(TetMesh mesh, std::vector<double> values);
  double at(const Vec3d& p) const override;

 private:
  TetMesh mesh_;
  std::vector<double> values_;
  spatial::BoxGrid grid_;
};

/// The sizing field a tet mesh carries: its node field named "values"
/// (fTetWild's name), or its only node field. Throws InputError naming
/// `path` when it has no tets, no such field, or a value that is neither
/// positive nor NaN.
std::shared_ptr<const ScalarField> sizing_from_tet_mesh(TetMesh mesh, const std::string& path);

}  // namespace mr::tetmesh
