// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/mesh/quad_mesh.h"

#include <algorithm>
#include <iterator>
#include <numeric>
#include <set>
#include <string>
#include <utility>

#include "quadsimp/util/errors.h"

namespace qs {
namespace {

std::uint64_t edge_key(Index a, Index b) { return (std::uint64_t(a) << 32) | b; }

// Count of half-edges leaving each vertex; the fan walk must reach all of them,
// otherwise the vertex joins two or more fans (a non-manifold vertex).
std::vector<Index> outgoing_counts(const QuadMesh& m) {
  std::vector<Index> count(m.vertex_capacity(), 0);
  for (Index f = 0; f < m.face_capacity(); ++f)
    if (m.is_face_live(f))
      for (Index k = 0; k < 4; ++k) ++count[m.vertex(f, k)];
  return count;
}

Index fan_size(const QuadMesh& m, Index v, Index limit) {
  Index n = 0;
  const Index start = m.out(v);
  Index h = start;
  do {
    if (++n > limit) break;
    h = m.rotate(h);
  } while (h != kNone && h != start);
  return n;
}

}  // namespace

QuadMesh QuadMesh::from_faces(std::vector<Vec3> positions,
                              const std::vector<std::array<Index, 4>>& quads) {
  QuadMesh m;
  m.pos_ = std::move(positions);
  const Index nv = Index(m.pos_.size());
  m.out_.assign(nv, kNone);
  m.origin_.reserve(4 * quads.size());
  for (std::size_t f = 0; f < quads.size(); ++f) {
    const auto& q = quads[f];
    for (int k = 0; k < 4; ++k) {
      if (q[k] >= nv)
        throw InvalidInput("face " + std::to_string(f) + " refers to vertex " +
                           std::to_string(q[k]) + " but there are only " + std::to_string(nv));
      for (int j = 0; j < k; ++j)
        if (q[j] == q[k])
          throw InvalidInput("quad " + std::to_string(f) + " repeats vertex " + std::to_string(q[k]));
    }
    for (int k = 0; k < 4; ++k) m.origin_.push_back(q[k]);
  }
  m.twin_.assign(m.origin_.size(), kNone);
  m.n_live_faces_ = Index(quads.size());

  // Half-edges grouped by origin and sorted by end: a half-edge's twin is found by a
  // binary search among those leaving its end. A hash map of every half-edge took 1.05 s
  // of the conversion of a 1.1M-triangle scan (555,610 quads); this takes 0.12-0.16 s.
  const Index nh = Index(m.origin_.size());
  std::vector<Index> first(nv + 1, 0);
  for (Index h = 0; h < nh; ++h) ++first[m.from(h) + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<std::pair<Index, Index>> leaving(nh);  // (end, half-edge), by origin
  std::vector<Index> fill(first.begin(), first.end() - 1);
  for (Index h = 0; h < nh; ++h) leaving[fill[m.from(h)]++] = {m.to(h), h};
  for (Index v = 0; v < nv; ++v) std::sort(leaving.begin() + first[v], leaving.begin() + first[v + 1]);
  const auto between = [&](Index a, Index b) {
    return std::equal_range(leaving.begin() + first[a], leaving.begin() + first[a + 1], std::pair<Index, Index>(b, 0),
                            [](const auto& x, const auto& y) { return x.first < y.first; });
  };
  for (Index h = 0; h < nh; ++h) {
    const auto same = between(m.from(h), m.to(h));
    if (same.second - same.first > 1)
      throw InvalidInput("edge " + std::to_string(m.from(h)) + "-" + std::to_string(m.to(h)) +
                         " is shared by more than two faces or by faces of opposite orientation");
  }
  for (Index h = 0; h < nh; ++h) {
    const auto back = between(m.to(h), m.from(h));
    if (back.first != back.second) m.twin_[h] = back.first->second;
  }
  for (Index h = 0; h < m.origin_.size(); ++h) {
    const Index v = m.from(h);
    if (m.out_[v] == kNone || m.twin_[h] == kNone) m.out_[v] = h;
  }
  m.face_count_ = outgoing_counts(m);
  const std::vector<Index>& count = m.face_count_;
  for (Index v = 0; v < nv; ++v) {
    if (m.out_[v] == kNone) continue;
    ++m.n_live_vertices_;
    if (fan_size(m, v, count[v]) != count[v])
      throw InvalidInput("vertex " + std::to_string(v) +
                         " is non-manifold (its faces form more than one fan)");
  }
  return m;
}

Vec3 QuadMesh::face_area_normal(Index f) const {
  const auto q = face_vertices(f);
  return (pos_[q[2]] - pos_[q[0]]).cross(pos_[q[3]] - pos_[q[1]]);
}

Vec3 QuadMesh::vertex_area_normal(Index v) const {
  Vec3 n = Vec3::Zero();
  for_each_outgoing(v, [&](Index h) { n += face_area_normal(face(h)); });
  return n;
}

Vec3 QuadMesh::face_centroid(Index f) const {
  const auto q = face_vertices(f);
  return 0.25 * (pos_[q[0]] + pos_[q[1]] + pos_[q[2]] + pos_[q[3]]);
}

Index QuadMesh::add_vertex(const Vec3& p) {
  pos_.push_back(p);
  out_.push_back(kNone);
  face_count_.push_back(0);
  return Index(pos_.size() - 1);
}

Index QuadMesh::add_face(const std::array<Index, 4>& v) {
  const Index f = face_capacity();
  for (Index k = 0; k < 4; ++k) {
    origin_.push_back(v[k]);
    twin_.push_back(kNone);
    ++face_count_[v[k]];
    if (out_[v[k]] == kNone) {
      out_[v[k]] = 4 * f + k;
      ++n_live_vertices_;
    }
  }
  ++n_live_faces_;
  return f;
}

void QuadMesh::kill_face(Index f) {
  if (!is_face_live(f)) return;
  for (Index k = 0; k < 4; ++k) {
    const Index h = 4 * f + k;
    if (twin_[h] != kNone && twin_[twin_[h]] == h) twin_[twin_[h]] = kNone;
    twin_[h] = kNone;
    --face_count_[origin_[h]];
    origin_[h] = kNone;
  }
  --n_live_faces_;
}

void QuadMesh::kill_vertex(Index v) {
  if (out_[v] == kNone) return;
  out_[v] = kNone;
  --n_live_vertices_;
}

void QuadMesh::repair_out(Index v) {
  // Walk backwards from the current out-edge to the start of the fan: that is
  // the border out-edge if v is on the border.
  Index h = out_[v];
  if (h == kNone || origin_[h] != v) return;
  const Index start = h;
  for (;;) {
    const Index t = twin_[h];
    if (t == kNone) break;
    const Index back = next(t);
    if (back == start) break;
    h = back;
  }
  out_[v] = h;
}

std::vector<Index> QuadMesh::live_vertex_ids() const {
  std::vector<Index> id(pos_.size(), kNone);
  Index n = 0;
  for (Index v = 0; v < pos_.size(); ++v)
    if (out_[v] != kNone) id[v] = n++;
  return id;
}

void QuadMesh::compact(std::vector<Index>* vertex_map, std::vector<Index>* face_map) {
  std::vector<Index> vmap = live_vertex_ids(), fmap(face_capacity(), kNone);
  const Index nv = Index(std::count_if(vmap.begin(), vmap.end(), [](Index x) { return x != kNone; }));
  Index nf = 0;
  for (Index f = 0; f < face_capacity(); ++f)
    if (is_face_live(f)) fmap[f] = nf++;

  std::vector<Vec3> pos(nv);
  std::vector<Index> out(nv), face_count(nv);
  for (Index v = 0; v < pos_.size(); ++v) {
    if (vmap[v] == kNone) continue;
    pos[vmap[v]] = pos_[v];
    face_count[vmap[v]] = face_count_[v];
    out[vmap[v]] = 4 * fmap[face(out_[v])] + corner(out_[v]);
  }
  std::vector<Index> origin(4 * std::size_t(nf)), twin(4 * std::size_t(nf));
  for (Index f = 0; f < face_capacity(); ++f) {
    if (fmap[f] == kNone) continue;
    for (Index k = 0; k < 4; ++k) {
      const Index h = 4 * f + k, nh = 4 * fmap[f] + k;
      origin[nh] = vmap[origin_[h]];
      twin[nh] = twin_[h] == kNone ? kNone : 4 * fmap[face(twin_[h])] + corner(twin_[h]);
    }
  }
  pos_ = std::move(pos);
  out_ = std::move(out);
  face_count_ = std::move(face_count);
  origin_ = std::move(origin);
  twin_ = std::move(twin);
  n_live_vertices_ = nv;
  n_live_faces_ = nf;
  if (vertex_map) *vertex_map = std::move(vmap);
  if (face_map) *face_map = std::move(fmap);
}

std::vector<std::array<Index, 4>> QuadMesh::quads() const {
  std::vector<std::array<Index, 4>> q;
  q.reserve(n_live_faces_);
  for (Index f = 0; f < face_capacity(); ++f)
    if (is_face_live(f)) q.push_back(face_vertices(f));
  return q;
}

void validate(const QuadMesh& m) {
  auto fail = [](const std::string& what) { throw TopologyError("validate: " + what); };
  Index live_faces = 0, live_vertices = 0;
  std::vector<std::uint64_t> edges;
  edges.reserve(m.halfedge_capacity());
  for (Index f = 0; f < m.face_capacity(); ++f) {
    if (!m.is_face_live(f)) continue;
    ++live_faces;
    const auto q = m.face_vertices(f);
    for (Index k = 0; k < 4; ++k) {
      if (q[k] >= m.vertex_capacity() || !m.is_vertex_live(q[k]))
        fail("face " + std::to_string(f) + " uses a dead or invalid vertex");
      for (Index j = 0; j < k; ++j)
        if (q[j] == q[k]) fail("face " + std::to_string(f) + " repeats vertex " + std::to_string(q[k]));
      const Index h = QuadMesh::halfedge(f, k), t = m.twin(h);
      edges.push_back(edge_key(m.from(h), m.to(h)));
      if (t == kNone) continue;
      if (t >= m.halfedge_capacity() || !m.is_face_live(QuadMesh::face(t)))
        fail("half-edge " + std::to_string(h) + " has a dead twin");
      if (QuadMesh::face(t) == f) fail("face " + std::to_string(f) + " is its own neighbour");
      if (m.twin(t) != h) fail("twin of twin of half-edge " + std::to_string(h) + " is not itself");
      if (m.from(t) != m.to(h) || m.to(t) != m.from(h))
        fail("half-edge " + std::to_string(h) + " and its twin are not reversed (orientation)");
    }
  }
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end())
    fail("a directed edge appears twice (non-manifold or doubled edge)");
  if (live_faces != m.n_faces()) fail("live face count is stale");

  const std::vector<Index> count = outgoing_counts(m);
  for (Index v = 0; v < m.vertex_capacity(); ++v) {
    if (!m.is_vertex_live(v)) continue;
    ++live_vertices;
    const Index h = m.out(v);
    if (h >= m.halfedge_capacity() || !m.is_face_live(QuadMesh::face(h)) || m.from(h) != v)
      fail("vertex " + std::to_string(v) + " has an invalid out half-edge");
    if (fan_size(m, v, count[v]) != count[v])
      fail("vertex " + std::to_string(v) + " is not a single fan (non-manifold or bad border out-edge)");
    if (m.valence(v) != int(count[v]) + (m.is_border_vertex(v) ? 1 : 0))
      fail("vertex " + std::to_string(v) + " has a stale cached face count");
  }
  if (live_vertices != m.n_vertices()) fail("live vertex count is stale");
  // A live vertex without faces fails above: its out half-edge is in no live face.
}

bool share_a_face(const QuadMesh& m, Index p, Index q, Index skip_a, Index skip_b) {
  bool shared = false;
  m.for_each_outgoing(p, [&](Index h) {
    const Index f = QuadMesh::face(h);
    if (f == skip_a || f == skip_b) return;
    for (Index k = 0; k < 4; ++k) shared |= m.vertex(f, k) == q;
  });
  return shared;
}

Index two_quad_piece_partner(const QuadMesh& m, Index f) {
  const Index t0 = m.twin(QuadMesh::halfedge(f, 0));
  if (t0 == kNone) return kNone;
  for (Index k = 1; k < 4; ++k) {
    const Index t = m.twin(QuadMesh::halfedge(f, k));
    if (t == kNone || QuadMesh::face(t) != QuadMesh::face(t0)) return kNone;
  }
  return QuadMesh::face(t0);
}

std::vector<std::pair<Index, Index>> shared_diagonals(const QuadMesh& m) {
  std::vector<std::pair<Index, Index>> shared;
  for (Index f = 0; f < m.face_capacity(); ++f)
    if (m.is_face_live(f) && two_quad_piece_partner(m, f) == kNone)
      for (Index k = 0; k < 2; ++k)
        if (share_a_face(m, m.vertex(f, k), m.vertex(f, k + 2), f))
          shared.push_back(std::minmax(m.vertex(f, k), m.vertex(f, k + 2)));
  std::sort(shared.begin(), shared.end());
  shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
  return shared;
}

std::pair<Index, Index> new_shared_diagonal(const QuadMesh& m, const std::vector<std::pair<Index, Index>>& before,
                                            const std::vector<std::pair<Index, Index>>& now) {
  std::vector<std::pair<Index, Index>> added, gone;
  std::set_difference(now.begin(), now.end(), before.begin(), before.end(), std::back_inserter(added));
  std::set_difference(before.begin(), before.end(), now.begin(), now.end(), std::back_inserter(gone));
  auto same = [&](Index was, Index is) { return was == is || !m.is_vertex_live(was); };
  for (const auto& [p, q] : added) {
    const auto renamed = std::find_if(gone.begin(), gone.end(), [&, p = p, q = q](const auto& g) {
      return (same(g.first, p) && same(g.second, q)) || (same(g.first, q) && same(g.second, p));
    });
    if (renamed == gone.end()) return {p, q};
    gone.erase(renamed);
  }
  return {kNone, kNone};
}

std::vector<std::uint8_t> split_diagonals(const QuadMesh& m) {
  auto joined_by_edge = [&](Index p, Index q) {
    bool edge = false;
    m.for_each_outgoing(p, [&](Index h) { edge |= m.to(h) == q || m.from(QuadMesh::prev(h)) == q; });
    return edge;
  };
  std::vector<std::uint8_t> split(m.face_capacity(), 0);
  std::set<std::pair<Index, Index>> taken;  // splits whose corners share another face
  for (Index f = 0; f < m.face_capacity(); ++f) {
    if (!m.is_face_live(f)) continue;
    bool bad[2], shared[2];
    double length[2];
    std::pair<Index, Index> pair[2];
    for (Index k = 0; k < 2; ++k) {
      const Index p = m.vertex(f, k), q = m.vertex(f, k + 2);
      pair[k] = std::minmax(p, q);
      shared[k] = share_a_face(m, p, q, f);
      bad[k] = shared[k] && (joined_by_edge(p, q) || taken.count(pair[k]));
      length[k] = (m.position(p) - m.position(q)).squaredNorm();
    }
    const Index k = bad[0] != bad[1] ? bad[0] : shared[0] != shared[1] ? shared[0] : length[0] > length[1];
    split[f] = std::uint8_t(k);
    if (shared[k]) taken.insert(pair[k]);
  }
  return split;
}

Index connected_components(const QuadMesh& m, std::vector<Index>& component) {
  component.assign(m.vertex_capacity(), kNone);
  std::vector<Index> stack;
  Index n = 0;
  for (Index seed = 0; seed < m.vertex_capacity(); ++seed) {
    if (!m.is_vertex_live(seed) || component[seed] != kNone) continue;
    component[seed] = n;
    stack.assign(1, seed);
    while (!stack.empty()) {
      const Index v = stack.back();
      stack.pop_back();
      m.for_each_outgoing(v, [&](Index h) {
        for (Index k = 0; k < 4; ++k) {
          const Index w = m.vertex(QuadMesh::face(h), k);
          if (component[w] == kNone) component[w] = n, stack.push_back(w);
        }
      });
    }
    ++n;
  }
  return n;
}

}  // namespace qs
