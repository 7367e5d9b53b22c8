#pragma once
// Conversions between the soup and OpenMesh's halfedge TriMesh, for the
// algorithms that need adjacency. A soup may hold faces a halfedge structure
// cannot (non-manifold edges, degenerate faces): those are reported, not lost
// silently.

#include <mr/core/triangle_soup.h>

#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <vector>

namespace mr {

struct OpenMeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using TriMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMeshTraits>;

struct ToTriMeshResult {
  TriMesh mesh;
  /// Soup triangles the halfedge structure rejected (complex edge or vertex,
  /// repeated index). Their indices into soup.triangles, in increasing order.
  std::vector<std::size_t> rejected_triangles;
};

/// Whether mesh.add_face(a, b, c) would accept the face: the same tests,
/// without changing the mesh or writing to OpenMesh's error stream. False for
/// a repeated vertex.
bool can_add_face(const TriMesh& mesh, TriMesh::VertexHandle a, TriMesh::VertexHandle b,
                  TriMesh::VertexHandle c);

/// Adds every vertex of the soup (isolated ones too, same indices) and every
/// triangle OpenMesh accepts, in order. Never calls add_face with a face it
/// would refuse, so nothing is written to OpenMesh's error stream.
ToTriMeshResult to_trimesh(const TriangleSoup& soup);

/// Every vertex and face of the mesh; deleted elements are skipped.
TriangleSoup to_soup(const TriMesh& mesh);

}  // namespace mr
