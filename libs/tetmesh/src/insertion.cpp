#include <mr/tetmesh/insertion.h>

#include "triangle_inserter.h"

#include <mr/core/errors.h>

#include <string>

namespace mr::tetmesh {

InsertionStats insert_triangles(Mesh& mesh, const TriangleSoup& input,
                                std::span<const Index> input_vertex, std::span<const char> skip,
                                const Logger& logger) {
  if (input_vertex.size() != input.positions.size()) {
    throw UsageError("insert_triangles: the vertex map does not match the input");
  }
  if (!skip.empty() && skip.size() != input.triangles.size()) {
    throw UsageError("insert_triangles: the skip list does not match the input");
  }
  detail::TriangleInserter inserter(mesh);
  InsertionStats stats;
  const std::size_t n = input.triangles.size();
  const std::size_t report_every = std::max<std::size_t>(1, n / 100);
  for (std::size_t i = 0; i < n; ++i) {
    if (!skip.empty() && skip[i] != 0) {
      ++stats.skipped;
      continue;
    }
    const Triangle& f = input.triangles[i];
    inserter.insert(input_vertex[f[0]], input_vertex[f[1]], input_vertex[f[2]], static_cast<std::uint32_t>(i));
    if (i % report_every == 0) logger.progress("insertion", static_cast<double>(i) / static_cast<double>(n));
  }
  const detail::InsertionCounters& c = inserter.counters();
  stats.inserted = c.inserted;
  stats.degenerate = c.degenerate;
  stats.cut_tets = c.cut_tets;
  stats.rebuilt_tets = c.rebuilt_tets;
  stats.new_tets = c.new_tets;
  stats.new_vertices = c.new_vertices;
  stats.steiner_points = c.steiner_points;
  stats.vertex_creator = inserter.creators();
  stats.vertex_creator.resize(mesh.vertex_slots(), InsertionStats::kNoCreator);
  for (Index v = 0; v < mesh.vertex_slots(); ++v) {
    stats.rational_vertices += mesh.vertex_alive(v) && mesh.position(v).is_exact();
  }
  logger.log(LogLevel::debug, "insertion: " + std::to_string(stats.inserted) + " triangles, " +
                                  std::to_string(stats.new_vertices) + " cut points, " +
                                  std::to_string(stats.rational_vertices) + " still rational");
  return stats;
}

}  // namespace mr::tetmesh
