#include <mr/core/openmesh_convert.h>

namespace mr {
namespace {

// OpenMesh's add_face refuses a face at a complex vertex (an interior vertex)
// or a complex edge (a halfedge already used) and logs each refusal to its
// global error stream. Testing the same conditions first keeps that stream quiet.
bool halfedge_structure_accepts(const TriMesh& mesh, const TriMesh::VertexHandle (&v)[3]) {
  for (int i = 0; i < 3; ++i) {
    if (!mesh.is_boundary(v[i]) && !mesh.is_isolated(v[i])) return false;
    const auto h = mesh.find_halfedge(v[i], v[(i + 1) % 3]);
    if (h.is_valid() && !mesh.is_boundary(h)) return false;
  }
  return true;
}

}  // namespace

ToTriMeshResult to_trimesh(const TriangleSoup& soup) {
  ToTriMeshResult result;
  TriMesh& mesh = result.mesh;
  mesh.reserve(soup.positions.size(), 3 * soup.triangles.size() / 2, soup.triangles.size());
  std::vector<TriMesh::VertexHandle> handles;
  handles.reserve(soup.positions.size());
  for (const Vec3d& p : soup.positions) handles.push_back(mesh.add_vertex(TriMesh::Point(p.x(), p.y(), p.z())));
  for (std::size_t f = 0; f < soup.triangles.size(); ++f) {
    const Triangle& t = soup.triangles[f];
    const bool repeated = t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    const TriMesh::VertexHandle v[3] = {handles[t[0]], handles[t[1]], handles[t[2]]};
    if (repeated || !halfedge_structure_accepts(mesh, v) || !mesh.add_face(v[0], v[1], v[2]).is_valid())
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
