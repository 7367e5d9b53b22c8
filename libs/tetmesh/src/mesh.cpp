#include <mr/tetmesh/mesh.h>

#include <mr/core/errors.h>
#include <mr/kernel/rounding.h>

#include <tbb/parallel_sort.h>

#include <algorithm>
#include <string>

namespace mr::tetmesh {

// A free face, keyed by its sorted corners, waiting for its twin.
struct Mesh::FaceSlot {
  std::array<Index, 3> key;
  Index tet;
  int face;
  bool operator<(const FaceSlot& other) const {
    if (key != other.key) return key < other.key;
    return tet != other.tet ? tet < other.tet : face < other.face;
  }
};

namespace {

std::array<Index, 3> sorted_key(std::array<Index, 3> corners) {
  std::sort(corners.begin(), corners.end());
  return corners;
}

}  // namespace

void Mesh::reserve(std::size_t vertices, std::size_t tets) {
  positions_.reserve(vertices);
  flags_.reserve(vertices);
  vertex_alive_.reserve(vertices);
  tets_.reserve(tets);
}

Index Mesh::add_vertex(const HybridPoint& position, std::uint8_t flags) {
  if (!free_vertices_.empty()) {
    const Index v = free_vertices_.back();
    free_vertices_.pop_back();
    positions_[v] = position;
    flags_[v] = flags;
    vertex_alive_[v] = 1;
    return v;
  }
  positions_.push_back(position);
  flags_.push_back(flags);
  vertex_alive_.push_back(1);
  return static_cast<Index>(positions_.size() - 1);
}

void Mesh::remove_vertex(Index v) {
  if (!vertex_alive(v)) throw UsageError("remove_vertex: vertex " + std::to_string(v) + " is not live");
  vertex_alive_[v] = 0;
  positions_[v] = HybridPoint();
  flags_[v] = 0;
  free_vertices_.push_back(v);
}

Index Mesh::add_tet(const Tet& corners) {
  for (int i = 0; i < 4; ++i) {
    if (!vertex_alive(corners[i])) {
      throw UsageError("add_tet: corner " + std::to_string(corners[i]) + " is not a live vertex");
    }
    for (int j = 0; j < i; ++j) {
      if (corners[i] == corners[j]) throw UsageError("add_tet: repeated corner");
    }
  }
  TetRecord record;
  record.corners = corners;
  record.alive = true;
  if (!free_tets_.empty()) {
    const Index t = free_tets_.back();
    free_tets_.pop_back();
    tets_[t] = record;
    return t;
  }
  tets_.push_back(record);
  return static_cast<Index>(tets_.size() - 1);
}

void Mesh::remove_tet(Index t) {
  if (!tet_alive(t)) throw UsageError("remove_tet: tet " + std::to_string(t) + " is not live");
  for (int f = 0; f < 4; ++f) {
    if (tets_[t].neighbours[f] != kNoTet) detach(t, f);
  }
  tets_[t] = TetRecord();
  free_tets_.push_back(t);
}

std::array<Index, 3> Mesh::face_vertices(Index t, int face) const {
  return opposite_face(tets_[t].corners, face);
}

int Mesh::corner_of(Index t, Index v) const {
  for (int k = 0; k < 4; ++k) {
    if (tets_[t].corners[k] == v) return k;
  }
  return -1;
}

int Mesh::face_towards(Index t, Index u) const {
  for (int k = 0; k < 4; ++k) {
    if (tets_[t].neighbours[k] == u) return k;
  }
  return -1;
}

void Mesh::glue(Index t, int ft, Index u, int fu) {
  tets_[t].neighbours[ft] = u;
  tets_[u].neighbours[fu] = t;
}

void Mesh::detach(Index t, int f) {
  const Index u = tets_[t].neighbours[f];
  if (u == kNoTet) return;
  const int fu = face_towards(u, t);
  if (fu >= 0) tets_[u].neighbours[fu] = kNoTet;
  tets_[t].neighbours[f] = kNoTet;
}

void Mesh::link_matching_faces(std::vector<FaceSlot>& faces) {
  tbb::parallel_sort(faces.begin(), faces.end());
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t end = i + 1;
    while (end < faces.size() && faces[end].key == faces[i].key) ++end;
    if (end - i > 2) {
      throw UsageError("tet mesh: a face (vertices " + std::to_string(faces[i].key[0]) + ", " +
                       std::to_string(faces[i].key[1]) + ", " + std::to_string(faces[i].key[2]) +
                       ") is shared by more than two tets");
    }
    if (end - i == 2) {
      const FaceSlot& a = faces[i];
      const FaceSlot& b = faces[i + 1];
      glue(a.tet, a.face, b.tet, b.face);
      std::uint32_t& ma = tets_[a.tet].marks[a.face];
      std::uint32_t& mb = tets_[b.tet].marks[b.face];
      if (ma == kNoMark) ma = mb;
      if (mb == kNoMark) mb = ma;
    }
    i = end;
  }
}

void Mesh::connect(std::span<const Index> tets) {
  std::vector<FaceSlot> faces;
  faces.reserve(tets.size() * 4);
  for (const Index t : tets) {
    if (!tet_alive(t)) throw UsageError("connect: tet " + std::to_string(t) + " is not live");
    for (int f = 0; f < 4; ++f) {
      if (tets_[t].neighbours[f] == kNoTet) faces.push_back({sorted_key(face_vertices(t, f)), t, f});
    }
  }
  // A tet listed twice would offer each free face twice.
  std::sort(faces.begin(), faces.end());
  faces.erase(
      std::unique(faces.begin(), faces.end(),
                  [](const FaceSlot& a, const FaceSlot& b) { return a.tet == b.tet && a.face == b.face; }),
      faces.end());
  link_matching_faces(faces);
}

void Mesh::rebuild_adjacency() {
  std::vector<FaceSlot> faces;
  faces.reserve(num_tets() * 4);
  for (Index t = 0; t < tets_.size(); ++t) {
    if (!tets_[t].alive) continue;
    tets_[t].neighbours = {kNoTet, kNoTet, kNoTet, kNoTet};
    for (int f = 0; f < 4; ++f) faces.push_back({sorted_key(face_vertices(t, f)), t, f});
  }
  link_matching_faces(faces);
}

std::span<const std::uint32_t> Mesh::surface_ids(Index t, int face) const {
  const std::uint32_t handle = tets_[t].marks[face];
  if (handle == kNoMark) return {};
  return mark_sets_[handle - 1];
}

std::uint32_t Mesh::intern(std::vector<std::uint32_t> ids) {
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  if (ids.empty()) return kNoMark;
  if (ids.size() == 1) {
    const std::uint32_t id = ids[0];
    if (id >= singleton_handles_.size()) singleton_handles_.resize(std::size_t(id) + 1, kNoMark);
    if (singleton_handles_[id] == kNoMark) {
      mark_sets_.push_back(std::move(ids));
      singleton_handles_[id] = static_cast<std::uint32_t>(mark_sets_.size());
    }
    return singleton_handles_[id];
  }
  const auto found = multi_handles_.find(ids);
  if (found != multi_handles_.end()) return found->second;
  mark_sets_.push_back(ids);
  const auto handle = static_cast<std::uint32_t>(mark_sets_.size());
  multi_handles_.emplace(std::move(ids), handle);
  return handle;
}

void Mesh::set_surface_ids(Index t, int face, std::span<const std::uint32_t> ids) {
  const std::uint32_t handle = intern(std::vector<std::uint32_t>(ids.begin(), ids.end()));
  set_mark_one_side(t, face, handle);
  const Index u = tets_[t].neighbours[face];
  if (u != kNoTet) {
    const int fu = face_towards(u, t);
    if (fu >= 0) set_mark_one_side(u, fu, handle);
  }
  if (handle == kNoMark) return;
  for (const Index v : face_vertices(t, face)) add_flags(v, kOnSurface);
}

Compaction Mesh::compact() {
  Compaction maps;
  maps.vertex_map.assign(positions_.size(), kNoVertex);
  maps.tet_map.assign(tets_.size(), kNoTet);
  Index next = 0;
  for (Index v = 0; v < positions_.size(); ++v) {
    if (!vertex_alive_[v]) continue;
    maps.vertex_map[v] = next;
    positions_[next] = std::move(positions_[v]);
    flags_[next] = flags_[v];
    ++next;
  }
  positions_.resize(next);
  flags_.resize(next);
  vertex_alive_.assign(next, 1);
  free_vertices_.clear();

  next = 0;
  for (Index t = 0; t < tets_.size(); ++t) {
    if (tets_[t].alive) maps.tet_map[t] = next++;
  }
  for (Index t = 0; t < tets_.size(); ++t) {
    if (!tets_[t].alive) continue;
    TetRecord record = tets_[t];
    for (int k = 0; k < 4; ++k) {
      record.corners[k] = maps.vertex_map[record.corners[k]];
      if (record.neighbours[k] != kNoTet) record.neighbours[k] = maps.tet_map[record.neighbours[k]];
    }
    tets_[maps.tet_map[t]] = record;
  }
  tets_.resize(next);
  free_tets_.clear();
  return maps;
}

}  // namespace mr::tetmesh
