#include <mr/core/openmesh_convert.h>

namespace mr {

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
    // OpenMesh rejects (and logs) faces at complex edges or vertices.
    if (repeated || !mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]).is_valid())
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
