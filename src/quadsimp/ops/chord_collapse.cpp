// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/ops/chord_collapse.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <utility>

namespace qs {

bool gather_chord(const QuadMesh& m, Index h, Chord& chord, Index max_faces) {
  chord.faces.clear(), chord.entries.clear(), chord.left.clear(), chord.right.clear();
  chord.closed = false;
  if (!m.is_face_live(QuadMesh::face(h))) return false;
  // Back to the start: the walk is a permutation of half-edges, so it either comes
  // back to h or stops on the border.
  Index s = h;
  for (Index steps = 0; m.twin(s) != kNone; ++steps) {
    s = QuadMesh::opposite_in_face(m.twin(s));
    if (s == h) {
      chord.closed = true;
      break;
    }
    if (steps >= max_faces) return false;
  }
  for (Index g = s;;) {
    if (chord.faces.size() >= max_faces) return false;
    chord.faces.push_back(QuadMesh::face(g));
    chord.entries.push_back(g);
    chord.left.push_back(m.from(g));
    chord.right.push_back(m.to(g));
    const Index o = QuadMesh::opposite_in_face(g), t = m.twin(o);
    if (t == kNone) {  // the open end: o runs right -> left
      chord.left.push_back(m.to(o));
      chord.right.push_back(m.from(o));
      return true;
    }
    if (t == s) return true;
    g = t;
  }
}

int chord_pair_of(const Chord& chord, Index v) {
  for (std::size_t i = 0; i < chord.left.size(); ++i)
    if (chord.left[i] == v || chord.right[i] == v) return int(i);
  return -1;
}

void faces_beside_chord(const QuadMesh& m, const Chord& chord, std::vector<Index>& faces) {
  faces.clear();
  for (const auto* side : {&chord.left, &chord.right})
    for (Index v : *side) m.for_each_outgoing(v, [&](Index h) { faces.push_back(QuadMesh::face(h)); });
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  faces.erase(std::remove_if(
                  faces.begin(), faces.end(),
                  [&](Index f) { return std::find(chord.faces.begin(), chord.faces.end(), f) != chord.faces.end(); }),
              faces.end());
}

namespace {

bool has_duplicates(std::vector<Index> v) {
  std::sort(v.begin(), v.end());
  return std::adjacent_find(v.begin(), v.end()) != v.end();
}

// Whether corners i and j of a quad are joined by one of its edges.
bool quad_edge(int i, int j) {
  return (i - j + 4) % 4 == 1 || (j - i + 4) % 4 == 1;
}

}  // namespace

bool can_collapse_chord(const QuadMesh& m, const Chord& chord) {
  const Index n = Index(chord.faces.size()), p = chord.pairs();
  if (n == 0) return false;
  // Each vertex in one pair at most, which also refuses a chord that meets a face twice
  // (it meets the face's corners twice).
  std::vector<Index> ends = chord.left;
  ends.insert(ends.end(), chord.right.begin(), chord.right.end());
  if (has_duplicates(ends)) return false;
  for (Index i = 0; i < p; ++i) {
    const bool open_end = !chord.closed && (i == 0 || i == p - 1);
    if (!open_end && m.is_border_vertex(chord.left[i]) && m.is_border_vertex(chord.right[i])) return false;
  }
  // The faces beside the chord with their corners merged: every edge and corner the
  // collapse changes belongs to one of them.
  std::vector<Index> beside;
  faces_beside_chord(m, chord, beside);
  std::vector<std::array<Index, 4>> after(beside.size());
  std::vector<char> kept(p, 0);
  std::vector<std::pair<Index, Index>> directed;
  for (std::size_t f = 0; f < beside.size(); ++f) {
    for (Index k = 0; k < 4; ++k) {
      const Index v = m.vertex(beside[f], k);
      const int pair = chord_pair_of(chord, v);
      if (pair >= 0) kept[pair] = 1;
      after[f][k] = pair >= 0 ? chord.left[pair] : v;
    }
    const auto& c = after[f];
    if (c[0] == c[1] || c[0] == c[2] || c[0] == c[3] || c[1] == c[2] || c[1] == c[3] || c[2] == c[3]) return false;
    for (Index k = 0; k < 4; ++k) directed.emplace_back(c[k], c[(k + 1) % 4]);
  }
  if (std::find(kept.begin(), kept.end(), 0) != kept.end()) return false;
  std::sort(directed.begin(), directed.end());
  if (std::adjacent_find(directed.begin(), directed.end()) != directed.end()) return false;
  // Two faces may share one edge, or one corner, and nothing else.
  for (std::size_t a = 0; a < after.size(); ++a)
    for (std::size_t b = a + 1; b < after.size(); ++b) {
      int shared = 0, ia[2] = {0, 0}, ib[2] = {0, 0};
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          if (after[a][i] == after[b][j]) {
            if (shared < 2) ia[shared] = i, ib[shared] = j;
            ++shared;
          }
      if (shared > 2 || (shared == 2 && !(quad_edge(ia[0], ia[1]) && quad_edge(ib[0], ib[1])))) return false;
    }
  return true;
}

void collapse_chord(QuadMesh& m, const Chord& chord, const std::vector<Vec3>& positions) {
  assert(can_collapse_chord(m, chord));
  std::vector<Index> beside;
  faces_beside_chord(m, chord, beside);
  // Each chord face's two side edges become one edge between the faces beyond them.
  std::vector<std::pair<Index, Index>> sides;
  for (Index e : chord.entries) sides.emplace_back(m.twin(QuadMesh::prev(e)), m.twin(QuadMesh::next(e)));
  for (Index f : chord.faces) m.kill_face(f);
  for (const auto& [l, r] : sides) {
    if (l != kNone)
      m.set_twin(l, r);
    else if (r != kNone)
      m.set_twin(r, kNone);
  }
  for (Index f : beside)
    for (Index k = 0; k < 4; ++k) {
      const Index h = QuadMesh::halfedge(f, k);
      const int pair = chord_pair_of(chord, m.from(h));
      if (pair < 0) continue;
      m.set_origin(h, chord.left[pair]);
      m.set_out(chord.left[pair], h);
    }
  for (Index i = 0; i < chord.pairs(); ++i) {
    m.kill_vertex(chord.right[i]);
    m.repair_out(chord.left[i]);
    m.position(chord.left[i]) = positions[i];
  }
}

}  // namespace qs
