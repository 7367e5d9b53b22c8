#include <mr/tetmesh/mesh_check.h>

#include <mr/core/errors.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <string>
#include <tuple>
#include <vector>

namespace mr::tetmesh {
namespace {

std::string tet_name(Index t) { return "tet " + std::to_string(t); }

std::string check_corners(const Mesh& mesh, Index t) {
  const Tet& c = mesh.tet(t);
  for (int i = 0; i < 4; ++i) {
    if (!mesh.vertex_alive(c[i]))
      return tet_name(t) + " uses removed or missing vertex " + std::to_string(c[i]);
    for (int j = 0; j < i; ++j) {
      if (c[i] == c[j]) return tet_name(t) + " repeats vertex " + std::to_string(c[i]);
    }
  }
  return "";
}

std::array<Index, 3> sorted_face(const Mesh& mesh, Index t, int f) {
  std::array<Index, 3> key = mesh.face_vertices(t, f);
  std::sort(key.begin(), key.end());
  return key;
}

std::string check_neighbour(const Mesh& mesh, Index t, int f) {
  const Index u = mesh.neighbour(t, f);
  if (u == kNoTet) return "";
  const std::string where = tet_name(t) + " face " + std::to_string(f);
  if (!mesh.tet_alive(u)) return where + " points to removed or missing tet " + std::to_string(u);
  const int back = mesh.face_towards(u, t);
  if (back < 0) return where + " -> " + tet_name(u) + " is not symmetric";
  if (sorted_face(mesh, t, f) != sorted_face(mesh, u, back)) {
    return where + " and " + tet_name(u) + " do not share that face's corners";
  }
  const std::array<Index, 3> face = mesh.face_vertices(t, f);
  const HybridPoint& a = mesh.position(face[0]);
  const HybridPoint& b = mesh.position(face[1]);
  const HybridPoint& c = mesh.position(face[2]);
  const int side_t = orient3d(a, b, c, mesh.position(mesh.tet(t)[f]));
  const int side_u = orient3d(a, b, c, mesh.position(mesh.tet(u)[back]));
  if (side_t * side_u >= 0) return where + " and " + tet_name(u) + " are not on opposite sides of it";
  if (mesh.surface_handle(t, f) != mesh.surface_handle(u, back)) {
    return where + " has different surface marks on its two sides";
  }
  return "";
}

std::string check_marks(const Mesh& mesh, Index t, int f) {
  if (!mesh.is_surface_face(t, f)) return "";
  for (const Index v : mesh.face_vertices(t, f)) {
    if (!mesh.has_flag(v, kOnSurface)) {
      return tet_name(t) + " face " + std::to_string(f) + " is tracked but vertex " + std::to_string(v) +
             " is not flagged on-surface";
    }
  }
  return "";
}

// Lowest live tet index that is not strictly positive, or kNoTet.
Index first_badly_oriented(const Mesh& mesh) {
  return tbb::parallel_reduce(
      tbb::blocked_range<Index>(0, static_cast<Index>(mesh.tet_slots()), 1024), kNoTet,
      [&](const tbb::blocked_range<Index>& range, Index found) {
        for (Index t = range.begin(); t != range.end() && t < found; ++t) {
          if (!mesh.tet_alive(t)) continue;
          const Tet& c = mesh.tet(t);
          if (orient3d(mesh.position(c[0]), mesh.position(c[1]), mesh.position(c[2]), mesh.position(c[3])) <=
              0) {
            return t;
          }
        }
        return found;
      },
      [](Index a, Index b) { return std::min(a, b); });
}

// Free faces must have no twin; no face may appear three times.
std::string check_face_multiplicity(const Mesh& mesh) {
  std::vector<std::tuple<std::array<Index, 3>, Index, int>> faces;
  faces.reserve(mesh.num_tets() * 4);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int f = 0; f < 4; ++f) faces.emplace_back(sorted_face(mesh, t, f), t, f);
  }
  tbb::parallel_sort(faces.begin(), faces.end());
  for (std::size_t i = 0; i + 1 < faces.size(); ++i) {
    const auto& [key, t, f] = faces[i];
    if (key != std::get<0>(faces[i + 1])) continue;
    if (i + 2 < faces.size() && key == std::get<0>(faces[i + 2])) {
      return "a face of " + tet_name(t) + " is shared by more than two tets";
    }
    if (mesh.neighbour(t, f) == kNoTet) {
      return tet_name(t) + " face " + std::to_string(f) + " is free but " +
             tet_name(std::get<1>(faces[i + 1])) + " has the same face";
    }
  }
  return "";
}

std::string check_vertices(const Mesh& mesh) {
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    if (!mesh.vertex_alive(v)) continue;
    const HybridPoint& p = mesh.position(v);
    if (p.exact && round_to_nearest(*p.exact) != p.approx) {
      return "vertex " + std::to_string(v) + ": approx is not the nearest double of its rational";
    }
  }
  return "";
}

}  // namespace

std::string find_mesh_inconsistency(const Mesh& mesh) {
  if (std::string problem = check_vertices(mesh); !problem.empty()) return problem;
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    if (std::string problem = check_corners(mesh, t); !problem.empty()) return problem;
  }
  if (const Index bad = first_badly_oriented(mesh); bad != kNoTet) {
    return tet_name(bad) + " is not positively oriented (exact orient3d <= 0)";
  }
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (int f = 0; f < 4; ++f) {
      if (std::string problem = check_neighbour(mesh, t, f); !problem.empty()) return problem;
      if (std::string problem = check_marks(mesh, t, f); !problem.empty()) return problem;
    }
  }
  return check_face_multiplicity(mesh);
}

void check_in_debug([[maybe_unused]] const Mesh& mesh, [[maybe_unused]] const char* where) {
#ifndef NDEBUG
  if (std::string problem = find_mesh_inconsistency(mesh); !problem.empty()) {
    throw RunError(std::string(where) + ": tet mesh invariant violated: " + problem);
  }
#endif
}

}  // namespace mr::tetmesh
