// Vertex smoothing: Newton steps on the summed conformal AMIPS energy of a
// vertex's tets (in a polish, on a soft maximum of them where one of its
// tets is at or above the stop energy), with a backtracking line search
// that accepts only positions keeping every tet strictly positive (exact), the star's
// largest energy not higher, and the vertex's tracked faces inside the
// envelope. Surface vertices move in their tangent plane, hull vertices
// within their box face(s); vertices on surface boundaries, creases, or
// flagged locked stay.

#include "improve_local.h"

#include <mr/kernel/rounding.h>
#include <mr/spatial/triangle_distance.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mr::tetmesh::improve_detail {
namespace {

using Mat3 = Eigen::Matrix3d;

// One tet of the star seen from the moving vertex: the other three corners,
// ordered so that the tet is positive when orient3d(p, b, c, d) > 0.
struct Opposite {
  Vec3d b, c, d;
};

// What a step minimizes: the sum of the star's energies, or, with a
// positive `reference`, the soft maximum sum (E / reference)^kSoftMaxPower.
// The sum's minimum can keep a bad tet bad, its neighbours gaining more than
// it loses; the line search then refuses the step, as the largest energy
// would rise, and the vertex stays. On thingi10k/55581, 51 of the 77 tets
// left above the stop energy had a corner whose star's largest energy could
// go from 11-14 to 5-10 by moving that corner alone (the 8 worst have every
// corner on the surface, next to its creases, and cannot).
struct Objective {
  double reference = 0;  ///< 0: the sum
};

constexpr int kSoftMaxPower = 8;

// The objective with gradient and Hessian in p. AMIPS = N / D^(2/3) with
// N = (sum of squared edges) / 2 and D = sqrt(2) * 6 * volume: the closed
// form of tr(J^T J) / det(J)^(2/3) against the regular unit tet.
struct EnergyTerms {
  double value = 0, max = 0;
  Vec3d gradient = Vec3d::Zero();
  Mat3 hessian = Mat3::Zero();
  bool finite = true;
};

EnergyTerms star_energy(const Vec3d& p, std::span<const Opposite> tets, bool derivatives,
                        Objective objective = {}) {
  EnergyTerms out;
  const double r = objective.reference;
  for (const Opposite& o : tets) {
    const Vec3d n = (o.c - o.b).cross(o.d - o.b);
    const double det = std::sqrt(2.0) * (o.b - p).dot((o.c - p).cross(o.d - p));
    if (!(det > 0)) {
      out.finite = false;
      return out;
    }
    const double sq = (p - o.b).squaredNorm() + (p - o.c).squaredNorm() + (p - o.d).squaredNorm() +
                      (o.b - o.c).squaredNorm() + (o.c - o.d).squaredNorm() + (o.d - o.b).squaredNorm();
    const double N = 0.5 * sq;
    const double d23 = std::cbrt(det * det);
    const double e = N / d23;
    out.max = std::max(out.max, e);
    // d(objective)/dE and d2(objective)/dE2 for this tet.
    double weight = 1, curvature = 0;
    if (r > 0) {
      const double ratio = e / r, r2 = ratio * ratio, r6 = r2 * r2 * r2;
      static_assert(kSoftMaxPower == 8);
      out.value += r6 * r2;
      weight = kSoftMaxPower / r * r6 * ratio;
      curvature = kSoftMaxPower * (kSoftMaxPower - 1) / (r * r) * r6;
    } else {
      out.value += e;
    }
    if (!derivatives) continue;
    const Vec3d gN = 3 * p - (o.b + o.c + o.d);
    const Vec3d gD = -std::sqrt(2.0) * n;
    const Vec3d g = gN / d23 - (2.0 / 3.0) * N * gD / (d23 * det);
    const Mat3 h = 3 * Mat3::Identity() / d23 -
                   (2.0 / 3.0) / (d23 * det) * (gN * gD.transpose() + gD * gN.transpose()) +
                   (10.0 / 9.0) * N / (d23 * det * det) * gD * gD.transpose();
    out.gradient += weight * g;
    out.hessian += weight * h + curvature * g * g.transpose();
  }
  if (!std::isfinite(out.value)) out.finite = false;
  return out;
}

// Where the vertex may go: nowhere, or p + d with d restricted as below.
struct Freedom {
  bool fixed = false;
  std::array<bool, 3> frozen_axis{false, false, false};  ///< box faces the vertex lies on
  bool tangent = false;                                  ///< stay in the plane of `normal`
  Vec3d normal = Vec3d::Zero();
  std::vector<FaceCorners> tracked;  ///< its tracked faces, checked against the envelope
  /// Fixed only by its tracked faces (a crease, an intersection curve, a
  /// non-disk neighbourhood); `tracked` then holds them all.
  bool creased = false;
  /// Its tracked faces form a disk (two faces on each surface edge), each on
  /// one input triangle: a crease of one surface, not a line where parts
  /// meet or cross, nor overlapping copies.
  bool one_sheet = false;
  /// Its tracked faces form a fan with one or two faces on each surface
  /// edge, one at least (the open boundary of one sheet), each on one input
  /// triangle. `open_edges` are its neighbours across the edges of one face.
  bool boundary_sheet = false;
  std::vector<Index> open_edges;
  /// Moves anywhere, then back onto the nearest of `sources` (a creased
  /// vertex released where its tets are bad).
  bool project = false;
  /// The input triangles its tracked faces lie on (filled for a creased
  /// vertex).
  std::vector<std::uint32_t> sources;
};

// Whether v's tracked faces are the open boundary of one sheet (Freedom::
// boundary_sheet); fills `open_edges`.
void find_boundary_sheet(const std::vector<TrackedFace>& faces, Index v, Freedom& out) {
  std::vector<Index> neighbours;
  for (const TrackedFace& f : faces) {
    if (f.ids.size() != 1) return;
    for (const Index w : f.key) {
      if (w != v) neighbours.push_back(w);
    }
  }
  std::sort(neighbours.begin(), neighbours.end());
  std::vector<Index> open;
  for (std::size_t i = 0; i < neighbours.size();) {
    std::size_t j = i;
    while (j < neighbours.size() && neighbours[j] == neighbours[i]) ++j;
    if (j - i > 2) return;
    if (j - i == 1) open.push_back(neighbours[i]);
    i = j;
  }
  out.boundary_sheet = !open.empty();
  out.open_edges = std::move(open);
}

Vec3d unit_normal(const Mesh& mesh, const FaceKey& f) {
  const Vec3d& a = mesh.position(f[0]).approx;
  return (mesh.position(f[1]).approx - a).cross(mesh.position(f[2]).approx - a).normalized();
}

// Surface around v: a disk (two faces on each surface edge) that is nearly flat.
bool surface_freedom(const Mesh& mesh, const std::vector<TrackedFace>& faces, Index v, Freedom& out) {
  constexpr double kMinCosine = 0.866;  // creases sharper than 30 degrees stay put
  std::vector<Index> neighbours;
  for (const TrackedFace& f : faces) {
    for (const Index w : f.key) {
      if (w != v) neighbours.push_back(w);
    }
  }
  std::sort(neighbours.begin(), neighbours.end());
  for (std::size_t i = 0; i < neighbours.size();) {
    std::size_t j = i;
    while (j < neighbours.size() && neighbours[j] == neighbours[i]) ++j;
    if (j - i != 2) return false;
    i = j;
  }
  out.one_sheet =
      std::all_of(faces.begin(), faces.end(), [](const TrackedFace& f) { return f.ids.size() == 1; });
  const Vec3d first = unit_normal(mesh, faces[0].key);
  Vec3d sum = Vec3d::Zero();
  std::vector<Vec3d> normals;
  for (const TrackedFace& f : faces) {
    Vec3d n = unit_normal(mesh, f.key);
    if (n.dot(first) < 0) n = -n;
    if (!n.allFinite()) return false;
    normals.push_back(n);
    sum += n;
  }
  const Vec3d average = sum.normalized();
  for (const Vec3d& n : normals) {
    if (n.dot(average) < kMinCosine) return false;
  }
  out.tangent = true;
  out.normal = average;
  for (const TrackedFace& f : faces) out.tracked.push_back(f.key);
  return true;
}

Freedom freedom_of(const Mesh& mesh, Index v, std::span<const Index> star) {
  Freedom out;
  if ((mesh.flags(v) & (kLocked | kOnBoundary)) != 0 || star.empty()) {
    out.fixed = true;
    return out;
  }
  bool on_hull = false;
  for (const Index t : star) {
    for (int f = 0; f < 4; ++f) {
      if (mesh.neighbour(t, f) != kNoTet || mesh.tet(t)[f] == v || mesh.corner_of(t, v) < 0) continue;
      on_hull = true;
      const std::array<Index, 3> c = mesh.face_vertices(t, f);
      bool any = false;
      for (int axis = 0; axis < 3; ++axis) {
        const double x = mesh.position(c[0]).approx[axis];
        if (mesh.position(c[1]).approx[axis] == x && mesh.position(c[2]).approx[axis] == x) {
          out.frozen_axis[axis] = any = true;
        }
      }
      if (!any) out.fixed = true;  // a hull face off the box planes: do not touch
    }
  }
  if (mesh.has_flag(v, kOnBox) && !on_hull) out.fixed = true;
  const std::vector<TrackedFace> faces = tracked_faces_at(mesh, star, v);
  if (!faces.empty() && (on_hull || !surface_freedom(mesh, faces, v, out))) {
    out.creased = !out.fixed && !on_hull;
    out.fixed = true;
    out.tangent = false;
    out.tracked.clear();
    for (const TrackedFace& f : faces) out.tracked.push_back(f.key);
    if (out.creased) {
      find_boundary_sheet(faces, v, out);
      for (const TrackedFace& f : faces) out.sources.insert(out.sources.end(), f.ids.begin(), f.ids.end());
      std::sort(out.sources.begin(), out.sources.end());
      out.sources.erase(std::unique(out.sources.begin(), out.sources.end()), out.sources.end());
    }
  }
  return out;
}

// The nearest point to p on the given triangles of the soup.
Vec3d project_onto(const TriangleSoup& soup, std::span<const std::uint32_t> triangles, const Vec3d& p) {
  Vec3d best = p;
  double best_sq = std::numeric_limits<double>::infinity();
  for (const std::uint32_t t : triangles) {
    const auto& c = soup.triangles[t];
    const spatial::PointOnPrimitive hit =
        spatial::closest_on_triangle(p, soup.positions[c[0]], soup.positions[c[1]], soup.positions[c[2]]);
    if (hit.squared_distance < best_sq) {
      best_sq = hit.squared_distance;
      best = hit.point;
    }
  }
  return best;
}

Vec3d restrict_step(Vec3d d, const Freedom& freedom) {
  if (freedom.tangent) d -= d.dot(freedom.normal) * freedom.normal;
  for (int axis = 0; axis < 3; ++axis) {
    if (freedom.frozen_axis[axis]) d[axis] = 0;
  }
  return d;
}

std::vector<Opposite> opposites(const Mesh& mesh, Index v, std::span<const Index> star) {
  std::vector<Opposite> out;
  out.reserve(star.size());
  for (const Index t : star) {
    const std::array<Index, 3> o = opposite_face(mesh.tet(t), mesh.corner_of(t, v));
    out.push_back({mesh.position(o[0]).approx, mesh.position(o[1]).approx, mesh.position(o[2]).approx});
  }
  return out;
}

// The Newton direction, or the scaled descent direction when the Hessian
// (restricted to the free directions) is not positive definite.
Vec3d step_direction(const EnergyTerms& at, const Freedom& freedom, double scale) {
  const Vec3d g = restrict_step(at.gradient, freedom);
  if (g.squaredNorm() == 0 || !g.allFinite()) return Vec3d::Zero();
  Mat3 h = at.hessian;
  Mat3 projector = Mat3::Identity();
  if (freedom.tangent) projector -= freedom.normal * freedom.normal.transpose();
  for (int axis = 0; axis < 3; ++axis) {
    if (freedom.frozen_axis[axis]) projector.row(axis).setZero();
  }
  h = projector * h * projector.transpose() + (Mat3::Identity() - projector * projector.transpose());
  const Eigen::LDLT<Mat3> solver(h);
  if (solver.info() == Eigen::Success && solver.isPositive()) {
    const Vec3d d = restrict_step(solver.solve(-g), freedom);
    if (d.allFinite() && d.dot(g) < 0 && d.norm() < 10 * scale) return d;
  }
  return -g.normalized() * (0.1 * scale);
}

// Accepts p when it keeps the star valid and its tracked faces inside, and,
// for a released vertex, the open boundary edges at v inside the envelope
// of the input's open edges (seed 3.4: a boundary may not drift across the
// surface).
bool valid_position(const Workspace& ws, Index v, std::span<const Index> star, const Vec3d& p,
                    const Freedom& freedom) {
  std::vector<Tet> tets;
  tets.reserve(star.size());
  for (const Index t : star) tets.push_back(ws.mesh.tet(t));
  const HybridPoint at(p);
  if (!all_positive(ws.mesh, tets, {v, &at}) || !faces_inside(ws, freedom.tracked, {v, &at})) return false;
  if (!freedom.project || freedom.open_edges.empty()) return true;
  if (ws.open_boundary == nullptr) return false;
  return std::all_of(freedom.open_edges.begin(), freedom.open_edges.end(),
                     [&](Index x) { return ws.open_boundary->is_inside(p, ws.mesh.position(x).approx); });
}

// A creased vertex may be released where its tets are bad: on a crease of
// one sheet, at the open boundary of one (its boundary edges checked, see
// valid_position), or anywhere when asked (ImproveOptions::release_junctions).
// Where parts meet, projected onto one part's triangle, it could turn the
// other part's faces over for a filter orienting tracked faces by geometry
// (manifold/openscad-nonmanifold-crash left the envelope by 19 eps).
bool releasable(const Workspace& ws, const Freedom& freedom) {
  if (!freedom.creased || ws.triangles == nullptr) return false;
  return freedom.one_sheet || freedom.boundary_sheet || ws.release_junctions;
}

double average_edge(std::span<const Opposite> tets, const Vec3d& p) {
  double sum = 0;
  for (const Opposite& o : tets) sum += (o.b - p).norm() + (o.c - p).norm() + (o.d - p).norm();
  return sum / double(3 * tets.size());
}

// At most this many soft-maximum steps a vertex takes in a pass.
constexpr int kSoftMaxSteps = 8;

// One Newton step on the objective with a backtracking line search; moves
// v and returns true where a position passes (see the file comment).
bool newton_step(const Workspace& ws, Index v, std::span<const Index> star, std::span<const Opposite> tets,
                 const Freedom& freedom, Objective objective) {
  const Vec3d p0 = ws.mesh.position(v).approx;
  const EnergyTerms before = star_energy(p0, tets, true, objective);
  if (!before.finite) return false;
  const Vec3d d = step_direction(before, freedom, average_edge(tets, p0));
  if (d.squaredNorm() == 0) return false;
  for (double s = 1; s > 1.0 / 1024; s /= 2) {
    Vec3d p = p0 + s * d;
    for (int axis = 0; axis < 3; ++axis) {
      if (freedom.frozen_axis[axis]) p[axis] = p0[axis];
    }
    if (freedom.project) p = project_onto(*ws.triangles, freedom.sources, p);
    if (p == p0) continue;
    const EnergyTerms after = star_energy(p, tets, false, objective);
    if (!after.finite || after.value >= before.value || after.max > before.max) continue;
    if (!valid_position(ws, v, star, p, freedom)) continue;
    ws.mesh.position(v) = HybridPoint(p);
    return true;
  }
  return false;
}

}  // namespace

bool try_smooth(const Workspace& ws, Index v, std::span<const Index> star, bool soft_max) {
  Freedom freedom = freedom_of(ws.mesh, v, star);
  if (freedom.fixed && !releasable(ws, freedom)) return false;
  // The energy of the tets that count; every tet of the star stays positive.
  const std::vector<Opposite> tets = opposites(ws.mesh, v, ws.counted(star));
  if (tets.empty()) return false;
  const EnergyTerms before = star_energy(ws.mesh.position(v).approx, tets, false);
  if (!before.finite) return false;
  // A creased vertex moves only where its tets are bad, so that features
  // are blunted (within the envelope) only where quality needs it.
  if (freedom.fixed) {
    if (before.max < ws.stop_energy) return false;
    freedom.fixed = false;
    freedom.project = true;
  }
  // With soft_max (in a polish, see run_pass), a vertex of a bad tet takes
  // soft-maximum steps while they lower its star's largest energy.
  if (before.max < ws.stop_energy || !soft_max) return newton_step(ws, v, star, tets, freedom, {});
  bool moved = false;
  for (int step = 0; step < kSoftMaxSteps; ++step) {
    const double worst = star_energy(ws.mesh.position(v).approx, tets, false).max;
    if (!newton_step(ws, v, star, tets, freedom, {worst})) break;
    moved = true;
  }
  return moved;
}

Mobility mobility(const Workspace& ws, Index v, std::span<const Index> star) {
  const Freedom freedom = freedom_of(ws.mesh, v, star);
  if (freedom.fixed) return releasable(ws, freedom) ? Mobility::creased : Mobility::fixed;
  const bool on_box =
      std::find(freedom.frozen_axis.begin(), freedom.frozen_axis.end(), true) != freedom.frozen_axis.end();
  return freedom.tangent || on_box ? Mobility::sliding : Mobility::free;
}

bool try_relocate(const Workspace& ws, Index v, std::span<const Index> star) {
  const Freedom freedom = freedom_of(ws.mesh, v, star);
  // A creased vertex (on a feature or on the crossing of two input
  // surfaces) may leave its crease by a rounding error's worth, no more:
  // its tracked faces stay in the envelope, and the feature stays sharp.
  if (freedom.fixed && !freedom.creased) return false;
  const double largest_step = freedom.creased ? 0x1p-24 : 0.5;
  const Vec3d p0 = ws.mesh.position(v).approx;
  Vec3d centre = Vec3d::Zero();
  const std::vector<Opposite> tets = opposites(ws.mesh, v, star);
  for (const Opposite& o : tets) centre += (o.b + o.c + o.d) / 3.0;
  centre /= double(tets.size());
  const Vec3d d = restrict_step(centre - p0, freedom);
  // Tiny moves first: the rational point is usually a rounding error away
  // from a position that works.
  for (double s = 0x1p-40; s <= largest_step; s *= 16) {
    Vec3d p = p0 + s * d;
    for (int axis = 0; axis < 3; ++axis) {
      if (freedom.frozen_axis[axis]) p[axis] = p0[axis];
    }
    if (!star_energy(p, tets, false).finite || !valid_position(ws, v, star, p, freedom)) continue;
    ws.mesh.position(v) = HybridPoint(p);
    return true;
  }
  return false;
}

}  // namespace mr::tetmesh::improve_detail
