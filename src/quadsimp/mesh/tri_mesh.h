// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "quadsimp/util/types.h"

namespace qs {

//! An indexed triangle mesh: the reference surface M0 and the input of the
//! tri-to-quad conversion. Plain data; invariants are established by clean().
struct TriMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<Index, 3>> faces;

  Index n_vertices() const { return Index(positions.size()); }
  Index n_faces() const { return Index(faces.size()); }
  //! The cross product of triangle t's edges from its first corner: its normal, as long
  //! as twice its area.
  Vec3 area_normal(const std::array<Index, 3>& t) const {
    return (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
  }
};

//! Neighbouring triangles whose normals' cosine is under this are turned back onto each
//! other (by over 120 degrees): clean() mends a single triangle so turned against all its
//! neighbours, and ReferenceSurface marks the small patches bounded by such edges
//! (folded_patches()) that clean() could not lay flat.
inline constexpr double kFoldedBackCos = -0.5;

//! clean() lays flat the patches folded back that cover under this share of their piece
//! (folded_patches()); ReferenceSurface marks those it left under a smaller one.
inline constexpr double kLaidFlatShare = 1e-2;

//! The patches clean() tries to lay flat are bounded by edges turning by over about 101.5
//! degrees, less than kFoldedBackCos asks: where a fold's layers meet the surface at a
//! slant, its ends turn by as little as 108 degrees (a column of a wave grid pushed past
//! its neighbours). ReferenceSurface's marking keeps kFoldedBackCos.
inline constexpr double kLaidFlatCos = -0.2;

inline double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); }

//! Thinness of triangle t: twice its area over its longest edge squared (its height over
//! that edge, in edge lengths); `longest` is set to that edge (k: corners k, k+1).
double thinness(const TriMesh& mesh, const std::array<Index, 3>& t, Index& longest);

//! The triangles' unit normals.
std::vector<Vec3> unit_normals(const TriMesh& mesh);

//! For each position, the lowest index of the positions equal to it (itself if none
//! comes before it); non-finite positions map to themselves. clean() merges by it.
std::vector<Index> first_equal_positions(const std::vector<Vec3>& positions);

//! Renumbers faces along a Morton curve of their centroids, and vertices in the order
//! the faces first use them; the surface is unchanged. The simplifier's queries jump
//! from collapse to collapse and each one reads M0 and the quads around one place:
//! with neighbours close in memory the bunny ran 10% faster.
//! \pre no unreferenced vertices (they are dropped).
void sort_spatially(TriMesh& mesh);

//! The mean length of the triangles' edges (each counted once per triangle), 0 without
//! triangles: the fitmaps' first radius, ReferenceSurface's mean edge, Creases' measure.
double mean_edge_length(const TriMesh& mesh);

//! Length of the diagonal of the axis-aligned bounding box.
double bbox_diagonal(const std::vector<Vec3>& positions);

//! The axis-aligned bounding box of the vertices the faces use: a stray vertex no face
//! uses, far off, must not set the size tolerances are relative to.
std::pair<Vec3, Vec3> used_bbox(const TriMesh& mesh);

//! The point to subtract before float or moment arithmetic: the bounding box's centre
//! when it lies farther from the origin than the box's diagonal (a scan in survey
//! coordinates, a million units out: float rounds it to a quarter unit, and moments
//! cancel every digit), else the origin itself, where a shift would only change rounding.
Vec3 working_origin(const std::vector<Vec3>& positions);

//! The sum of the triangles' areas, in their order (ReferenceSurface::area() is this).
double surface_area(const TriMesh& mesh);
//! Each vertex's area-weighted normal, not normalised: the sum of its triangles' area
//! normals, in their order (ReferenceSurface's vertex normals are these, normalised).
std::vector<Vec3> vertex_area_normals(const TriMesh& mesh);
//! Each vertex's angle-weighted unit normal: its triangles' unit normals weighted by their
//! angles at it, which does not depend on how the surface around it is split into
//! triangles (a cube's corner: along the diagonal however its three sides are split).
//! Zero where the vertex has no triangle of any area.
std::vector<Vec3> vertex_angle_normals(const TriMesh& mesh);

//! Neighbour triangle across edge k (corner k to k+1) of each triangle; kNone on the
//! border. \pre edge-manifold (see clean()).
std::vector<std::array<Index, 3>> triangle_adjacency(const TriMesh& mesh);

//! Each vertex's neighbours through edges, as compressed rows in increasing order: those
//! of v are next[start[v]] to next[start[v + 1] - 1]. `border` marks the vertices with an
//! edge in one triangle only.
struct VertexRings {
  std::vector<Index> start, next;
  std::vector<char> border;
};
VertexRings vertex_rings(const TriMesh& mesh);

//! Connected component id per face (faces sharing an edge), and their count, from
//! the mesh's triangle_adjacency(); with `joined`, only neighbours f, g for which
//! joined(f, g) holds are in the same component.
Index face_components(const std::vector<std::array<Index, 3>>& adjacency, std::vector<Index>& component,
                      const std::function<bool(Index, Index)>& joined = {});

//! Small patches folded back onto the surface, as a scan's Z-fold leaves them (three
//! layers, the middle one facing the other way). Triangles form patches across edges
//! that do not turn back (normals' cosine at least `turned_cos`); a patch under
//! `largest_share` of its connected piece's area is taken for folded back, while a sheet
//! with a sharp rim (two sides alike in area) is not. Sets patch[f] to the number of f's
//! patch, kNone for other triangles (or leaves `patch` empty), and returns how many there
//! are.
//! `unit_normals` are the triangles' unit normals.
Index folded_patches(const TriMesh& mesh, const std::vector<std::array<Index, 3>>& adjacency,
                     const std::vector<Vec3>& unit_normals, std::vector<Index>& patch, double largest_share,
                     double turned_cos);

//! Every triangle split into four at its edges' midpoints (the same surface, four times
//! the triangles): how the benchmarks and tests make a large mesh of a shared one.
TriMesh split_in_four(const TriMesh& mesh);

}  // namespace qs
