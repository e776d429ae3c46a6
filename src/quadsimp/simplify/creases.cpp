// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Creases kept (ours; SimplifyOptions::creases): which vertices lie on them, how they
// slide along them, and how a crease loses vertices as the quads around it grow.
#include "quadsimp/simplify/simplifier.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "quadsimp/ops/doublet.h"
#include "quadsimp/ops/doublet_collapse.h"
#include "quadsimp/ops/local_rewrite.h"

namespace qs::detail {
namespace {

// A crease vertex is taken out when its two crease edges add up to less than this many
// mu: border coarsening's measure (border.cpp), for the same reason. Without it a crease
// keeps its input's vertices, and the quads along it theirs. Where the crease runs on
// straight (turning by under kStraight), it loses no shape with fewer vertices, and 1.6
// there gave 81.1% regular vertices instead of 78.0% over five CAD parts at four counts
// (bench/creases.py's, 200 to 1,000 quads), RMS distance from 5% lower to 15% higher on
// the three with curved creases (1.6 everywhere: 81.7%, but 15 to 43% higher).
constexpr double kCreaseShort = 1.3, kStraightCreaseShort = 1.6;
const double kStraight = std::cos(5 * M_PI / 180);

}  // namespace

// The mesh's vertices are M0's own at the start, or midpoints of its edges (the
// conversion's splits): each lies on M0's corners and crease edges exactly, up to rounding.
// A converted mesh's vertices are M0's under the same ids, which tells apart the copies of
// a vertex that cleaning split (a non-manifold vertex: one copy per fan, all at one place,
// and the closest point may lie on another copy's triangles); others are found by place.
void Simplifier::mark_creases() {
  const Creases* creases = opt_.creases;
  if (!creases || creases->empty()) return;
  crease_.assign(m_.vertex_capacity(), kNone);
  crease_s_.assign(m_.vertex_capacity(), 0.0);
  on_crease_.assign(m_.vertex_capacity(), 0);
  const double tolerance = 1e-7 * ref_.bbox_diagonal();
  for (Index v = 0; v < m_.vertex_capacity(); ++v) {
    if (!m_.is_vertex_live(v)) continue;
    Creases::Place place;
    if (v < ref_.mesh().n_vertices() && ref_.mesh().positions[v] == m_.position(v)) {
      place = creases->place_of_vertex(v);
    } else {
      const SurfacePoint s = ref_.closest_within(m_.position(v), 0.0);
      if (!s.found()) continue;
      place = creases->place_of(ref_.mesh(), s.face, m_.position(v), tolerance);
      // Curves end at M0's border: a border vertex found inside one is another copy's.
      if (m_.is_border_vertex(v) && place.curve != kNone) continue;
    }
    if (place.corner) {
      held_[v] |= kHeldCorner;
      on_crease_[v] = 1;
    } else if (place.curve != kNone) {
      crease_[v] = place.curve, crease_s_[v] = place.s, on_crease_[v] = 1;
      crease_verts_.push_back(v);
    }
  }
}

void Simplifier::inherit(Index survivor, Index from) {
  if (crease_.empty() || survivor == from) return;
  crease_[survivor] = crease_[from];
  crease_s_[survivor] = crease_s_[from];
  on_crease_[survivor] = on_crease_[from];
  note_crease(survivor);
}

// Whether merging `gone` into pinned `keep` would join keep by an edge to a pinned vertex
// it has no edge to: a crease vertex to another curve, or to its own curve by a shortcut.
// Edges between two pinned vertices are then the creases' own, which rotations and
// smoothing rely on (crease_arc()), and no quad spans a crease from one side to the other.
bool Simplifier::joins_pinned(Index keep, Index gone) const {
  if (crease_.empty() || !pinned(keep)) return false;
  bool joins = false;
  m_.for_each_outgoing(gone, [&](Index h) {
    const Index n = m_.to(h);
    if (joins || n == keep || !pinned(n)) return;
    bool adjacent = false;
    m_.for_each_outgoing(keep, [&](Index e) { adjacent = adjacent || m_.to(e) == n; });
    if (m_.is_border_vertex(keep)) adjacent = adjacent || m_.prev_on_border(keep) == n;
    joins = !adjacent;
  });
  return joins;
}

bool Simplifier::creates_pinned_edge(Index h, Rotation r) const {
  if (crease_.empty()) return false;
  const auto [a, b] = rotated_edge(m_, h, r);
  return pinned(a) && pinned(b);
}

// A corner's sides each take one face where its creases meet at it (a box's corner: three
// creases, three faces); where one crease ends or runs on round a turn, four.
int Simplifier::target_valence_of_corner(Index v) const {
  int creases = 0;
  m_.for_each_outgoing(v, [&](Index h) { creases += pinned(m_.to(h)); });
  return creases >= 3 ? creases : creases == 2 ? 3 : 4;
}

void Simplifier::crease_arc(Index v, double& back, double& ahead) const {
  const Creases& creases = *opt_.creases;
  const Index c = crease_[v];
  const double s = crease_s_[v], span = creases.span(c);
  if (creases.closed(c)) {
    back = ahead = 0.5 * span;
  } else {
    back = s, ahead = span - s;  // the corners at its ends
  }
  m_.for_each_outgoing(v, [&](Index h) {
    const Index n = m_.to(h);
    if (crease_[n] != c) return;
    const double d = creases.ahead_of(c, s, crease_s_[n]);
    if (creases.closed(c)) {
      ahead = std::min(ahead, d), back = std::min(back, span - d);
    } else if (d > 0) {
      ahead = std::min(ahead, d);
    } else {
      back = std::min(back, -d);
    }
  });
}

// A crease vertex's spring step, taken along its curve: to the curve's point nearest the
// springs' target between its neighbours on the curve, or half or a quarter of the way,
// the first the checks allow (as smooth_vertex() does off creases).
void Simplifier::slide_on_crease(Index v, const Vec3& target) {
  const Creases& creases = *opt_.creases;
  const Index c = crease_[v];
  double back, ahead;
  crease_arc(v, back, ahead);
  const Creases::CurvePoint to = creases.closest(ref_.mesh(), c, target, crease_s_[v], back, ahead);
  if (!to.foot.found() || (to.foot.point - m_.position(v)).squaredNorm() < 1e-4 * mu_at(v) * mu_at(v)) return;
  double d = creases.ahead_of(c, crease_s_[v], to.s);
  if (creases.closed(c) && d > 0.5 * creases.span(c)) d -= creases.span(c);
  for (double scale : {1.0, 0.5, 0.25}) {
    const Creases::CurvePoint x = scale == 1.0 ? to : creases.at(ref_.mesh(), c, crease_s_[v] + scale * d);
    if (!moved_faces_ok(v, x.foot.point)) continue;
    m_.position(v) = x.foot.point;
    crease_s_[v] = x.s;
    record_foot(v, x.foot);
    return;
  }
}

// Crease coarsening, as border coarsening (border.cpp) does on the border: a crease vertex
// whose crease edges are short next to mu, or that is left with one face on either side
// (a doublet) by the collapses beside it, is taken out with two segments of its crease
// (collapse_doublet()), once the edges across the crease at it are rotated away. Returns
// whether any was.
bool Simplifier::coarsen_creases() {
  std::size_t kept = 0;
  for (Index v : crease_verts_)
    if (m_.is_vertex_live(v) && crease_[v] != kNone) crease_verts_[kept++] = v;
  crease_verts_.resize(kept);
  std::sort(crease_verts_.begin(), crease_verts_.end());
  crease_verts_.erase(std::unique(crease_verts_.begin(), crease_verts_.end()), crease_verts_.end());
  crease_scan_ = crease_verts_;  // removals add survivors to crease_verts_
  bool any = false;
  for (Index b : crease_scan_)
    if (m_.is_vertex_live(b) && crease_[b] != kNone && piece_room(b) > 0) any |= remove_crease_vertex(b);
  return any;
}

bool Simplifier::remove_crease_vertex(Index b) {
  if (is_doublet(m_, b)) return remove_crease_doublet(b) || absorb_far_corners(b);
  if (m_.valence(b) > 4) return false;
  Vec3 along[2];
  int n = 0;
  m_.for_each_outgoing(b, [&](Index h) {
    if (pinned(m_.to(h)) && n++ < 2) along[n - 1] = m_.position(m_.to(h)) - m_.position(b);
  });
  if (n != 2) return false;
  const double length = along[0].norm() + along[1].norm();
  const bool straight = -along[0].dot(along[1]) > kStraight * along[0].norm() * along[1].norm();
  if (length >= (straight ? kStraightCreaseShort : kCreaseShort) * mu_at(b)) return false;
  // Each edge across the crease at b rotates away from it, until b has one face on
  // either side; every rotation is undone, the last first, unless the collapse follows.
  std::array<RotationUndo, 2> undo;
  int done = 0;
  while (m_.valence(b) > 2) {
    Index h = kNone;
    m_.for_each_outgoing(b, [&](Index e) {
      if (h == kNone && !pinned(m_.to(e))) h = e;
    });
    if (h == kNone || m_.twin(h) == kNone || done == 2) break;
    undo[done] = rotation_undo(m_, h);
    bool rotated = false;
    // The faces at b are not checked: they go with the collapse, which checks the rest.
    for (Rotation r : {Rotation::Ccw, Rotation::Cw}) {
      if (!rotation_passes_cap(h, r) || !can_rotate_edge(m_, h, r, b) || creates_pinned_edge(h, r) ||
          rotation_folds(m_, h, r, b, refuse_folds_) || !rotation_follows_reference(h, r, b))
        continue;
      rotate_edge(m_, h, r, b);
      rotated = true;
      ++done;
      break;
    }
    if (!rotated) break;
  }
  if (is_doublet(m_, b) && remove_crease_doublet(b)) return true;
  while (done > 0) undo_rotation(m_, undo[--done]);
  return false;
}

bool Simplifier::remove_crease_doublet(Index b) {
  if (!can_collapse_doublet(m_, b)) return false;
  const DoubletCorners c = doublet_corners(m_, b);
  // p and r are b's neighbours along its curve, or corners at its ends; not both corners.
  for (Index x : {c.p, c.r})
    if (!(held_[x] & kHeldCorner) && crease_[x] != crease_[b]) return false;
  if ((held_[c.p] & held_[c.r] & kHeldCorner) != 0) return false;
  if (opt_.max_valence > 0 && m_.valence(c.p) + m_.valence(c.r) - 4 > opt_.max_valence) {
    ++rep_.refused_valence;
    return false;
  }
  // The merged vertex takes a corner's place, or b's on the curve.
  const Index keep = (held_[c.p] & kHeldCorner) ? c.p : (held_[c.r] & kHeldCorner) ? c.r : b;
  const SurfacePoint foot = keep == b ? opt_.creases->at(ref_.mesh(), crease_[b], crease_s_[b]).foot
                                      : ref_.closest_within(m_.position(keep), 0.0);
  const Vec3 pos = m_.position(keep);
  bool ok = foot.found();
  const Index f1 = QuadMesh::face(m_.out(b)), f2 = QuadMesh::face(m_.rotate(m_.out(b)));
  for (Index x : {c.p, c.r})
    m_.for_each_outgoing(x, [&](Index h) {
      const Index g = QuadMesh::face(h);
      if (!ok || g == f1 || g == f2) return;
      Vec3 q[4];
      for (Index i = 0; i < 4; ++i) {
        const Index v = m_.vertex(g, i);
        q[i] = v == c.p || v == c.r ? pos : m_.position(v);
      }
      ok = shape_ok(g, q, ref_.normal_at(foot));
    });
  if (!ok) {
    ++rep_.refused_geometry;
    return false;
  }
  const char held = held_[c.p] | held_[c.r];
  const Index v = collapse_doublet(m_, b, pos);
  held_[v] = held;
  inherit(v, keep);
  record_foot(v, foot);
  ++rep_.crease_collapses;
  after_change({v, c.x, c.y});
  return true;
}

// A crease doublet b that cannot go (its neighbours' faces would not take the merged
// vertex: near a corner, where they reach other curves) takes in the far corners of its
// faces instead, by diagonal collapses that keep it where it is: its straight angles go,
// and the crease keeps its vertices there. Returns whether the first did.
bool Simplifier::absorb_far_corners(Index b) {
  bool any = false;
  for (int i = 0; i < 2 && m_.is_vertex_live(b); ++i) {
    const Index h = m_.out(b), f = QuadMesh::face(h), k = QuadMesh::corner(h) & 1u;
    Vec3 pos;
    SurfacePoint foot;
    const Verdict v = check_collapse(f, k, pos, foot, Bound::Loop);
    if (v != Verdict::Ok) {
      count_refusal(v);
      break;
    }
    cycle(f, k, pos, foot);
    any = true;
    if (!m_.is_vertex_live(b)) break;  // the cleaning after it took b
    if (!is_doublet(m_, b)) {
      // The other face, still straight at b, is the one whose far corner b takes next.
      Index straight = kNone;
      m_.for_each_outgoing(b, [&](Index e) {
        if (straight == kNone && pinned(m_.to(e)) && pinned(m_.from(QuadMesh::prev(e)))) straight = e;
      });
      if (straight == kNone) break;
      const Index g = QuadMesh::face(straight), j = QuadMesh::corner(straight) & 1u;
      const Verdict w = check_collapse(g, j, pos, foot, Bound::Loop);
      if (w == Verdict::Ok) cycle(g, j, pos, foot);
      else count_refusal(w);
      break;
    }
  }
  return any;
}

// Where a chord merges l and r, both on one curve: the curve's point nearest their
// midpoint, between them. False when they lie on different curves.
bool Simplifier::place_between_on_crease(Index l, Index r, const Vec3& mid, SurfacePoint& foot, double& s) const {
  const Creases& creases = *opt_.creases;
  const Index c = crease_[l];
  if (c == kNone || crease_[r] != c) return false;
  double d = creases.ahead_of(c, crease_s_[l], crease_s_[r]);
  if (creases.closed(c) && d > 0.5 * creases.span(c)) d -= creases.span(c);
  const Creases::CurvePoint x =
      creases.closest(ref_.mesh(), c, mid, crease_s_[l], std::max(-d, 0.0), std::max(d, 0.0));
  foot = x.foot;
  s = x.s;
  return foot.found();
}

// Every vertex on a curve lies at its parameter's point and has two faces at least
// (corners are held: nothing moves them).
void Simplifier::check_creases() const {
  const double tolerance = 1e-6 * ref_.bbox_diagonal();
  for (Index v = 0; v < m_.vertex_capacity(); ++v) {
    if (!m_.is_vertex_live(v) || crease_[v] == kNone) continue;
    const Vec3 at = opt_.creases->at(ref_.mesh(), crease_[v], crease_s_[v]).foot.point;
    if (!((at - m_.position(v)).norm() <= tolerance))
      throw std::logic_error("simplify: crease vertex " + std::to_string(v) + " is off its curve by " +
                             std::to_string((at - m_.position(v)).norm() / ref_.mean_edge_length()) +
                             " input edges");
    if (m_.valence(v) < 2) throw std::logic_error("simplify: crease vertex " + std::to_string(v) + " has one face");
  }
}

}  // namespace qs::detail
