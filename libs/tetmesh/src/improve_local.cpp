#include "improve_local.h"

#include <mr/check/tet_check.h>
#include <mr/core/errors.h>
#include <mr/tetmesh/incidence.h>
#include <mr/tetmesh/winding_filter.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

namespace mr::tetmesh::improve_detail {

FaceKey face_key(std::array<Index, 3> corners) {
  std::sort(corners.begin(), corners.end());
  return corners;
}

Workspace::Workspace(Mesh& mesh_, const envelope::Envelope* envelope_, double target_edge_length_,
                     double stop_energy_)
    : mesh(mesh_),
      envelope(envelope_),
      target_edge_length(target_edge_length_),
      stop_energy(stop_energy_),
      sizing(mesh_.vertex_slots(), 1.0) {
  reset_seeds();
}

void Workspace::reset_seeds() {
  seed_.assign(mesh.vertex_slots(), kNoTet);
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (!mesh.tet_alive(t)) continue;
    for (const Index v : mesh.tet(t)) {
      if (seed_[v] == kNoTet) seed_[v] = t;
    }
  }
}

Index Workspace::find_seed(Index v) {
  if (v < seed_.size()) {
    const Index t = seed_[v];
    if (t != kNoTet && mesh.tet_alive(t) && mesh.corner_of(t, v) >= 0) return t;
  }
  // Seeds are refreshed after every edit; this scan is a safety net.
  for (Index t = 0; t < mesh.tet_slots(); ++t) {
    if (mesh.tet_alive(t) && mesh.corner_of(t, v) >= 0) {
      if (v >= seed_.size()) seed_.resize(std::size_t(v) + 1, kNoTet);
      seed_[v] = t;
      return t;
    }
  }
  return kNoTet;
}

std::vector<Index> Workspace::star(Index v) {
  if (!mesh.vertex_alive(v)) return {};
  const Index seed = find_seed(v);
  if (seed == kNoTet) return {};
  return tets_around_vertex(mesh, v, seed);
}

std::optional<std::vector<Index>> Workspace::seeded_star(Index v) const {
  if (!mesh.vertex_alive(v)) return std::vector<Index>{};
  if (v >= seed_.size()) return std::nullopt;
  const Index t = seed_[v];
  if (t == kNoTet || !mesh.tet_alive(t) || mesh.corner_of(t, v) < 0) return std::nullopt;
  return tets_around_vertex(mesh, v, t);
}

std::vector<Index> Workspace::edge_tets(Index a, Index b, Index hint) {
  const auto has_edge = [&](Index t) {
    return t != kNoTet && mesh.tet_alive(t) && mesh.corner_of(t, a) >= 0 && mesh.corner_of(t, b) >= 0;
  };
  if (!has_edge(hint)) {
    if (!mesh.vertex_alive(a) || !mesh.vertex_alive(b)) return {};
    const Index seed = find_seed(a);
    if (seed == kNoTet) return {};
    hint = tet_with_edge(mesh, a, b, seed);
    if (hint == kNoTet) return {};
  }
  return tets_around_edge(mesh, a, b, hint);
}

// A field value far from the global target is clamped: the lattice and
// the envelope work at the global target's scale, and a field a thousand
// times finer would make a billion tets (use -l for a finer mesh overall).
constexpr double kFieldScaleRange = 100;

std::pair<double, Workspace::Sample> Workspace::sampled_scale(Index v) const {
  const double value = field_->at(mesh.position(v).approx) / target_edge_length;
  if (!(value > 0)) return {1.0, Sample::outside};  // NaN: the field says nothing here
  const double clamped = std::clamp(value, 1 / kFieldScaleRange, kFieldScaleRange);
  return {clamped, clamped == value ? Sample::inside : Sample::clamped};
}

Workspace::FieldSamples Workspace::use_sizing_field(const ScalarField* field) {
  field_ = field;
  field_scale.assign(mesh.vertex_slots(), 1.0);
  FieldSamples samples;
  if (field_ == nullptr) return samples;
  std::vector<Sample> kind(mesh.vertex_slots(), Sample::inside);
  tbb::parallel_for(tbb::blocked_range<Index>(0, Index(mesh.vertex_slots()), 256),
                    [&](const tbb::blocked_range<Index>& range) {
                      for (Index v = range.begin(); v != range.end(); ++v)
                        if (mesh.vertex_alive(v)) std::tie(field_scale[v], kind[v]) = sampled_scale(v);
                    });
  samples.outside = std::size_t(std::count(kind.begin(), kind.end(), Sample::outside));
  samples.clamped = std::size_t(std::count(kind.begin(), kind.end(), Sample::clamped));
  return samples;
}

double Workspace::scale(Index v) const {
  const double refined = v < sizing.size() ? sizing[v] : 1.0;
  const double field = v < field_scale.size() ? field_scale[v] : 1.0;
  return refined * field;
}

double Workspace::target(Index a, Index b) const { return target_edge_length * 0.5 * (scale(a) + scale(b)); }

void Workspace::note_tets(std::span<const Index> tets) {
  for (const Index t : tets) {
    for (const Index v : mesh.tet(t)) {
      if (v >= seed_.size()) seed_.resize(std::size_t(v) + 1, kNoTet);
      seed_[v] = t;
    }
  }
}

std::vector<Index> Workspace::counted(std::span<const Index> tets) const {
  std::vector<Index> out;
  out.reserve(tets.size());
  for (const Index t : tets) {
    if (counts(t)) out.push_back(t);
  }
  return out;
}

std::pair<bool, bool> Workspace::kept_side(Index t) const {
  if (t == kNoTet) return {false, false};
  const double w = payload.value[t];
  return {is_inside(w, WindingRule::absolute), is_inside(w, WindingRule::positive)};
}

bool Workspace::mixes_decisions(std::span<const Index> tets) const {
  if (payload.value.empty() || tets.empty()) return false;
  const std::pair<bool, bool> first = kept_side(tets.front());
  return std::any_of(tets.begin() + 1, tets.end(), [&](Index t) { return kept_side(t) != first; });
}

void Workspace::note_vertex(Index v, double size) {
  if (v >= sizing.size()) sizing.resize(std::size_t(v) + 1, 1.0);
  sizing[v] = size;
  if (field_ == nullptr) return;
  if (v >= field_scale.size()) field_scale.resize(std::size_t(v) + 1, 1.0);
  field_scale[v] = sampled_scale(v).first;
}

namespace {

const HybridPoint& corner(const Mesh& mesh, Index v, const Override& moved) {
  return v == moved.vertex ? *moved.at : mesh.position(v);
}

}  // namespace

bool all_positive(const Mesh& mesh, std::span<const Tet> tets, Override moved) {
  for (const Tet& t : tets) {
    if (orient3d(corner(mesh, t[0], moved), corner(mesh, t[1], moved), corner(mesh, t[2], moved),
                 corner(mesh, t[3], moved)) <= 0) {
      return false;
    }
  }
  return true;
}

double max_energy(const Mesh& mesh, std::span<const Tet> tets, Override moved) {
  double worst = 0;
  for (const Tet& t : tets) {
    const double e = check::amips_energy(corner(mesh, t[0], moved).approx, corner(mesh, t[1], moved).approx,
                                         corner(mesh, t[2], moved).approx, corner(mesh, t[3], moved).approx);
    worst = std::max(worst, std::isnan(e) ? std::numeric_limits<double>::infinity() : e);
  }
  return worst;
}

double tet_energy(const Mesh& mesh, Index t) {
  const Tet& c = mesh.tet(t);
  const double e = check::amips_energy(mesh.position(c[0]).approx, mesh.position(c[1]).approx,
                                       mesh.position(c[2]).approx, mesh.position(c[3]).approx);
  return std::isnan(e) ? std::numeric_limits<double>::infinity() : e;
}

double max_energy_of(const Mesh& mesh, std::span<const Index> tets) {
  double worst = 0;
  for (const Index t : tets) worst = std::max(worst, tet_energy(mesh, t));
  return worst;
}

bool faces_inside(const Workspace& ws, std::span<const FaceCorners> faces, Override moved) {
  if (faces.empty()) return true;
  if (ws.envelope == nullptr) return false;
  for (const FaceCorners& f : faces) {
    if (!ws.envelope->is_inside(corner(ws.mesh, f[0], moved).approx, corner(ws.mesh, f[1], moved).approx,
                                corner(ws.mesh, f[2], moved).approx)) {
      return false;
    }
  }
  return true;
}

std::vector<TrackedFace> tracked_faces(const Mesh& mesh, std::span<const Index> tets) {
  // Each face is seen from both its tets: keep the first sighting of each
  // key (sorted, then unique: a search per face was quadratic in big stars).
  std::vector<std::pair<FaceKey, std::pair<Index, int>>> seen;
  for (const Index t : tets) {
    for (int f = 0; f < 4; ++f) {
      if (mesh.is_surface_face(t, f)) seen.push_back({face_key(mesh.face_vertices(t, f)), {t, f}});
    }
  }
  std::stable_sort(seen.begin(), seen.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  seen.erase(
      std::unique(seen.begin(), seen.end(), [](const auto& a, const auto& b) { return a.first == b.first; }),
      seen.end());
  std::vector<TrackedFace> faces;
  faces.reserve(seen.size());
  for (const auto& [key, where] : seen) {
    const auto ids = mesh.surface_ids(where.first, where.second);
    faces.push_back({key, std::vector<std::uint32_t>(ids.begin(), ids.end())});
  }
  return faces;
}

std::vector<TrackedFace> tracked_faces_at(const Mesh& mesh, std::span<const Index> star, Index v) {
  std::vector<TrackedFace> faces = tracked_faces(mesh, star);
  std::erase_if(
      faces, [&](const TrackedFace& f) { return std::find(f.key.begin(), f.key.end(), v) == f.key.end(); });
  return faces;
}

namespace {

// The payload of each new tet, read before the old slots are freed.
TetPayload payload_of_new_tets(const Workspace& ws, std::span<const Index> old_tets, std::size_t new_tets,
                               std::span<const std::size_t> origin) {
  const TetPayload& old = ws.payload;
  TetPayload out;
  if (!old.fate.empty()) {
    if (origin.empty()) {
      char mildest = kDropped;
      for (const Index t : old_tets) mildest = std::min(mildest, old.fate[t]);
      out.fate.assign(new_tets, mildest);
    } else {
      for (std::size_t i = 0; i < new_tets; ++i) out.fate.push_back(old.fate[old_tets[origin[i]]]);
    }
  }
  if (!old.value.empty()) {
    for (std::size_t i = 0; i < new_tets; ++i)
      out.value.push_back(old.value[old_tets[origin.empty() ? 0 : origin[i]]]);
  }
  return out;
}

template <class T>
void store(std::vector<T>& per_slot, std::span<const Index> slots, const std::vector<T>& entries,
           std::size_t slot_count) {
  if (entries.empty()) return;
  per_slot.resize(slot_count, T{});
  for (std::size_t i = 0; i < slots.size(); ++i) per_slot[slots[i]] = entries[i];
}

}  // namespace

std::vector<Index> replace_tets(Workspace& ws, std::span<const Index> old_tets, std::span<const Tet> new_tets,
                                const ParentFaces& parents, std::span<const std::size_t> origin) {
  Mesh& mesh = ws.mesh;
  const TetPayload carried = payload_of_new_tets(ws, old_tets, new_tets.size(), origin);
  const std::vector<TrackedFace> old_faces = tracked_faces(mesh, old_tets);
  std::vector<Index> around;
  for (const Index t : old_tets) {
    for (int f = 0; f < 4; ++f) {
      const Index u = mesh.neighbour(t, f);
      if (u != kNoTet && std::find(old_tets.begin(), old_tets.end(), u) == old_tets.end()) {
        around.push_back(u);
      }
    }
  }
  for (const Index t : old_tets) mesh.remove_tet(t);
  std::vector<Index> added;
  added.reserve(new_tets.size());
  for (const Tet& t : new_tets) added.push_back(mesh.add_tet(t));
  store(ws.payload.fate, added, carried.fate, mesh.tet_slots());
  store(ws.payload.value, added, carried.value, mesh.tet_slots());

  std::vector<Index> linked = added;
  linked.insert(linked.end(), around.begin(), around.end());
  mesh.connect(linked);

  std::vector<FaceKey> sources;
  std::vector<std::uint32_t> ids;
  for (const Index t : added) {
    for (int f = 0; f < 4; ++f) {
      sources.clear();
      parents(face_key(mesh.face_vertices(t, f)), sources);
      ids.clear();
      for (const FaceKey& source : sources) {
        for (const TrackedFace& old : old_faces) {
          if (old.key == source) ids.insert(ids.end(), old.ids.begin(), old.ids.end());
        }
      }
      if (!ids.empty()) mesh.set_surface_ids(t, f, ids);
    }
  }
  ws.note_tets(around);
  ws.note_tets(added);
  return added;
}

bool edge_on_hull(const Mesh& mesh, std::span<const Index> tets, Index a, Index b) {
  for (const Index t : tets) {
    for (int f = 0; f < 4; ++f) {
      if (mesh.neighbour(t, f) != kNoTet) continue;
      const Index opposite = mesh.tet(t)[f];
      if (opposite != a && opposite != b && mesh.corner_of(t, a) >= 0 && mesh.corner_of(t, b) >= 0) {
        return true;
      }
    }
  }
  return false;
}

bool vertex_on_hull(const Mesh& mesh, std::span<const Index> tets, Index v) {
  for (const Index t : tets) {
    for (int f = 0; f < 4; ++f) {
      if (mesh.neighbour(t, f) == kNoTet && mesh.tet(t)[f] != v && mesh.corner_of(t, v) >= 0) return true;
    }
  }
  return false;
}

}  // namespace mr::tetmesh::improve_detail
