// Medit .mesh (ASCII): Vertices, Tetrahedra and Triangles with references
// (labels), 1-based indices. Other keywords are skipped by their entry sizes.

#include "tet_formats_internal.h"

#include <mr/core/errors.h>
#include <mr/io/output_file.h>
#include <mr/io/text_cursor.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <string>

namespace mr::plugins::tet {
namespace {

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// Numbers per entry of the keywords this reader skips; -1 for unknown.
int skipped_entry_size(std::string_view keyword, int dimension) {
  struct Entry {
    const char* keyword;
    int size;
  };
  static constexpr Entry kSizes[] = {{"Edges", 3},
                                     {"Corners", 1},
                                     {"Ridges", 1},
                                     {"RequiredVertices", 1},
                                     {"RequiredEdges", 1},
                                     {"RequiredTriangles", 1},
                                     {"RequiredQuadrilaterals", 1},
                                     {"RequiredTetrahedra", 1},
                                     {"Quadrilaterals", 5},
                                     {"Hexahedra", 9},
                                     {"Prisms", 7},
                                     {"Pyramids", 6},
                                     {"EdgesP2", 4},
                                     {"TrianglesP2", 7},
                                     {"QuadrilateralsQ2", 10},
                                     {"TetrahedraP2", 11},
                                     {"HexahedraQ2", 28},
                                     {"Tangents", -2},
                                     {"Normals", -2},
                                     {"NormalAtVertices", 2},
                                     {"TangentAtVertices", 2},
                                     {"TangentAtEdges", 3},
                                     {"NormalAtTriangleVertices", 3},
                                     {"NormalAtQuadrilateralVertices", 3},
                                     {"SubDomainFromMesh", 4},
                                     {"SubDomainFromGeom", 4},
                                     {"VertexOnGeometricVertex", 2},
                                     {"VertexOnGeometricEdge", 3},
                                     {"VertexOnGeometricTriangle", 4},
                                     {"EdgeOnGeometricEdge", 2},
                                     {"Crack", 2},
                                     {"Identifier", 0},
                                     {"Geometry", 0}};
  for (const Entry& e : kSizes)
    if (equals_ignoring_case(keyword, e.keyword)) return e.size == -2 ? dimension : e.size;
  return -1;
}

class MeditReader {
 public:
  MeditReader(const std::string& path, std::string_view bytes) : cursor_(path, bytes, '#') {}

  TetMesh read() {
    if (!equals_ignoring_case(cursor_.token_or_empty(), "MeshVersionFormatted"))
      cursor_.fail("not a Medit mesh file (it does not start with MeshVersionFormatted)");
    const std::int64_t version = cursor_.signed_integer("MeshVersionFormatted");
    if (version < 1 || version > 4)
      cursor_.fail("unsupported MeshVersionFormatted " + std::to_string(version));
    while (true) {
      const std::string_view keyword = cursor_.token_or_empty();
      if (keyword.empty() || equals_ignoring_case(keyword, "End")) break;
      read_keyword(keyword);
    }
    if (!seen_vertices_) cursor_.fail("no Vertices section");
    return std::move(mesh_);
  }

 private:
  void read_keyword(std::string_view keyword) {
    if (equals_ignoring_case(keyword, "Dimension")) {
      const std::int64_t dim = cursor_.signed_integer("Dimension");
      if (dim != 2 && dim != 3) cursor_.fail("unsupported Dimension " + std::to_string(dim));
      dimension_ = static_cast<int>(dim);
    } else if (equals_ignoring_case(keyword, "Vertices")) {
      read_vertices();
    } else if (equals_ignoring_case(keyword, "Tetrahedra")) {
      read_cells(mesh_.tets, mesh_.tet_labels, "Tetrahedra");
    } else if (equals_ignoring_case(keyword, "Triangles")) {
      read_cells(mesh_.faces, mesh_.face_labels, "Triangles");
    } else {
      skip_keyword(keyword);
    }
  }

  std::uint64_t count(const char* what, std::uint64_t numbers_per_entry) {
    const std::uint64_t n = cursor_.unsigned_integer(what);
    cursor_.require(n, 2 * numbers_per_entry, what);  // each number takes >= 2 bytes with its separator
    return n;
  }

  void read_vertices() {
    if (seen_vertices_) cursor_.fail("a second Vertices section");
    seen_vertices_ = true;
    const std::uint64_t n = count("Vertices", dimension_ + 1);
    mesh_.positions.reserve(n);
    for (std::uint64_t i = 0; i < n; ++i) {
      const double x = cursor_.real("vertex x"), y = cursor_.real("vertex y");
      const double z = dimension_ == 3 ? cursor_.real("vertex z") : 0.0;
      cursor_.signed_integer("vertex reference");
      mesh_.positions.emplace_back(x, y, z);
    }
  }

  // Indices are 1-based and checked against the vertex count as they are read;
  // Medit files list Vertices before the elements that use them. Cells are
  // kept as written, even when negatively oriented: orientation is a contract
  // checked by the caller, not something a reader repairs silently.
  template <std::size_t N>
  void read_cells(std::vector<std::array<Index, N>>& cells, std::vector<std::int32_t>& labels,
                  const char* what) {
    if (!seen_vertices_) cursor_.fail(std::string(what) + " before Vertices");
    const std::uint64_t n = count(what, N + 1);
    cells.reserve(cells.size() + n);
    labels.reserve(labels.size() + n);
    const std::uint64_t vertices = mesh_.positions.size();
    for (std::uint64_t e = 0; e < n; ++e) {
      std::array<Index, N> cell;
      for (Index& v : cell) {
        const std::uint64_t index = cursor_.unsigned_integer("vertex index");
        if (index == 0 || index > vertices)
          cursor_.fail(std::string(what) + " entry " + std::to_string(e + 1) + " refers to vertex " +
                       std::to_string(index) + " but the vertices are numbered 1 to " +
                       std::to_string(vertices));
        v = static_cast<Index>(index - 1);
      }
      cells.push_back(cell);
      labels.push_back(cursor_.int32("reference"));
    }
  }

  void skip_keyword(std::string_view keyword) {
    const int size = skipped_entry_size(keyword, dimension_);
    if (size < 0) cursor_.fail("unknown keyword '" + std::string(keyword.substr(0, 40)) + "'");
    if (size == 0) {  // a single string value
      cursor_.token("keyword value");
      return;
    }
    const std::string name(keyword.substr(0, 40));
    const std::uint64_t n = count(name.c_str(), static_cast<std::uint64_t>(size));
    for (std::uint64_t i = 0; i < n * static_cast<std::uint64_t>(size); ++i) cursor_.token("entry value");
  }

  io::TextCursor cursor_;
  TetMesh mesh_;
  int dimension_ = 3;
  bool seen_vertices_ = false;
};

template <std::size_t N>
void write_cells(io::OutputFile& out, const char* keyword, const std::vector<std::array<Index, N>>& cells,
                 const std::vector<std::int32_t>& labels) {
  if (cells.empty()) return;
  out << "\n" << keyword << "\n" << static_cast<std::int64_t>(cells.size()) << "\n";
  for (std::size_t c = 0; c < cells.size(); ++c) {
    for (Index v : cells[c]) out << std::int64_t(v) + 1 << " ";
    out << static_cast<std::int64_t>(labels.empty() ? 0 : labels[c]) << "\n";
  }
}

}  // namespace

TetMesh read_medit(std::string_view bytes, const std::string& name) {
  return MeditReader(name, bytes).read();
}

void write_medit(const TetMesh& mesh, const std::filesystem::path& path) {
  io::OutputFile out(path);
  out << "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n"
      << static_cast<std::int64_t>(mesh.positions.size()) << "\n";
  for (const Vec3d& p : mesh.positions) out << p.x() << " " << p.y() << " " << p.z() << " 0\n";
  write_cells(out, "Tetrahedra", mesh.tets, mesh.tet_labels);
  write_cells(out, "Triangles", mesh.faces, mesh.face_labels);
  out << "\nEnd\n";
  out.close();
}

}  // namespace mr::plugins::tet
