// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#include "quadsimp/mesh/mend_folds.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <utility>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "quadsimp/mesh/tri_topology.h"

namespace qs::detail {
namespace {

// Whether the corner opposite edge k stands over the edge's inner four fifths: a thin
// triangle with its apex there is a cap, one with its apex near an end a needle (two
// corners almost together), whose flip only makes another needle.
bool apex_over_middle(const TriMesh& m, const std::array<Index, 3>& t, Index k) {
  const Vec3 &a = m.positions[t[k]], &b = m.positions[t[(k + 1) % 3]], &c = m.positions[t[(k + 2) % 3]];
  const double s = (c - a).dot(b - a) / (b - a).squaredNorm();
  return s > 0.1 && s < 0.9;
}

// Two kinds of triangle are mended by flipping one of their edges, the standard repairs
// (Botsch and Kobbelt 2001 for caps; MeshLab's "Remove Isolated Folded Faces by Edge
// Flip" for folds). No vertex moves, and the pair covers the same ground as before up to
// the cap's height or the fold's depth.
// - A cap: its apex lies almost on its longest edge (thinner than kCapThinness). A wall
//   no working mesh resolves, yet its normal is its own: glmark2's bunny has four, two
//   where it closes a hole along its base, standing at 64 degrees to it. Split finely,
//   a cap's inner vertices have only cap faces; the conversion paired them into quads
//   with no area, whose orientation every later move was checked against, and on one
//   machine a quad there kept an edge of 0.03 mu. Its longest edge is flipped when the
//   thinner of the two new triangles is less thin than before. Needles (the apex near
//   an end of that edge) are left: their flip is another needle. The datasets have no
//   cap (their thinnest triangle: 3.9e-3).
// - A fold: a single triangle turned back against all three neighbours by over 120
//   degrees (kFoldedBackCos; a Z-fold of a scan: glmark2's bunny has 2, bunny.ply 1, the armadillo 17,
//   16 of them mended). The edge flipped is one whose far neighbour lies under the
//   fold's apex. Over a fold the working mesh kept a flipped quad on that machine.
// Either flip is made only when both new triangles face like the neighbour they replace.
// Rounds of independent flips, so that a row of caps is taken from its ends inwards.
constexpr double kCapThinness = 1e-3;

// The edge of face t (of `m`) joining u and w.
Index edge_joining(const std::array<Index, 3>& t, Index u, Index w) {
  Index k = 0;
  while (k < 3 && !((t[k] == u && t[(k + 1) % 3] == w) || (t[k] == w && t[(k + 1) % 3] == u))) ++k;
  return k;
}

// One entry of the adjacency: adj[face][slot] = value.
struct AdjacencyWrite {
  Index face, slot, value;
};

// What the flip of edge k of f that mend_by_edge_flips() makes writes into `adj`, read
// before m.faces changes: f = (a, b, c) and g = (b, a, o) become (c, a, o) and (c, o, b).
// Only f, g and their neighbours across a-o and b-c change; the mesh is manifold here,
// so that is the adjacency built anew.
void flip_adjacency(const std::vector<std::array<Index, 3>>& adj, const TriMesh& m, Index f, Index k, Index o,
                    std::vector<AdjacencyWrite>& writes) {
  const auto& t = m.faces[f];
  const Index a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3], g = adj[f][k];
  const Index ca = adj[f][(k + 2) % 3], bc = adj[f][(k + 1) % 3];
  const Index ao = adj[g][edge_joining(m.faces[g], a, o)], ob = adj[g][edge_joining(m.faces[g], o, b)];
  // f's edges c-a, a-o, o-c; g's c-o, o-b, b-c.
  writes.insert(writes.end(), {{f, 0, ca}, {f, 1, ao}, {f, 2, g}, {g, 0, f}, {g, 1, ob}, {g, 2, bc}});
  if (ao != kNone) writes.push_back({ao, edge_joining(m.faces[ao], a, o), f});
  if (bc != kNone) writes.push_back({bc, edge_joining(m.faces[bc], b, c), g});
}

}  // namespace

Index mend_by_edge_flips(TriMesh& m, std::vector<std::array<Index, 3>>& adj, std::vector<Vec3>& normals) {
  // The longest edge of a cap, kNone for any other triangle.
  const auto cap_edge = [&](Index f, double& thin) {
    Index longest = 0;
    thin = thinness(m, m.faces[f], longest);
    return thin < kCapThinness && apex_over_middle(m, m.faces[f], longest) ? longest : kNone;
  };
  const auto folded = [&](Index f) {
    for (Index g : adj[f])
      if (g == kNone || normals[f].dot(normals[g]) >= kFoldedBackCos) return false;
    return true;
  };
  std::vector<Index> todo;  // most meshes have neither: nothing more is built for them
  double thin = 0;
  for (Index f = 0; f < m.n_faces(); ++f)
    if (cap_edge(f, thin) != kNone || folded(f)) todo.push_back(f);
  Index flips = 0;
  // The round's flips change `adj` when the round ends: the tests of later faces in the
  // round read it as the round found it. Building it anew after each round took a third
  // of the conversion of a bunny split into 1.1 million triangles (2.3 s, now 1.5 s).
  std::vector<AdjacencyWrite> writes;
  // The corners at each vertex, built for the first flip tried, and the faces each vertex
  // has joined through flips since: rebuilding them each round was a tenth of converting
  // the bunny split into 4.5 million triangles.
  CornersAround around;
  std::unordered_multimap<Index, Index> joined;
  const auto share_a_face_now = [&](Index u, Index w) {
    const auto both = [&](Index face) {
      const auto& t = m.faces[face];
      return (t[0] == u || t[1] == u || t[2] == u) && (t[0] == w || t[1] == w || t[2] == w);
    };
    for (Index i = around.start[u]; i < around.start[u + 1]; ++i)
      if (both(around.corner[i] / 3)) return true;
    const auto [first, last] = joined.equal_range(u);
    return std::any_of(first, last, [&](const auto& vf) { return both(vf.second); });
  };
  for (int round = 0; !todo.empty() && round < 64; ++round) {
    // Flips edge k of f (corners k, k+1) if `better` accepts the new pair; f = (a, b, c)
    // and g = (b, a, o) become (c, a, o) and (c, o, b), oriented alike.
    std::vector<char> touched(m.n_vertices(), 0);
    const auto try_flip = [&](Index f, Index k, auto&& better) {
      const Index g = adj[f][k];
      if (g == kNone) return false;
      const auto& t = m.faces[f];
      const auto& tg = m.faces[g];
      const Index a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      const Index o = tg[0] != a && tg[0] != b ? tg[0] : tg[1] != a && tg[1] != b ? tg[1] : tg[2];
      if (o == c || touched[a] || touched[b] || touched[c] || touched[o]) return false;
      if (around.start.empty()) around = corners_around(m);
      if (share_a_face_now(c, o)) return false;  // c-o an edge already
      const std::array<Index, 3> f2{c, a, o}, g2{c, o, b};
      const Vec3 ng = m.area_normal(tg);
      if (m.area_normal(f2).dot(ng) <= 0 || m.area_normal(g2).dot(ng) <= 0 || !better(f2, g2, tg)) return false;
      flip_adjacency(adj, m, f, k, o, writes);
      m.faces[f] = f2;
      m.faces[g] = g2;
      normals[f] = m.area_normal(f2).normalized();
      normals[g] = m.area_normal(g2).normalized();
      touched[a] = touched[b] = touched[c] = touched[o] = 1;
      joined.emplace(c, g);
      joined.emplace(o, f);
      ++flips;
      return true;
    };
    std::vector<Index> left;
    const Index flips_before = flips;
    for (Index f : todo) {
      if (const Index k = cap_edge(f, thin); k != kNone) {
        left.push_back(f);
        try_flip(f, k, [&](const auto& f2, const auto& g2, const auto& tg) {
          Index unused;
          return std::min(thinness(m, f2, unused), thinness(m, g2, unused)) > std::min(thin, thinness(m, tg, unused));
        });
      } else if (folded(f)) {
        left.push_back(f);
        for (Index k = 0; k < 3; ++k)
          if (try_flip(f, k, [](const auto&...) { return true; })) break;
      }
    }
    if (flips == flips_before) break;
    for (const AdjacencyWrite& w : writes) adj[w.face][w.slot] = w.value;
    writes.clear();
    todo.swap(left);
  }
  return flips;
}

namespace {

// Gauss-Seidel's sweeps grow with the square of a patch's width: a noisy scan's rings of
// 100 to 400 vertices took 100 to 450 sweeps each, and bunny.ply with noise of 0.2% of its
// diagonal spent 5 of the 5.8 s it took to convert there. From this many vertices the
// embedding is solved directly; below, sweeps are cheaper than a factorisation (the
// datasets' patches have at most 13 vertices, and keep their positions to the bit).
constexpr std::size_t kSolveDirectlyFrom = 32;

// Puts each vertex of `vs` at the mean of the other corners of its triangles, all at
// once: a sparse symmetric system (each pair of corners counted as often as they share a
// triangle), the vertices outside `vs` fixed. False, with nothing moved, where that has no
// sound solution: a part of `vs` that reaches no fixed vertex makes the system singular
// (its unknowns came out at the origin), and a harmonic map lies within the box of the
// fixed vertices, so a solution outside it is rounding gone wrong.
// `row` maps vertices to unknowns: kNone everywhere on entry, and again on return.
bool solve_neighbour_means(TriMesh& m, const CornersAround& around, const std::vector<Index>& vs,
                           std::vector<Index>& row) {
  auto& P = m.positions;
  const Index n = Index(vs.size());
  for (Index i = 0; i < n; ++i) row[vs[i]] = i;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d fixed = Eigen::MatrixX3d::Zero(n, 3);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  std::vector<Index> reached;  // unknowns with a fixed neighbour, then those connected to them
  for (Index i = 0; i < n; ++i) {
    const Index v = vs[i];
    entries.emplace_back(i, i, 2.0 * (around.start[v + 1] - around.start[v]));
    for (Index c = around.start[v]; c < around.start[v + 1]; ++c) {
      const auto& t = m.faces[around.corner[c] / 3];
      const Index k = around.corner[c] % 3;
      for (const Index u : {t[(k + 1) % 3], t[(k + 2) % 3]}) {
        if (row[u] != kNone) {
          entries.emplace_back(i, row[u], -1.0);
          continue;
        }
        fixed.row(i) += P[u].transpose();
        lo = lo.cwiseMin(P[u]), hi = hi.cwiseMax(P[u]);
        if (reached.empty() || reached.back() != i) reached.push_back(i);
      }
    }
  }
  for (Index v : vs) row[v] = kNone;
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  std::vector<char> linked(n, 0);
  for (Index i : reached) linked[i] = 1;
  for (std::size_t q = 0; q < reached.size(); ++q)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, reached[q]); it; ++it)
      if (!linked[it.row()]) linked[it.row()] = 1, reached.push_back(Index(it.row()));
  if (reached.size() < n) return false;
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
  if (solver.info() != Eigen::Success) return false;
  const Eigen::MatrixX3d x = solver.solve(fixed);
  const Vec3 slack = 1e-6 * (hi - lo).cwiseMax(0.0).norm() * Vec3::Ones();
  for (Index i = 0; i < n; ++i) {
    const Vec3 p = x.row(i).transpose();
    if (!p.allFinite() || (p.array() < (lo - slack).array()).any() || (p.array() > (hi + slack).array()).any())
      return false;
  }
  for (Index i = 0; i < n; ++i) P[vs[i]] = x.row(i).transpose();
  return true;
}

// Moves each vertex of `vs` to the mean of the other corners of its triangles, sweep
// after sweep (Gauss-Seidel), until no vertex moves by more than `settled` (or 1,000
// sweeps); from kSolveDirectlyFrom vertices, solved directly where that is sound.
// `row`: as solve_neighbour_means() takes it.
void move_to_neighbour_means(TriMesh& m, const CornersAround& around, const std::vector<Index>& vs, double settled,
                             std::vector<Index>& row) {
  if (vs.size() >= kSolveDirectlyFrom && solve_neighbour_means(m, around, vs, row)) return;
  auto& P = m.positions;
  for (int sweep = 0; sweep < 1000; ++sweep) {
    double largest = 0;
    for (Index v : vs) {
      Vec3 sum = Vec3::Zero();
      for (Index i = around.start[v]; i < around.start[v + 1]; ++i) {
        const auto& t = m.faces[around.corner[i] / 3];
        const Index k = around.corner[i] % 3;
        sum += P[t[(k + 1) % 3]] + P[t[(k + 2) % 3]];
      }
      const Vec3 mean = sum / double(2 * (around.start[v + 1] - around.start[v]));
      largest = std::max(largest, (mean - P[v]).squaredNorm());
      P[v] = mean;
    }
    if (largest <= settled * settled) return;
  }
}

// A patch of several triangles folded back (glmark2's bunny's fold split in four twice is
// 16) has no one edge to flip. Its vertices move instead, each to the mean of the other
// corners of its triangles, in sweeps until they settle: a Tutte embedding of the patch
// inside the ring of vertices that stay, which lays it flat between them. Kept only if
// every triangle around a moved vertex then faces like the unmoved triangles there did
// (their summed normal) and none turns back against a neighbour. Else the vertices around
// the ones moved join them, ring by ring, while their region faces the way the patch's
// own surroundings do: a Tutte embedding lies flat inside a convex ring, and the ring of
// a sliver is long and thin (the armadillo split in four twice has 23 folded patches; 12
// lay flat inside their own ring, the others inside 1 to 6 more). A patch whose rings met
// another patch's vertices gets a second try at the end, and one still folded a last try
// that need only leave its region with fewer defects than it had. If none lays it flat,
// the patch stays as it was, for ReferenceSurface to mark. Border vertices stay. A quad mesh cannot
// follow a Z-fold, and the simplifier's care over a marked one (over_flap()) is not
// enough everywhere: on glmark2's bunny split before cleaning it left a flipped quad and
// homeometry down to 0.18 at 20,000 quads, on the armadillo split twice two flipped quads
// and 0.07.
constexpr int kUnfoldRings = 8;
// Rings are added while fewer vertices than this move: a large patch that will not lie
// flat costs sweeps over all of it for each ring (the unit tests' thin leaf on a stalk,
// 2,000 vertices: 0.1 s to put back, 0.9 s with eight rings).
constexpr std::size_t kUnfoldMostVertices = 1024;

// Folded patches that face the same way and share a vertex that may move are laid flat as
// one: one at a time, each held the vertices it shared with the other still, and neither
// lay flat (two slivers side by side on a grid split twice). Patches facing opposite ways
// stay apart: a post's overhanging wall and its head are both patches, and laid flat as
// one they flattened the post. Renumbers `patch` in the order of the patches' first
// triangles and returns the count.
Index join_patches_sharing_a_vertex(const TriMesh& m, const std::vector<char>& border, Index patches,
                                    std::vector<Index>& patch) {
  std::vector<Vec3> facing(patches, Vec3::Zero());
  for (Index f = 0; f < m.n_faces(); ++f)
    if (patch[f] != kNone) facing[patch[f]] += m.area_normal(m.faces[f]);
  std::vector<std::array<Index, 2>> at;  // (vertex, patch) for every corner that may move
  for (Index f = 0; f < m.n_faces(); ++f)
    if (patch[f] != kNone)
      for (Index v : m.faces[f])
        if (!border[v]) at.push_back({v, patch[f]});
  std::sort(at.begin(), at.end());
  at.erase(std::unique(at.begin(), at.end()), at.end());
  UnionFind sets(patches);
  for (std::size_t i = 0; i < at.size(); ++i)  // every two patches at one vertex
    for (std::size_t j = i + 1; j < at.size() && at[j][0] == at[i][0]; ++j)
      if (facing[at[i][1]].dot(facing[at[j][1]]) > 0) sets.unite(at[i][1], at[j][1]);
  std::vector<Index> number(patches, kNone);
  Index n = 0;
  for (Index p = 0; p < patches; ++p)  // the lowest part of each set is its root, and comes first
    if (sets.find(p) == p) number[p] = n++;
  for (Index& p : patch)
    if (p != kNone) p = number[sets.find(p)];
  return n;
}

// Whether each patch is a disc of triangles, by its Euler characteristic (V - E + F = 1;
// discs joined at a vertex count too). A fold is one: the surface turns back over itself
// and forward again. The overhanging wall of a post is a band round the post (0), and laid
// flat it squashed the post: coarse posts of 16 to 64 sides, walls leaning out by 20 to 60
// degrees, lost their overhang, rim moved in.
std::vector<char> patches_that_are_discs(const TriMesh& m, const std::vector<Index>& patch, Index patches) {
  std::vector<int> euler(patches, 0);
  std::vector<std::array<Index, 2>> corners;
  std::vector<std::array<Index, 3>> edges;
  for (Index f = 0; f < m.n_faces(); ++f)
    if (const Index p = patch[f]; p != kNone) {
      ++euler[p];
      for (int k = 0; k < 3; ++k) {
        const Index a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
        corners.push_back({p, a});
        edges.push_back({p, std::min(a, b), std::max(a, b)});
      }
    }
  std::sort(corners.begin(), corners.end());
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < corners.size(); ++i)
    if (i == 0 || corners[i] != corners[i - 1]) ++euler[corners[i][0]];
  for (std::size_t i = 0; i < edges.size(); ++i)
    if (i == 0 || edges[i] != edges[i - 1]) --euler[edges[i][0]];
  std::vector<char> disc(patches);
  for (Index p = 0; p < patches; ++p) disc[p] = euler[p] == 1;
  return disc;
}

// Keeps `tried` only for the patches with a vertex within `near` of one of `points`.
// Cleaning moves no vertex before the patches are laid flat, but merges border vertices
// closer than 1e-6 of the diagonal into one of them: compared exactly, a point given at
// the copy merged away missed its patch.
void only_patches_at(const TriMesh& m, const std::vector<Index>& patch, const std::vector<Vec3>& points,
                     double near, std::vector<char>& tried) {
  std::vector<Vec3> sorted = points;
  std::sort(sorted.begin(), sorted.end(), [](const Vec3& a, const Vec3& b) { return a.x() < b.x(); });
  const auto is_near = [&](const Vec3& y) {
    auto i = std::lower_bound(sorted.begin(), sorted.end(), y.x() - near,
                              [](const Vec3& a, double x) { return a.x() < x; });
    for (; i != sorted.end() && i->x() <= y.x() + near; ++i)
      if ((*i - y).squaredNorm() <= near * near) return true;
    return false;
  };
  std::vector<char> at(tried.size(), 0);
  for (Index f = 0; f < m.n_faces(); ++f)
    if (const Index p = patch[f]; p != kNone && !at[p])
      for (Index v : m.faces[f]) at[p] = at[p] || is_near(m.positions[v]);
  for (std::size_t p = 0; p < tried.size(); ++p) tried[p] = tried[p] && at[p];
}

}  // namespace

void unfold_patches(TriMesh& m, const std::vector<std::array<Index, 3>>& adj, const std::vector<Vec3>& normals,
                    const CleanOptions& options, double diagonal, CleanReport& report) {
  if (options.folds_only_at && options.folds_only_at->empty()) return;  // asked for none
  const double max_move = options.longest_fold_move * diagonal;
  std::vector<Index> patch;
  // A sheet's two sides are about half of it each. 1e-4 missed five vertices of a
  // 128 x 128 grid pushed past their neighbours, 1e-3 a column of twelve pushed 3.5
  // cells on a 64 x 64 one (flipped quads followed); the datasets' patches are the same
  // at any share from 1e-4 to 1e-2. The side of a thin part with a sharp rim, a leaf on
  // a stalk, is a patch too, but laid flat it still faces against its surroundings, and
  // the check below puts it back.
  Index patches = folded_patches(m, adj, normals, patch, kLaidFlatShare, kLaidFlatCos);
  if (patches == 0) return;
  const CornersAround around = corners_around(m);
  std::vector<char> border(m.n_vertices(), 0);
  for (Index f = 0; f < m.n_faces(); ++f)
    for (Index k = 0; k < 3; ++k)
      if (adj[f][k] == kNone) border[m.faces[f][k]] = border[m.faces[f][(k + 1) % 3]] = 1;
  patches = join_patches_sharing_a_vertex(m, border, patches, patch);
  // held[v]: the patch whose vertices v is among, its own from the start, or one of its
  // rings while it tries and after it lay flat. A try's rings take vertices no patch holds.
  std::vector<std::vector<Index>> to_move(patches);
  std::vector<Index> held(m.n_vertices(), kNone);
  for (Index f = 0; f < m.n_faces(); ++f)
    if (patch[f] != kNone)
      for (Index v : m.faces[f])
        if (!border[v] && held[v] == kNone) held[v] = patch[f], to_move[patch[f]].push_back(v);

  auto& P = m.positions;
  std::vector<Index> seen(m.n_faces(), kNone), region, in_try(m.n_vertices(), kNone), newly_held;
  std::vector<Index> row(m.n_vertices(), kNone);  // move_to_neighbour_means()' unknowns
  // Per patch, the move of its first try that laid it flat but went past max_move, after
  // which it is not tried again: a coarse mesh's sharp tip, cut off, moved vertices by up
  // to 32% of the diagonal, and tried with more rings, it was still cut off, more gently
  // (bench/RESULTS.md).
  std::vector<double> too_far(patches, std::numeric_limits<double>::infinity());
  Index visit = 0, tries = 0;  // mark `seen` per region and `in_try` per try
  std::vector<Vec3> before;
  bool met = false;  // whether the last try's rings met vertices another patch holds
  // Whether triangle f faces against `facing`, plus its edges turning back by more than
  // kFoldedBackCos: 0 for a sound triangle.
  const auto defects_of = [&](Index f, const Vec3& facing) {
    const Vec3 n = m.area_normal(m.faces[f]);
    Index bad = !(n.dot(facing) > 0);
    for (Index g : adj[f])
      bad += g != kNone && n.normalized().dot(m.area_normal(m.faces[g]).normalized()) < kFoldedBackCos;
    return bad;
  };
  // Lays patch p flat, ring by ring. `strict`: only a region left with no defect counts;
  // else (a last pass) one left with fewer defects than it had, whose patch itself is flat.
  const auto lay_flat = [&](Index p, bool strict) {
    if (std::isfinite(too_far[p])) return false;
    std::vector<Index>& vs = to_move[p];
    const Index own = Index(vs.size()), try_id = tries++;
    for (Index v : vs) in_try[v] = try_id;
    newly_held.clear();
    met = false;
    // The way the triangles around the patch itself face (ring 0). The rings stop where
    // their region as a whole turns to face the other way: grown from a leaf's top down
    // its underside and a short stalk onto the disc below, the disc's triangles came to
    // outweigh the underside's, and the whole leaf and stalk laid flat on the disc passed
    // the checks. Stopping at the first triangle facing the other way kept the leaf too,
    // but laid 7 to 55% fewer of a noisy scan's folds flat (bunny.ply with noise added),
    // and checking every ring against ring 0's direction left one of the 23 folds of the
    // armadillo split twice, where the surface curves.
    Vec3 facing0 = Vec3::Zero();
    for (int ring = 0; ring <= kUnfoldRings && !vs.empty(); ++ring) {
      if (ring > 0) {  // the region's other vertices join the ones that move
        if (vs.size() >= kUnfoldMostVertices) break;
        for (Index f : region)
          for (Index v : m.faces[f]) {
            if (border[v] || in_try[v] == try_id) continue;
            if (held[v] != kNone) {
              met = true;
              continue;
            }
            if (held[v] == kNone) held[v] = p, newly_held.push_back(v);
            in_try[v] = try_id, vs.push_back(v);
          }
      }
      region.clear();
      ++visit;
      Vec3 facing = Vec3::Zero();
      double extent = 0;
      for (Index v : vs)
        for (Index i = around.start[v]; i < around.start[v + 1]; ++i) {
          const Index f = around.corner[i] / 3;
          if (seen[f] == visit) continue;
          seen[f] = visit;
          region.push_back(f);
          if (patch[f] == kNone) facing += m.area_normal(m.faces[f]);
          for (Index k = 0; k < 3; ++k) extent = std::max(extent, (P[m.faces[f][k]] - P[v]).norm());
        }
      if (facing == Vec3::Zero()) break;  // not isZero(): fuzzy by an absolute 1e-12
      if (ring == 0) facing0 = facing;
      else if (!(facing.dot(facing0) > 0)) break;
      before.clear();
      for (Index v : vs) before.push_back(P[v]);
      Index defects_before = 0;
      if (!strict)
        for (Index f : region) defects_before += defects_of(f, facing);
      move_to_neighbour_means(m, around, vs, 1e-9 * extent, row);
      // Strict: every triangle of the region sound. Last try: the patch's own, and fewer
      // defects in the region than before.
      bool flat = true;
      Index defects_after = 0;
      for (Index f : region) {
        const Index d = defects_of(f, facing);
        if (d > 0 && (strict || patch[f] == p)) {
          flat = false;
          break;
        }
        defects_after += d;
      }
      if (flat && (strict || defects_after < defects_before)) {
        double farthest = 0;
        for (std::size_t i = 0; i < vs.size(); ++i) farthest = std::max(farthest, (P[vs[i]] - before[i]).norm());
        if (farthest <= max_move) {
          ++report.unfolded_patches, report.moved_vertices += Index(vs.size());
          report.farthest_move = std::max(report.farthest_move, farthest);
          return true;
        }
        too_far[p] = farthest;
      }
      for (std::size_t i = 0; i < vs.size(); ++i) P[vs[i]] = before[i];
      if (std::isfinite(too_far[p])) break;
    }
    for (Index v : newly_held) held[v] = kNone;  // free for the patches after it
    vs.resize(own);
    return false;
  };
  std::vector<char> tried = patches_that_are_discs(m, patch, patches);
  // Ten times the distance of the merges, far below any mesh's spacing.
  if (options.folds_only_at) only_patches_at(m, patch, *options.folds_only_at, 1e-5 * diagonal, tried);
  // A patch whose rings met another patch's vertices is tried again at the end, once every
  // patch has moved: whether two folds a few triangles apart both lay flat depended on
  // which came first. Letting the second try take the vertices of patches laid flat was
  // not needed for that, and is not done: no try moves another patch's vertices.
  std::vector<Index> retry, left;
  for (Index p = 0; p < patches; ++p)
    if (tried[p] && !lay_flat(p, true)) (met ? retry : left).push_back(p);
  for (Index p : retry)
    if (!lay_flat(p, true)) left.push_back(p);
  // Noise turns triangles around a fold too, and a region with one of them left turned
  // never counted as flat: glmark2's bunny split twice, with noise of a tenth of its mean
  // edge, kept 10 of its 29 folds, and 11 defective quads at 20,000 over them. What the
  // strict tries left is laid flat where that leaves its region with fewer defects. Only
  // patches no strict try laid flat come here, so inputs without such leave as they were.
  std::sort(left.begin(), left.end());
  for (Index p : left) lay_flat(p, false);
  for (Index p = 0; p < patches; ++p)
    if (std::isfinite(too_far[p]))
      report.least_kept_move = report.kept_far_folds++ ? std::min(report.least_kept_move, too_far[p]) : too_far[p];
}

}  // namespace qs::detail
