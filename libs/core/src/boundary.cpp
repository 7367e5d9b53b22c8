#include <mr/core/boundary.h>

#include <algorithm>
#include <tuple>

namespace mr {
namespace {

// The four faces of a positively oriented tet (a,b,c,d), each oriented outward.
constexpr int kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

struct TetFace {
  Triangle sorted;  // key: vertex indices in increasing order
  Triangle oriented;
  std::size_t tet;
};

std::vector<TetFace> collect_faces(const TetMesh& mesh, const TetSelector& selected) {
  std::vector<TetFace> faces;
  for (std::size_t t = 0; t < mesh.tets.size(); ++t) {
    if (selected && !selected(t)) continue;
    const Tet& tet = mesh.tets[t];
    for (const auto& f : kTetFaces) {
      Triangle oriented{tet[f[0]], tet[f[1]], tet[f[2]]};
      Triangle sorted = oriented;
      std::sort(sorted.begin(), sorted.end());
      faces.push_back({sorted, oriented, t});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const TetFace& a, const TetFace& b) {
    return std::tie(a.sorted, a.tet) < std::tie(b.sorted, b.tet);
  });
  return faces;
}

std::int32_t label_of(const TetMesh& mesh, std::size_t tet) {
  return mesh.has_tet_labels() ? mesh.tet_labels[tet] : 0;
}

// Keeps only referenced vertices, in order of first use.
TriangleSoup compact(const TetMesh& mesh, std::vector<Triangle> triangles,
                     std::vector<std::int32_t> regions) {
  TriangleSoup soup;
  std::vector<Index> remap(mesh.positions.size(), Index(-1));
  for (Triangle& t : triangles)
    for (Index& v : t) {
      if (remap[v] == Index(-1)) {
        remap[v] = static_cast<Index>(soup.positions.size());
        soup.positions.push_back(mesh.positions[v]);
      }
      v = remap[v];
    }
  soup.triangles = std::move(triangles);
  soup.face_regions = std::move(regions);
  return soup;
}

}  // namespace

TriangleSoup extract_boundary(const TetMesh& mesh, const TetSelector& selected, bool keep_tet_labels) {
  const std::vector<TetFace> faces = collect_faces(mesh, selected);
  std::vector<Triangle> triangles;
  std::vector<std::int32_t> regions;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].sorted == faces[i].sorted) ++j;
    if (j - i == 1) {
      triangles.push_back(faces[i].oriented);
      if (keep_tet_labels) regions.push_back(label_of(mesh, faces[i].tet));
    }
    i = j;
  }
  return compact(mesh, std::move(triangles), std::move(regions));
}

TriangleSoup extract_interfaces(const TetMesh& mesh) {
  const std::vector<TetFace> faces = collect_faces(mesh, {});
  std::vector<Triangle> triangles;
  std::vector<std::int32_t> regions;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].sorted == faces[i].sorted) ++j;
    const std::int32_t first = label_of(mesh, faces[i].tet);
    if (j - i == 1) {
      triangles.push_back(faces[i].oriented);
      regions.push_back(first);
    } else if (j - i == 2 && label_of(mesh, faces[i + 1].tet) != first) {
      const std::size_t lower = label_of(mesh, faces[i + 1].tet) < first ? i + 1 : i;
      triangles.push_back(faces[lower].oriented);
      regions.push_back(label_of(mesh, faces[lower].tet));
    }
    i = j;
  }
  return compact(mesh, std::move(triangles), std::move(regions));
}

}  // namespace mr
