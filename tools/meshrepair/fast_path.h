#pragma once
// The settings of meshrepair's rebuild through tets, shared by the tool and
// the Python module so the two cannot drift apart.

#include <mr/repair/repair.h>
#include <mr/tetmesh/tetrahedralize.h>

namespace mr::tools {

/// The fast path needs a valid embedding, not well-shaped interior tets, so
/// its background mesh has no voxel lattice: lattice points make every input
/// triangle cross many more tets (docs/ARCHITECTURE.md, "Repair").
tetmesh::TetrahedralizeOptions repair_defaults();

/// The tetrahedralization meshrepair runs: filtered by |winding number| > 1/2
/// (a solid whose faces all point inward is repaired too; the peeled surface is
/// oriented by the tets, so it comes out outward), rejected tets kept for the
/// manifold fix, no quality improvement.
tetmesh::PipelineOptions repair_pipeline_options(const tetmesh::TetrahedralizeOptions& tetrahedralize);

/// The surface repair's options for a pipeline's result; the output grids are the caller's.
repair::RepairOptions surface_repair_options(const tetmesh::PipelineResult& pipeline, int threads,
                                             bool cleanup);

/// The tet labels as the surface repair takes them (1 = inside).
std::vector<std::uint8_t> inside_labels(const tetmesh::PipelineResult& pipeline);

}  // namespace mr::tools
