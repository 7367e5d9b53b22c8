#include <mr/core/openmesh_convert.h>

namespace mr {

// OpenMesh's add_face refuses a face at a complex vertex (an interior vertex),
// at a complex edge (a halfedge already used), or when it cannot re-link the
// fans around a corner, and logs each refusal to its global error stream
// (std::cerr). The same tests, read-only, in the same order: add_face checks
// everything before it changes the mesh (its re-linking is cached until the
// end), so a face that passes here is accepted and one that fails is refused.
bool can_add_face(const TriMesh& mesh, TriMesh::VertexHandle a, TriMesh::VertexHandle b,
                  TriMesh::VertexHandle c) {
  const TriMesh::VertexHandle v[3] = {a, b, c};
  if (a == b || b == c || a == c) return false;
  TriMesh::HalfedgeHandle h[3];
  for (int i = 0; i < 3; ++i) {
    if (!mesh.is_boundary(v[i])) return false;  // complex vertex (isolated vertices count as boundary)
    h[i] = mesh.find_halfedge(v[i], v[(i + 1) % 3]);
    if (h[i].is_valid() && !mesh.is_boundary(h[i])) return false;  // complex edge
  }
  // Corner v[i + 1] between two existing edges that are not consecutive on the
  // boundary: the fans between them must move into another gap around the
  // corner. Walking around it from the outgoing edge, the first boundary
  // halfedge is that gap; if it is the incoming edge itself, there is none
  // (the face would close one fan while another one stays at the vertex).
  for (int i = 0; i < 3; ++i) {
    const int next = (i + 1) % 3;
    if (!h[i].is_valid() || !h[next].is_valid() || mesh.next_halfedge_handle(h[i]) == h[next]) continue;
    TriMesh::HalfedgeHandle gap = mesh.opposite_halfedge_handle(h[next]);
    do gap = mesh.opposite_halfedge_handle(mesh.next_halfedge_handle(gap));
    while (!mesh.is_boundary(gap));
    if (gap == h[i]) return false;  // "patch re-linking failed"
  }
  return true;
}

ToTriMeshResult to_trimesh(const TriangleSoup& soup) {
  ToTriMeshResult result;
  TriMesh& mesh = result.mesh;
  mesh.reserve(soup.positions.size(), 3 * soup.triangles.size() / 2, soup.triangles.size());
  std::vector<TriMesh::VertexHandle> handles;
  handles.reserve(soup.positions.size());
  for (const Vec3d& p : soup.positions)
    handles.push_back(mesh.add_vertex(TriMesh::Point(p.x(), p.y(), p.z())));
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const Triangle& t = soup.triangles[f];
    const TriMesh::VertexHandle a = handles[t[0]], b = handles[t[1]], c = handles[t[2]];
    if (!can_add_face(mesh, a, b, c) || !mesh.add_face(a, b, c).is_valid())
      result.rejected_triangles.push_back(f);
  }
  return result;
}

TriangleSoup to_soup(const TriMesh& mesh) {
  TriangleSoup soup;
  std::vector<Index> remap(mesh.n_vertices(), Index(-1));
  for (auto v : mesh.vertices()) {
    remap[v.idx()] = static_cast<Index>(soup.positions.size());
    const auto& p = mesh.point(v);
    soup.positions.emplace_back(p[0], p[1], p[2]);
  }
  for (auto f : mesh.faces()) {
    Triangle t{};
    int k = 0;
    for (auto v : f.vertices()) t[k++] = remap[v.idx()];
    soup.triangles.push_back(t);
  }
  return soup;
}

}  // namespace mr
