// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Poly-chord collapses (ours; SimplifyOptions::chord_collapses).
#include "quadsimp/simplify/simplifier.h"

#include <algorithm>
#include <vector>

namespace qs::detail {

// Poly-chord collapses (ours; SimplifyOptions::chord_collapses), once no diagonal
// collapse is left above the target: every chord of at most kChordFaces faces, shortest
// crossed edges (against their rest length) first. A chord is taken while that brings
// the face count closer to the target, and not if an earlier one of the same batch
// changed it; then the loop goes back to diagonal collapses. One chord per batch gave
// the same results on the odd inputs, but each batch walks the whole mesh: a ribbon of
// 5,000 quads to 50 took 2.9 s instead of 0.06 s. Without the marks (every allowed
// chord of the list, neighbours too) an annulus at 10 quads ended with RMS 11.8e-3
// instead of 3.1e-3.
bool Simplifier::collapse_chords() {
  constexpr Index kChordFaces = 64;
  const Index target = opt_.target_faces;
  struct Candidate {
    double key;
    Index h;
  };
  std::vector<Candidate> candidates;
  std::vector<char> seen(2 * std::size_t(m_.face_capacity()), 0);  // per face and parity of the crossed edges
  for (Index f = 0; f < m_.face_capacity(); ++f)
    for (Index k = 0; k < 2 && m_.is_face_live(f); ++k) {
      if (seen[2 * f + k]) continue;
      seen[2 * f + k] = 1;
      if (!gather_chord(m_, QuadMesh::halfedge(f, k), chord_, kChordFaces)) continue;
      double key = 0;
      for (Index i = 0; i < chord_.pairs(); ++i) {
        const Index l = chord_.left[i], r = chord_.right[i];
        key += (m_.position(l) - m_.position(r)).norm() / rest_length(l, r);
      }
      for (std::size_t i = 0; i < chord_.faces.size(); ++i)
        seen[2 * chord_.faces[i] + (QuadMesh::corner(chord_.entries[i]) & 1u)] = 1;
      candidates.push_back({key / double(chord_.pairs()), chord_.entries[0]});
    }
  std::sort(candidates.begin(), candidates.end(),
            [](const Candidate& a, const Candidate& b) { return a.key != b.key ? a.key < b.key : a.h < b.h; });
  std::fill(seen.begin(), seen.end(), 0);  // now: faces changed by this batch
  Index done = 0;
  for (const Candidate& c : candidates) {
    if (m_.n_faces() <= target) break;
    if (!m_.is_face_live(QuadMesh::face(c.h)) || !gather_chord(m_, c.h, chord_, kChordFaces)) continue;
    if (2 * (m_.n_faces() - target) <= Index(chord_.faces.size())) continue;
    if (2 * piece_room(chord_.left[0]) <= double(chord_.faces.size())) continue;
    bool changed = false;
    for (Index f : chord_.faces) changed = changed || seen[f];
    if (changed || !try_collapse_chord(chord_)) continue;
    ++done;
    // after_change() left the smoothed zone in region_verts_: its faces have changed.
    for (Index v : region_verts_)
      if (m_.is_vertex_live(v)) m_.for_each_outgoing(v, [&](Index h) { seen[QuadMesh::face(h)] = 1; });
  }
  return done > 0;
}

bool Simplifier::try_collapse_chord(const Chord& chord) {
  if (!can_collapse_chord(m_, chord)) {
    ++rep_.refused_topology;
    return false;
  }
  const Index pairs = chord.pairs();
  for (Index i = 0; i < pairs; ++i) {
    const Index l = chord.left[i], r = chord.right[i];
    if (opt_.preserve_boundary && (m_.is_border_vertex(l) || m_.is_border_vertex(r))) {
      ++rep_.refused_topology;
      return false;
    }
    const bool open_end = !chord.closed && (i == 0 || i == pairs - 1);
    if (opt_.max_valence > 0 && m_.valence(l) + m_.valence(r) - (open_end ? 3 : 4) > opt_.max_valence) {
      ++rep_.refused_valence;
      return false;
    }
  }
  // Each merged vertex: a border end keeps its place; two border ends (an open end of
  // the chord) meet at a border corner if either is one, else at the point of M0's
  // border closest to their midpoint, walked from one to the other (a walk from the
  // face nearest the midpoint may start on the other border of a part one triangle
  // wide: on a ribbon every chord was refused); otherwise the midpoint projected onto M0.
  chord_pos_.resize(pairs);
  chord_feet_.resize(pairs);
  chord_crease_s_.assign(crease_.empty() ? 0 : pairs, -1.0);
  for (Index i = 0; i < pairs; ++i) {
    const Index l = chord.left[i], r = chord.right[i];
    const bool bl = m_.is_border_vertex(l), br = m_.is_border_vertex(r);
    const Vec3 mid = 0.5 * (m_.position(l) + m_.position(r));
    SurfacePoint foot;
    Index tip;
    if (!crease_.empty() && crease_[l] != kNone && crease_[l] == crease_[r]) {
      // A crease edge crossed: its ends meet on the curve (the left one takes the place).
      if (!place_between_on_crease(l, r, mid, foot, chord_crease_s_[i])) {
        ++rep_.refused_geometry;
        return false;
      }
      chord_pos_[i] = foot.point;
      chord_feet_[i] = foot;
      continue;
    }
    if (!merge_keeps_tip(l, r, tip) || (tip != kNone && joins_pinned(tip, tip == l ? r : l))) {
      ++rep_.refused_topology;
      return false;
    }
    if (tip != kNone) {  // a tip's vertex stays on it, as in a diagonal collapse
      foot = ref_.closest_within(m_.position(tip), 0.0);
    } else if (bl != br) {
      foot = ref_.closest_within(m_.position(bl ? l : r), 0.0);
    } else if (bl) {
      Index corner;
      if (!border_merge_corner(l, r, corner)) {
        ++rep_.refused_topology;
        return false;
      }
      foot = corner != kNone ? ref_.closest_within(m_.position(corner), 0.0) : border_point_between(l, r, mid);
    } else {
      foot = ref_.project_near(foot_face_[l], mid, m_.vertex_area_normal(l) + m_.vertex_area_normal(r),
                               2 * (m_.position(l) - m_.position(r)).norm());
    }
    if (!foot.found()) {
      ++rep_.refused_geometry;
      return false;
    }
    chord_pos_[i] = foot.point;
    chord_feet_[i] = foot;
  }
  faces_beside_chord(m_, chord, beside_);
  for (Index g : beside_) {
    Vec3 q[4];
    for (Index k = 0; k < 4; ++k) {
      const Index v = m_.vertex(g, k);
      const int pair = chord_pair_of(chord, v);
      q[k] = pair >= 0 ? chord_pos_[pair] : m_.position(v);
    }
    if (!shape_ok(g, q, Vec3::Zero())) {
      ++rep_.refused_geometry;
      return false;
    }
    if (const Verdict v = opt_.adaptive ? check_grown_face(g, q, Bound::Loop) : Verdict::Ok; v != Verdict::Ok) {
      count_refusal(v);  // the enlarged faces, as for a diagonal collapse
      return false;
    }
  }
  collapse_chord(m_, chord, chord_pos_);
  for (Index i = 0; i < pairs; ++i) {
    record_foot(chord.left[i], chord_feet_[i]);
    if (!crease_.empty() && chord_crease_s_[i] >= 0) crease_s_[chord.left[i]] = chord_crease_s_[i];
    if (!crease_.empty() && pinned(chord.right[i]) && !pinned(chord.left[i])) inherit(chord.left[i], chord.right[i]);
    held_[chord.left[i]] |= held_[chord.right[i]];
  }
  ++rep_.chord_collapses;
  after_change(chord.left.data(), chord.left.data() + chord.left.size());
  return true;
}

}  // namespace qs::detail
