// Where improvement stopped short of the stop energy, and why: each tet
// left at or above it is counted by the freest of its corners. A tet with a
// free corner is one no operation could improve; one whose corners all sit
// on the tracked surface, its creases or the input's boundary is held there
// by the envelope and the features it keeps.

#include "improve_local.h"

#include <algorithm>
#include <array>

namespace mr::tetmesh::improve_detail {
namespace {

// Names and tallies in the order of Mobility, freest first.
constexpr std::array<const char*, 4> kNames{"free", "sliding", "creased", "fixed"};

std::size_t& tally(StuckReport& report, Mobility m) {
  const std::array<std::size_t*, 4> tallies{&report.free, &report.sliding, &report.creased, &report.fixed};
  return *tallies[static_cast<std::size_t>(m)];
}

}  // namespace

StuckReport stuck_report(Workspace& ws, std::span<const double> energy, std::size_t worst) {
  const Mesh& mesh = ws.mesh;
  std::vector<Index> stuck;
  for (Index t = 0; t < energy.size(); ++t) {
    if (mesh.tet_alive(t) && ws.drives(t) && energy[t] >= ws.stop_energy) stuck.push_back(t);
  }
  // Worst first; ties by slot, so the report does not depend on the threads.
  std::sort(stuck.begin(), stuck.end(),
            [&](Index a, Index b) { return energy[a] != energy[b] ? energy[a] > energy[b] : a < b; });
  std::vector<Mobility> of_vertex(mesh.vertex_slots(), Mobility::fixed);
  std::vector<char> known(mesh.vertex_slots(), 0);
  const auto corner_mobility = [&](Index v) {
    if (!known[v]) of_vertex[v] = mobility(ws, v, ws.star(v)), known[v] = 1;
    return of_vertex[v];
  };
  StuckReport report;
  report.tets = stuck.size();
  for (const Index t : stuck) {
    Mobility freest = Mobility::fixed;
    for (const Index v : mesh.tet(t)) freest = std::min(freest, corner_mobility(v));
    ++tally(report, freest);
    if (report.worst.size() == worst) continue;
    Vec3d centre = Vec3d::Zero();
    for (const Index v : mesh.tet(t)) centre += mesh.position(v).approx / 4.0;
    report.worst.push_back(
        {energy[t], {centre.x(), centre.y(), centre.z()}, kNames[static_cast<std::size_t>(freest)]});
  }
  return report;
}

}  // namespace mr::tetmesh::improve_detail
