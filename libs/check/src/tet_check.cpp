#include "exact.h"

#include <mr/check/tet_check.h>
#include <mr/core/boundary.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mr::check {
namespace {

struct Tally {
  std::size_t inverted = 0, degenerate = 0;
  double volume = 0, min_dihedral = 180, sum_min_dihedral = 0, max_amips = 0, sum_amips = 0;

  void add(const Tally& o) {
    inverted += o.inverted;
    degenerate += o.degenerate;
    volume += o.volume;
    min_dihedral = std::min(min_dihedral, o.min_dihedral);
    sum_min_dihedral += o.sum_min_dihedral;
    max_amips = std::max(max_amips, o.max_amips);
    sum_amips += o.sum_amips;
  }
};

Tally tally_range(const TetMesh& mesh, std::size_t begin, std::size_t end) {
  Tally tally;
  for (std::size_t i = begin; i < end; ++i) {
    const Tet& t = mesh.tets[i];
    const Vec3d &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]],
                &d = mesh.positions[t[3]];
    const int sign = detail::orient3d_sign(a, b, c, d);
    if (sign < 0) ++tally.inverted;
    if (sign == 0) ++tally.degenerate;
    tally.volume += (b - a).cross(c - a).dot(d - a) / 6;
    const double dihedral = min_dihedral_angle_deg(a, b, c, d);
    tally.min_dihedral = std::min(tally.min_dihedral, dihedral);
    tally.sum_min_dihedral += dihedral;
    const double amips = sign > 0 ? amips_energy(a, b, c, d) : std::numeric_limits<double>::infinity();
    tally.max_amips = std::max(tally.max_amips, amips);
    tally.sum_amips += amips;
  }
  return tally;
}

}  // namespace

// Above this, amips_energy recomputes the determinant exactly (fTetWild
// recomputes the whole energy in rationals above the same bound).
constexpr double kReliableAmips = 1e8;
// det of the inverse of a regular tet's edge matrix: 1 / (sqrt(2) / 2).
constexpr double kRegularInverseDeterminant = 1.4142135623730951;

double amips_energy(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  // Edge matrix of the tet times the inverse of a regular tet's edge matrix.
  static const Eigen::Matrix3d regular_inverse = [] {
    Eigen::Matrix3d regular;
    regular.col(0) = Vec3d(1, 0, 0);
    regular.col(1) = Vec3d(0.5, std::sqrt(3.0) / 2, 0);
    regular.col(2) = Vec3d(0.5, std::sqrt(3.0) / 6, std::sqrt(2.0 / 3.0));
    return Eigen::Matrix3d(regular.inverse());
  }();
  Eigen::Matrix3d edges;
  edges.col(0) = b - a;
  edges.col(1) = c - a;
  edges.col(2) = d - a;
  const Eigen::Matrix3d jacobian = edges * regular_inverse;
  const double det = jacobian.determinant();
  const double energy = jacobian.squaredNorm() / std::cbrt(det * det);
  if (det > 0 && energy < kReliableAmips) return energy;
  // Near flat, the determinant of the rounded edges may be all rounding
  // error, of either sign: take it exactly (the squared norm is well
  // conditioned). The tet is infinite only when exactly flat or inverted,
  // so an improvement step can tell a near-flat tet from a worse one.
  const double exact = detail::exact_orient3d_value(a, b, c, d);
  if (!(exact > 0)) return std::numeric_limits<double>::infinity();
  const double root = std::cbrt(exact * kRegularInverseDeterminant);
  return jacobian.squaredNorm() / (root * root);
}

double min_dihedral_angle_deg(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  const Vec3d p[4] = {a, b, c, d};
  // Outward-agnostic face normals; the dihedral angle at edge (i,j) is pi minus
  // the angle between the normals of the two faces containing it.
  auto face_normal = [&](int skip) {
    int v[3], k = 0;
    for (int i = 0; i < 4; ++i)
      if (i != skip) v[k++] = i;
    Vec3d n = (p[v[1]] - p[v[0]]).cross(p[v[2]] - p[v[0]]);
    if ((p[skip] - p[v[0]]).dot(n) > 0) n = -n;  // point away from the opposite vertex
    return n.normalized();
  };
  double smallest = 180;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      // The edge (k,l) opposite to (i,j) is shared by the faces skipping i and skipping j.
      const double cosine = std::clamp(-face_normal(i).dot(face_normal(j)), -1.0, 1.0);
      const double angle = std::acos(cosine) * 180 / M_PI;
      smallest = std::min(smallest, std::isfinite(angle) ? angle : 0.0);
    }
  return smallest;
}

TetReport check_tets(const TetMesh& mesh, const SurfaceCheckOptions& boundary_options) {
  TetReport report;
  report.vertices = mesh.positions.size();
  report.tets = mesh.tets.size();
  // Fixed grain and a deterministic reduction order keep the sums identical run to run.
  const Tally total = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, mesh.tets.size(), 4096), Tally{},
      [&](const tbb::blocked_range<std::size_t>& r, Tally acc) {
        acc.add(tally_range(mesh, r.begin(), r.end()));
        return acc;
      },
      [](Tally x, const Tally& y) {
        x.add(y);
        return x;
      });
  report.inverted_tets = total.inverted;
  report.degenerate_tets = total.degenerate;
  report.volume = total.volume;
  if (report.tets > 0) {
    report.min_dihedral_deg = total.min_dihedral;
    report.avg_min_dihedral_deg = total.sum_min_dihedral / double(report.tets);
    report.max_amips = total.max_amips;
    report.avg_amips = total.sum_amips / double(report.tets);
  }
  report.boundary = check_surface(extract_boundary(mesh), boundary_options);
  return report;
}

}  // namespace mr::check
