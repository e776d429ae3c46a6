// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// The MeshLab plugins' shared code (plugin/common) without MeshLab: its layer
// conversions on meshes built like MeshLab's CMeshO (optional components, in float as
// 2020.09 builds it and in double as pymeshlab's 2025.07d does), its parameter mapping
// and its filter bodies. The meshlabserver and pymeshlab suites run the same code inside
// MeshLab; these reach the cases those cannot build (deleted elements, doublets, each
// parameter on its own) in seconds, and give the code a coverage figure.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <vcg/complex/complex.h>

#include "filter_runner.h"
#include "filter_specs.h"
#include "fixtures/shapes.h"
#include "layer_conversion.h"
#include "quadsimp/fitmap/fitmap.h"
#include "quadsimp/mesh/clean.h"
#include "quadsimp/metrics/metrics.h"
#include "quadsimp/reference/reference_surface.h"
#include "quadsimp/texture/texture_bake.h"
#include "quadsimp/util/errors.h"

using namespace qs;
using namespace qs::plugin;
using namespace qs::fixtures;

namespace {

// A MeshLab layer's mesh: CMeshO's components that the plugin's code touches, with
// marks, face colours and adjacency optional as in MeshLab (SurfaceColours enables the
// marks), and wedge and vertex texture coordinates.
template <class S>
struct Parts {
  template <class T> class VCoord : public vcg::vertex::Coord<vcg::Point3<S>, T> {};
  template <class T> class VNormal : public vcg::vertex::Normal<vcg::Point3<S>, T> {};
  template <class T> class VQuality : public vcg::vertex::Quality<S, T> {};
  template <class T> class FNormal : public vcg::face::NormalAbs<vcg::Point3<S>, T> {};
};
template <class S> class LayerVertex;
template <class S> class LayerFace;
template <class S>
struct LayerTypes : vcg::UsedTypes<vcg::Use<LayerVertex<S>>::template AsVertexType,
                                   vcg::Use<LayerFace<S>>::template AsFaceType> {};
template <class S>
class LayerVertex
    : public vcg::Vertex<LayerTypes<S>, vcg::vertex::InfoOcf, Parts<S>::template VCoord, vcg::vertex::BitFlags,
                         Parts<S>::template VNormal, Parts<S>::template VQuality, vcg::vertex::Color4b,
                         vcg::vertex::MarkOcf, vcg::vertex::TexCoordfOcf> {};
template <class S>
class LayerFace : public vcg::Face<LayerTypes<S>, vcg::face::InfoOcf, vcg::face::VertexRef, vcg::face::BitFlags,
                                   Parts<S>::template FNormal, vcg::face::Color4bOcf, vcg::face::MarkOcf,
                                   vcg::face::FFAdjOcf, vcg::face::WedgeTexCoordfOcf> {};
template <class S>
class Layer
    : public vcg::tri::TriMesh<vcg::vertex::vector_ocf<LayerVertex<S>>, vcg::face::vector_ocf<LayerFace<S>>> {
 public:
  ~Layer() { this->ClearAttributes(); }
};

// A quad up to where its corner list starts, as positions (in float, as 2020.09's
// layers hold them): comparable across meshes whose vertex ids differ.
using Corners = std::array<std::array<float, 3>, 4>;
Corners corners_of(const std::vector<Vec3>& p, std::array<Index, 4> q) {
  std::rotate(q.begin(), std::min_element(q.begin(), q.end(), [&](Index a, Index b) {
                return std::lexicographical_compare(p[a].data(), p[a].data() + 3, p[b].data(), p[b].data() + 3);
              }), q.end());
  Corners c;
  for (int k = 0; k < 4; ++k) c[k] = {float(p[q[k]].x()), float(p[q[k]].y()), float(p[q[k]].z())};
  return c;
}
std::set<Corners> quads_of(const std::vector<Vec3>& positions, const std::vector<std::array<Index, 4>>& quads) {
  std::set<Corners> out;
  for (const auto& q : quads) out.insert(corners_of(positions, q));
  return out;
}
std::set<Corners> quads_of(const QuadMesh& q) { return quads_of(q.positions(), q.quads()); }

template <class S>
class PluginLayer : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(PluginLayer, Scalars);

TYPED_TEST(PluginLayer, quads_come_back_from_their_triangle_pairs) {
  for (const QuadMesh& q : {quad_grid(4, 3), cube()}) {
    Layer<TypeParam> layer;
    assign_quads(layer, q);
    ASSERT_EQ(layer.fn, int(2 * q.n_faces()));
    ASSERT_EQ(layer.vn, int(q.n_vertices()));
    // Each triangle has one faux edge: the diagonal it shares with its quad's other half.
    for (const auto& f : layer.face) EXPECT_EQ(int(f.IsF(0)) + int(f.IsF(1)) + int(f.IsF(2)), 1);
    const MeshFile back = mesh_file_of(layer);
    EXPECT_TRUE(back.is_pure_quad());
    EXPECT_EQ(quads_of(back.positions, back.quads), quads_of(q));
  }
}

// A texture's corner coordinates reach each quad's two triangles at the corners they
// belong to, whichever diagonal assign_quads() split the quad at, and read back the same;
// a deleted face is skipped, and a texture number naming no texture, or two numbers on one
// triangle, give none.
TYPED_TEST(PluginLayer, texture_coordinates_follow_the_quads_corners) {
  QuadMesh q = quad_grid(4, 3);
  for (Index v = 0; v < q.n_vertices(); ++v) q.position(v).x() += 0.3 * std::sin(3.0 * v);  // both splits occur
  const std::vector<std::uint8_t> split = split_diagonals(q);
  ASSERT_NE(std::count(split.begin(), split.end(), 1), 0);
  ASSERT_NE(std::count(split.begin(), split.end(), 0), 0);
  QuadTexture t;
  t.corners.resize(q.face_capacity());
  for (Index f = 0; f < q.face_capacity(); ++f)
    for (int k = 0; k < 4; ++k) t.corners[f][std::size_t(k)] = {float(f), float(k)};
  Layer<TypeParam> layer;
  assign_quads(layer, q);
  layer.face.EnableWedgeTexCoord();
  assign_texture(layer, q, split, t);
  const FileTexture back = texture_of(layer, true, {"atlas"});
  ASSERT_EQ(back.triangles.size(), 2 * std::size_t(q.n_faces()));
  EXPECT_EQ(back.images, std::vector<std::string>{"atlas"});
  for (std::size_t i = 0; i < back.triangles.size(); ++i) {
    const Index f = Index(i / 2);
    for (int k = 0; k < 3; ++k) {
      const TexCoord c = back.coords[i][std::size_t(k)];
      ASSERT_EQ(c[0], float(f));
      EXPECT_EQ(q.vertex(f, int(c[1])), back.triangles[i][std::size_t(k)]) << "triangle " << i << " corner " << k;
    }
  }
  vcg::tri::Allocator<Layer<TypeParam>>::DeleteFace(layer, layer.face[0]);
  EXPECT_EQ(texture_of(layer, true, {"atlas"}).triangles.size(), back.triangles.size() - 1);
  for (int k = 0; k < 3; ++k) layer.face[3].WT(k).N() = 1;
  EXPECT_TRUE(texture_of(layer, true, {"atlas"}).empty());
  const FileTexture two = texture_of(layer, true, {"atlas", "another"});
  ASSERT_EQ(two.image.size(), back.triangles.size() - 1);
  EXPECT_EQ(two.image[2], 1);
  layer.face[3].WT(2).N() = 0;  // one triangle, two textures
  EXPECT_TRUE(texture_of(layer, true, {"atlas", "another"}).empty());
  // Per-vertex coordinates: each corner its vertex's.
  layer.vert.EnableTexCoord();
  for (std::size_t v = 0; v < layer.vert.size(); ++v) {
    layer.vert[v].T().U() = float(v);
    layer.vert[v].T().V() = 0.5f;
    layer.vert[v].T().N() = 0;
  }
  const FileTexture per_vertex = texture_of(layer, false, {"atlas"});
  ASSERT_EQ(per_vertex.triangles.size(), back.triangles.size() - 1);
  for (std::size_t i = 0; i < per_vertex.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(per_vertex.coords[i][std::size_t(k)], (TexCoord{float(per_vertex.triangles[i][std::size_t(k)]), 0.5f}));
}

// With face colours asked for, a face whose texture number is -1 at every corner takes
// its face colour (image -1) beside the textured ones; without them, or where no face
// is textured, the layer has no texture.
TYPED_TEST(PluginLayer, faces_without_a_texture_take_their_colour) {
  const QuadMesh q = quad_grid(2, 1);
  Layer<TypeParam> layer;
  assign_quads(layer, q);
  layer.face.EnableWedgeTexCoord();
  layer.face.EnableColor();
  for (std::size_t f = 0; f < layer.face.size(); ++f) {
    layer.face[f].C() = f < 2 ? vcg::Color4b(255, 255, 255, 255) : vcg::Color4b(200, 10, 20, 128);
    for (int k = 0; k < 3; ++k) layer.face[f].WT(k).N() = f < 2 ? 0 : -1;
  }
  const FileTexture t = texture_of(layer, true, {"atlas"}, true);
  EXPECT_EQ(t.image, (std::vector<int>{0, 0, -1, -1}));
  ASSERT_EQ(t.colours.size(), 4u);
  EXPECT_EQ(t.colours[2], (Colour{200, 10, 20, 128}));
  EXPECT_TRUE(texture_of(layer, true, {"atlas"}).empty());
  for (std::size_t f = 0; f < 2; ++f)
    for (int k = 0; k < 3; ++k) layer.face[f].WT(k).N() = -1;
  EXPECT_TRUE(texture_of(layer, true, {"atlas"}, true).empty());
  for (int k = 0; k < 3; ++k) layer.face[0].WT(k).N() = 0;
  layer.face[3].WT(1).N() = 0;  // one triangle, a texture and none
  EXPECT_TRUE(texture_of(layer, true, {"atlas"}, true).empty());
}

TYPED_TEST(PluginLayer, deleted_vertices_and_faces_are_left_out) {
  const QuadMesh q = quad_grid(3, 3);
  Layer<TypeParam> layer;
  assign_quads(layer, q);
  // The first quad (assign_quads() writes each quad's two triangles in turn) and its
  // corner 0, which no other quad uses, deleted as a filter that does not compact leaves
  // them. assign_quads() keeps the order of the live vertices.
  using Alloc = vcg::tri::Allocator<Layer<TypeParam>>;
  ASSERT_EQ(q.valence(0), 2);
  Alloc::DeleteFace(layer, layer.face[0]);
  Alloc::DeleteFace(layer, layer.face[1]);
  Alloc::DeleteVertex(layer, layer.vert[0]);
  std::vector<std::array<Index, 4>> kept = q.quads();
  kept.erase(kept.begin());
  const MeshFile back = mesh_file_of(layer);
  EXPECT_EQ(back.positions.size(), q.n_vertices() - 1);
  EXPECT_TRUE(back.is_pure_quad());
  for (const auto& quad : back.quads)
    for (Index v : quad) ASSERT_LT(v, back.positions.size());
  EXPECT_EQ(quads_of(back.positions, back.quads), quads_of(q.positions(), kept));
}

TYPED_TEST(PluginLayer, a_doublet_is_two_pairs_and_no_triangle_twice) {
  // Two quads on the same four corners around an inner vertex, each listed from a corner
  // of diagonal 1-3, which both have: split along it, both would make triangle (1, 3, 4).
  const std::vector<Vec3> p = {{-1, 0, 0}, {0, -0.4, 0}, {1, 0, 0}, {0, 0.4, 0}, {-0.5, 0, 0}};
  const QuadMesh q = QuadMesh::from_faces(p, {{3, 0, 1, 4}, {1, 2, 3, 4}});
  Layer<TypeParam> layer;
  assign_quads(layer, q);
  std::set<std::set<const void*>> triangles;
  for (const auto& f : layer.face) triangles.insert({f.cV(0), f.cV(1), f.cV(2)});
  EXPECT_EQ(triangles.size(), layer.face.size());
  const MeshFile back = mesh_file_of(layer);
  EXPECT_TRUE(back.is_pure_quad());
  EXPECT_EQ(quads_of(back.positions, back.quads), quads_of(q));
}

TYPED_TEST(PluginLayer, fitmaps_go_to_the_live_vertices_in_order) {
  Layer<TypeParam> layer;
  assign_quads(layer, quad_grid(1, 1));
  vcg::tri::Allocator<Layer<TypeParam>>::DeleteVertex(layer, layer.vert[1]);
  const Fitmaps f{{0.5f, 1.5f, 2.5f}, {3.f, 4.f, 5.f}};
  store_fitmaps(layer, f);
  auto s = vcg::tri::Allocator<Layer<TypeParam>>::template GetPerVertexAttribute<TypeParam>(layer, "FitmapS");
  auto m = vcg::tri::Allocator<Layer<TypeParam>>::template GetPerVertexAttribute<TypeParam>(layer, "FitmapM");
  const std::size_t live[] = {0, 2, 3};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(s[live[i]], TypeParam(f.s[i]));
    EXPECT_EQ(m[live[i]], TypeParam(f.m[i]));
    EXPECT_EQ(layer.vert[live[i]].Q(), TypeParam(f.s[i]));
  }
}

TYPED_TEST(PluginLayer, quads_take_the_colour_at_their_closest_point) {
  // A unit square, red along x = 0 and blue along x = 1, and a quad above it with corners
  // over x = 0.25 and x = 1 and one past its side.
  Layer<TypeParam> input;
  assign_quads(input, quad_grid(1, 1));
  for (auto& v : input.vert) v.C() = v.cP()[0] < 0.5 ? vcg::Color4b(255, 0, 0, 255) : vcg::Color4b(0, 0, 255, 255);
  const std::vector<Vec3> p = {{0.25, 0, 0.1}, {1, 0, 0.1}, {2, 1, 0.1}, {0.25, 1, 0.1}};
  Layer<TypeParam> quads;
  assign_quads(quads, QuadMesh::from_faces(p, {{0, 1, 2, 3}}));
  paint(SurfaceColours<Layer<TypeParam>>(input, true, false), quads);
  EXPECT_EQ(quads.vert[0].C(), vcg::Color4b(191, 0, 64, 255));
  EXPECT_EQ(quads.vert[1].C(), vcg::Color4b(0, 0, 255, 255));
  EXPECT_EQ(quads.vert[2].C(), vcg::Color4b(0, 0, 255, 255));
  // One colour all over is passed on as it is.
  for (auto& v : input.vert) v.C() = vcg::Color4b(10, 20, 30, 40);
  paint(SurfaceColours<Layer<TypeParam>>(input, true, false), quads);
  for (const auto& v : quads.vert) EXPECT_EQ(v.cC(), vcg::Color4b(10, 20, 30, 40));
}

TYPED_TEST(PluginLayer, quads_take_the_colour_of_the_face_closest_to_their_centre) {
  // Four unit cells in a row, coloured red, red, blue, green; the green one deleted. Two
  // quads above it, each two cells wide, and a third past its end.
  const vcg::Color4b red(255, 0, 0, 255), blue(0, 0, 255, 255), green(0, 255, 0, 255);
  Layer<TypeParam> input;
  input.face.EnableColor();
  assign_quads(input, quad_grid(4, 1));
  for (auto& f : input.face) {
    const auto x = (f.cP(0)[0] + f.cP(1)[0] + f.cP(2)[0]) / 3;
    f.C() = x < 2 ? red : x < 3 ? blue : green;
    if (x > 3) vcg::tri::Allocator<Layer<TypeParam>>::DeleteFace(input, f);
  }
  const std::vector<Vec3> p = {{0, 0, 0.1}, {2, 0, 0.1}, {2, 1, 0.1}, {0, 1, 0.1}, {4.2, 0, 0.1},
                               {4.2, 1, 0.1}, {5, 0, 0.1}, {5, 1, 0.1}};
  Layer<TypeParam> quads;
  quads.face.EnableColor();
  assign_quads(quads, QuadMesh::from_faces(p, {{0, 1, 2, 3}, {1, 4, 5, 2}, {4, 6, 7, 5}}));
  for (auto& v : quads.vert) v.C() = green;
  paint(SurfaceColours<Layer<TypeParam>>(input, false, true), quads);
  // Quad 1 (x 2 to 4.2, centre 3.1) is nearest the blue cell once the green one is gone;
  // the last one too. Each quad's two triangles alike; the vertices left as they were.
  const vcg::Color4b expected[3] = {red, blue, blue};
  for (std::size_t f = 0; f < quads.face.size(); ++f) EXPECT_EQ(quads.face[f].cC(), expected[f / 2]) << f;
  for (const auto& v : quads.vert) EXPECT_EQ(v.cC(), green);
  // One colour all over is passed on as it is, and so are both kinds together.
  for (auto& f : input.face) f.C() = vcg::Color4b(10, 20, 30, 40);
  for (auto& v : input.vert) v.C() = vcg::Color4b(1, 2, 3, 4);
  paint(SurfaceColours<Layer<TypeParam>>(input, true, true), quads);
  for (const auto& f : quads.face) EXPECT_EQ(f.cC(), vcg::Color4b(10, 20, 30, 40));
  for (const auto& v : quads.vert) EXPECT_EQ(v.cC(), vcg::Color4b(1, 2, 3, 4));
}

TYPED_TEST(PluginLayer, a_layer_without_faces_is_refused_with_what_it_is) {
  Layer<TypeParam> points;
  vcg::tri::Allocator<Layer<TypeParam>>::AddVertices(points, 7);
  try {
    require_faces(points, "scan");
    FAIL() << "a point cloud was taken";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()),
              "scan: the layer has no faces (7 vertices: a point cloud, or lines only?); quadsimp needs a triangle "
              "surface");
  }
  assign_quads(points, quad_grid(1, 1));
  EXPECT_NO_THROW(require_faces(points, "scan"));
}

// A RichParameterList as simplify_params_of() reads it, which records the keys asked for.
class Parameters {
 public:
  explicit Parameters(FilterId id) {
    for (const ParamSpec& p : params_of(id)) values_[p.key] = p.value;
  }
  double& operator[](const std::string& key) { return values_.at(key); }
  bool getBool(const std::string& key) const { return value(key) != 0; }
  int getInt(const std::string& key) const { return int(value(key)); }
  float getFloat(const std::string& key) const { return float(value(key)); }  // MeshLab 2020.09's Scalarm
  std::set<std::string> read() const { return read_; }

 private:
  double value(const std::string& key) const {
    read_.insert(key);
    return values_.at(key);  // a key the filter does not declare: std::out_of_range
  }
  std::map<std::string, double> values_;
  mutable std::set<std::string> read_;
};

TEST(PluginParams, the_dialogs_defaults_are_the_clis) {
  Parameters list(kSimplify);
  list["TargetFaceNum"] = 500;  // the dialog's default depends on the layer
  const SimplifyParams p = simplify_params_of(list), cli;
  EXPECT_EQ(p.target_faces, 500u);
  EXPECT_EQ(p.target_share, cli.target_share);
  EXPECT_EQ(p.adaptive, cli.adaptive);
  EXPECT_EQ(p.auto_halt, cli.auto_halt);
  EXPECT_FLOAT_EQ(float(p.tau), float(cli.tau));
  EXPECT_FLOAT_EQ(float(p.halt_share), float(cli.halt_share));
  EXPECT_FLOAT_EQ(float(p.max_aspect), float(cli.max_aspect));
  EXPECT_FLOAT_EQ(float(p.reach), float(cli.reach));
  EXPECT_EQ(p.m_factor, cli.m_factor);  // not a filter parameter
  EXPECT_EQ(p.m_slack, cli.m_slack);
  EXPECT_EQ(p.preserve_boundary, cli.preserve_boundary);
  EXPECT_EQ(p.keep_tips, cli.keep_tips);
  EXPECT_EQ(p.crease_angle, cli.crease_angle);
  EXPECT_EQ(p.fast, cli.fast);
  EXPECT_EQ(p.fit_to_input, cli.fit_to_input);
  EXPECT_EQ(texture_size_of(list), TextureBakeOptions().max_side);  // the CLI's --texture-size
  // Every parameter the dialog shows is read, and nothing else.
  std::set<std::string> declared;
  for (const ParamSpec& s : params_of(kSimplify)) declared.insert(s.key);
  EXPECT_EQ(list.read(), declared);
}

// What a user reads must be what the filters take: the README's filter table names every
// filter and each one's parameters, its pymeshlab section every parameter's lowercased
// name (it once lacked `creaseangle` and `samplenum`), and its meshlabserver script is
// the example the meshlabserver test runs, with every parameter (2020.09 stops on a
// script that lacks one).
TEST(PluginParams, the_readme_names_every_filter_and_parameter) {
  const auto read = [](const std::string& path) {
    std::ifstream in(path);
    EXPECT_TRUE(in) << path;
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string readme = read(QS_SOURCE_DIR "/README.md");
  const auto section = [&](const std::string& heading) {
    const std::size_t at = readme.find("\n## " + heading);
    EXPECT_NE(at, std::string::npos) << heading;
    return at == std::string::npos ? std::string() : readme.substr(at, readme.find("\n## ", at + 1) - at);
  };
  const std::string meshlab = section("MeshLab 2020.09"), python = section("pymeshlab 2025.7");
  for (const FilterSpec& f : filter_specs()) {
    const std::size_t row = meshlab.find(std::string("\n| ") + f.name + " |");
    ASSERT_NE(row, std::string::npos) << f.name;
    const std::string line = meshlab.substr(row + 1, meshlab.find('\n', row + 1) - row - 1);
    EXPECT_NE(line.find(std::string("`") + f.python_name + "`"), std::string::npos) << line;
    for (const ParamSpec& p : params_of(f.id)) {
      const std::size_t at = line.find(p.key), end = at + std::strlen(p.key);
      const bool word = at != std::string::npos && line[at - 1] == ' ' &&
                        !std::isalnum(static_cast<unsigned char>(line[end]));
      EXPECT_TRUE(word) << p.key << " in " << line;
      std::string lower = p.key;
      std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return std::tolower(c); });
      EXPECT_TRUE(python.find("`" + lower + "`") != std::string::npos ||
                  python.find("(" + lower + "=") != std::string::npos)  // in an example's call
          << lower;
    }
  }
  const std::string script = read(QS_SOURCE_DIR "/plugin/meshlab2020/examples/quad_simplification.mlx");
  EXPECT_NE(meshlab.find("```xml\n" + script + "```"), std::string::npos) << "the README's script is not the example's";
  for (const ParamSpec& p : params_of(kSimplify))
    EXPECT_NE(script.find(std::string("<Param name=\"") + p.key + "\""), std::string::npos) << p.key;
}

TEST(PluginParams, each_parameter_reaches_its_own_field) {
  Parameters list(kSimplify);
  list["Adaptive"] = 1, list["TargetFaceNum"] = 321, list["HaltShare"] = 0.5, list["Tau"] = 0.125;
  list["MaxAspect"] = 2, list["Reach"] = 0.25, list["PreserveBoundary"] = 1, list["KeepTips"] = 1;
  list["Fast"] = 1, list["FitToInput"] = 1, list["TargetPerc"] = 0.375, list["CreaseAngle"] = 42;
  list["TextureSize"] = 512;
  EXPECT_EQ(texture_size_of(list), 512);
  SimplifyParams p = simplify_params_of(list);
  EXPECT_EQ(p.crease_angle, 42);
  EXPECT_TRUE(p.adaptive);
  EXPECT_FALSE(p.auto_halt);
  EXPECT_EQ(p.target_faces, 321u);
  EXPECT_EQ(p.target_share, 0.375);
  EXPECT_EQ(p.halt_share, 0.5);
  EXPECT_EQ(p.tau, 0.125);
  EXPECT_EQ(p.max_aspect, 2);
  EXPECT_EQ(p.reach, 0.25);
  EXPECT_TRUE(p.preserve_boundary && p.keep_tips && p.fast && p.fit_to_input);
  // Automatic halting leaves the target out (the dialog always has one).
  list["AutoHalt"] = 1;
  p = simplify_params_of(list);
  EXPECT_TRUE(p.auto_halt);
  EXPECT_EQ(p.target_faces, 0u);
  EXPECT_EQ(p.target_share, 0);
}

TEST(PluginParams, combinations_the_run_cannot_take_are_refused) {
  Parameters list(kSimplify);
  list["TargetFaceNum"] = -3;  // no target in uniform mode
  EXPECT_THROW(simplify_params_of(list), std::invalid_argument);
  list["TargetFaceNum"] = 100, list["AutoHalt"] = 1;  // automatic halting without the adaptive mode
  EXPECT_THROW(simplify_params_of(list), std::invalid_argument);
  list["AutoHalt"] = 0, list["MaxAspect"] = 0.5;
  EXPECT_THROW(simplify_params_of(list), std::invalid_argument);
  list["MaxAspect"] = 3, list["TargetPerc"] = 1.5;  // a share past the whole
  EXPECT_THROW(simplify_params_of(list), std::invalid_argument);
  list["TargetPerc"] = 0.5, list["TargetFaceNum"] = -3;  // a share is a target without a number
  EXPECT_NO_THROW(simplify_params_of(list));
  // The texture sizes the CLI refuses.
  for (const int side : {15, 16385, 0}) {
    list["TextureSize"] = side;
    EXPECT_THROW(texture_size_of(list), std::invalid_argument) << side;
  }
  list["TextureSize"] = 16;
  EXPECT_EQ(texture_size_of(list), 16);
}

TEST(PluginSpecs, names_are_unique_and_defaults_in_range) {
  std::set<std::string> names, python_names;
  for (const FilterSpec& f : filter_specs()) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name;
    EXPECT_TRUE(python_names.insert(f.python_name).second) << f.python_name;
    EXPECT_EQ(&filter_spec(f.id), &f);
    std::set<std::string> keys;
    for (const ParamSpec& p : params_of(f.id)) {
      EXPECT_TRUE(keys.insert(p.key).second) << f.name << ": " << p.key;
      EXPECT_LE(p.min, p.max) << p.key;
      if (p.kind == ParamKind::Float || p.kind == ParamKind::Bool) {
        EXPECT_TRUE(p.value >= p.min && p.value <= p.max) << f.name << ": " << p.key;
      }
      if (p.kind == ParamKind::Bool) {
        EXPECT_TRUE(p.value == 0 || p.value == 1) << p.key;
      }
    }
  }
  EXPECT_EQ(names.size(), 4u);
  EXPECT_THROW(filter_spec(FilterId(99)), std::out_of_range);
  EXPECT_EQ(default_target_faces(69'451), 3'472);
  EXPECT_EQ(default_target_faces(20), 6);
}

// The descriptions give some defaults in words, where the dialog cannot show them (the
// slack has no parameter; the reach and halting share appear in the filter's own text):
// a change of a default must change its words too.
TEST(PluginSpecs, descriptions_quote_the_pipelines_defaults) {
  const SimplifyParams d;
  const auto words = [](double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  const auto help = [](const char* key) {
    for (const ParamSpec& p : params_of(kSimplify))
      if (std::string(p.key) == key) return std::string(p.help);
    ADD_FAILURE() << key;
    return std::string();
  };
  const std::string& info = filter_spec(kSimplify).info;
  EXPECT_NE(info.find("reach (" + words(100 * d.reach) + "% "), std::string::npos) << info;
  EXPECT_NE(info.find("share of the surface (" + words(100 * d.halt_share) + "% "), std::string::npos) << info;
  EXPECT_NE(help("HaltShare").find("(" + words(d.halt_share) + ": "), std::string::npos);
  EXPECT_NE(help("Reach").find("may grow " + words(d.m_slack) + " times past"), std::string::npos);
}

// vcg::CallBackPos's shape: the percentage and a message.
std::vector<int> percents_seen;
bool record(const int percent, const char*) {
  percents_seen.push_back(percent);
  return true;
}

TEST(PluginProgress, each_percent_is_reported_once) {
  EXPECT_FALSE(progress_of<vcg::CallBackPos>(nullptr));
  percents_seen.clear();
  const ProgressFn progress = progress_of(&record);
  for (float f : {0.f, 0.001f, 0.004f, 0.01f, 0.011f, 0.5f, 0.5f, 1.f}) EXPECT_TRUE(progress(f, "stage"));
  EXPECT_EQ(percents_seen, (std::vector<int>{0, 1, 50, 100}));
}

// A sphere as a layer holds it with a seam: the vertices of one meridian twice.
MeshFile sphere_with_seam() {
  const TriMesh s = tri_sphere(12, 16);
  MeshFile f{s.positions, s.faces, {}};
  for (auto& t : f.triangles) {
    bool east = false;
    for (Index v : t) east |= s.positions[v].y() > 1e-9;
    for (Index& v : t) {
      if (!east || std::abs(s.positions[v].y()) > 1e-9 || s.positions[v].x() <= 0) continue;
      f.positions.push_back(s.positions[v]);  // a copy per use is enough for the test
      v = Index(f.positions.size() - 1);
    }
  }
  return f;
}

TEST(PluginRunner, fitmaps_reach_every_vertex_of_the_layer_seam_included) {
  const MeshFile layer = sphere_with_seam();
  ASSERT_GT(layer.positions.size(), tri_sphere(12, 16).positions.size());
  Outcome o;
  const Fitmaps f = run_fitmaps(layer, "ball", 0.05, {}, o);
  ASSERT_EQ(f.s.size(), layer.positions.size());
  ASSERT_EQ(f.m.size(), layer.positions.size());
  // The seam's copies read the fitmaps of the vertex cleaning merged them into.
  TriMesh clean_sphere = tri_sphere(12, 16);
  const Fitmaps reference = compute_fitmaps(clean_sphere, {});
  for (std::size_t v = 0; v < layer.positions.size(); ++v) {
    const auto& all = clean_sphere.positions;
    const auto it = std::find(all.begin(), all.end(), layer.positions[v]);
    ASSERT_NE(it, all.end());
    const std::size_t same = std::size_t(it - all.begin());
    EXPECT_NEAR(f.s[v], reference.s[same], 1e-4 * reference.s[same]) << v;
    EXPECT_NEAR(f.m[v], reference.m[same], 1e-4 * reference.m[same]) << v;
  }
  ASSERT_FALSE(o.log.empty());
  EXPECT_EQ(o.log.back(), "ball: fitmaps of " + std::to_string(layer.positions.size()) + " vertices (tau 0.05)");
}

TEST(PluginRunner, quality_measures_quads_and_refuses_anything_else) {
  const QuadMesh q = quad_grid(6, 6);
  MeshFile quads{q.positions(), {}, q.quads()};
  for (Vec3& p : quads.positions) p /= 6;  // tri_grid's unit square
  const TriMesh tri = tri_grid(6, 6);
  const MeshFile reference{tri.positions, tri.faces, {}};
  Outcome o;
  run_quality(quads, "quads", reference, "input", 5000, o);
  EXPECT_EQ(o.values.at("faces"), 36);
  EXPECT_EQ(o.values.at("vertices"), 49);
  EXPECT_NEAR(o.values.at("regular_percent"), 100.0 * 45 / 49, 1e-9);  // all but the four corners
  EXPECT_LT(o.values.at("rms_e3"), 1e-3);
  EXPECT_EQ(o.values.at("projectability"), 1);
  ASSERT_EQ(o.log.size(), 2u);
  const std::string first = "quads: 36 quads, max valence 4, regular 91.8%, homeometry 1.000 .. 1.000";
  EXPECT_EQ(o.log[0].rfind(first, 0), 0u) << o.log[0];
  EXPECT_EQ(o.log[1].rfind("distance to input (x1e-3 of its diagonal)", 0), 0u) << o.log[1];

  try {
    run_quality(reference, "tris", reference, "input", 5000, o);
    FAIL() << "triangles were measured as quads";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()), "tris: not a pure quad mesh (" + std::to_string(tri.faces.size()) +
                                         " triangles that do not pair up through faux edges)");
  }
  // Quads that are no surface are named too: three on one edge.
  const MeshFile fan{{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, -1, 0}, {0, -1, 0}, {0, 0, 1}, {1, 0, 1}},
                     {},
                     {{0, 1, 2, 3}, {1, 0, 5, 4}, {0, 1, 7, 6}}};
  try {
    run_quality(fan, "fan", reference, "input", 5000, o);
    FAIL() << "a non-manifold edge was measured";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind("fan: ", 0), 0u) << e.what();
  }
}

TEST(PluginRunner, simplification_logs_what_it_did_and_matches_the_pipeline) {
  const TriMesh t = tri_sphere(20, 30);
  const MeshFile layer{t.positions, t.faces, {}};
  SimplifyParams params;
  params.target_faces = 120;
  Outcome o;
  const QuadMesh q = run_simplification(layer, "ball", params, {}, o).mesh;
  EXPECT_LE(q.n_faces(), 120u);
  EXPECT_EQ(o.values.at("faces"), q.n_faces());
  ASSERT_GE(o.log.size(), 2u);
  EXPECT_EQ(o.log[0].rfind("ball: " + std::to_string(t.faces.size()) + " triangles paired into ", 0), 0u)
      << o.log[0];
  EXPECT_NE(o.log[1].find(" -> " + std::to_string(q.n_faces()) + " quads in "), std::string::npos) << o.log[1];
  // The CLI's path: the same quads.
  Input in = prepare_input(layer, "ball");
  const ReferenceSurface ref(std::move(in.reference));
  simplify_input(in, ref, params);
  EXPECT_EQ(quads_of(in.quads), quads_of(q));

  // A share of the quads the layer converts to, in place of the count.
  params.target_faces = 0, params.target_share = 0.25;
  Outcome share;
  const Index shared = run_simplification(layer, "ball", params, {}, share).mesh.n_faces();
  EXPECT_EQ(shared, Index(std::lround(0.25 * double(prepare_input(layer, "ball").quads.n_faces()))));
  params.target_share = 0;

  // A target under what the mesh can reach is said in the log.
  params.target_faces = 1;
  Outcome grid_log;
  const TriMesh holey = with_holes(tri_grid(30, 30), 0.03, 5);
  run_simplification({holey.positions, holey.faces, {}}, "grid", params, {}, grid_log);
  const bool said = std::any_of(grid_log.log.begin(), grid_log.log.end(),
                                [](const std::string& l) { return l.find("target") != std::string::npos; });
  EXPECT_TRUE(said) << ::testing::PrintToString(grid_log.log);

  // Conversion alone: the layer's triangles as quads, and how many paired.
  Outcome c;
  const QuadMesh converted = run_conversion(layer, "ball", 0, c).mesh;
  EXPECT_EQ(c.values.at("faces"), converted.n_faces());
  EXPECT_GT(c.values.at("pairing_rate"), 0.9);
  EXPECT_NO_THROW(validate(converted));
}

// A CAD cylinder's long triangles leave quads folded over its rims (README, Limits): the
// filter says how many and selects them in its result, both triangles of each and no
// other, so that a user finds them. A sphere's quads are sound: nothing is selected.
TEST(PluginRunner, flawed_quads_are_selected_in_the_result) {
  const TriMesh cylinder = cad_cylinder(64, 1, 2.0);
  SimplifyParams params;
  params.target_faces = 100;
  Outcome o;
  const LayerQuads r = run_simplification({cylinder.positions, cylinder.faces, {}}, "cylinder", params, {}, o);
  ASSERT_FALSE(r.flawed.empty());
  EXPECT_TRUE(std::is_sorted(r.flawed.begin(), r.flawed.end()));
  const std::string line = "the " + std::to_string(r.flawed.size()) +
                           " quads counted above (non-convex, flipped, folded or beyond the reach) are selected in "
                           "the new layer";
  EXPECT_NE(std::find(o.log.begin(), o.log.end(), line), o.log.end()) << ::testing::PrintToString(o.log);
  Layer<float> layer;
  assign_quads(layer, r.mesh, r.split, r.flawed);
  std::size_t t = 0, selected = 0;
  for (Index f = 0; f < r.mesh.face_capacity(); ++f) {
    if (!r.mesh.is_face_live(f)) continue;
    const bool flawed = std::binary_search(r.flawed.begin(), r.flawed.end(), f);
    for (int k = 0; k < 2; ++k, ++t) {
      EXPECT_EQ(layer.face[t].IsS(), flawed) << "quad " << f;
      selected += layer.face[t].IsS();
    }
  }
  EXPECT_EQ(selected, 2 * r.flawed.size());

  const TriMesh ball = tri_sphere(20, 30);
  params.target_faces = 120;
  Outcome sound;
  EXPECT_TRUE(run_simplification({ball.positions, ball.faces, {}}, "ball", params, {}, sound).flawed.empty());
  for (const std::string& l : sound.log) EXPECT_EQ(l.find("selected"), std::string::npos) << l;
}

// A sphere textured by longitude and height: the texture baked onto its quads is as wide
// as the input's texel density asks by default, and within the texture size given (both
// the simplification's and the conversion's).
TEST(PluginRunner, the_texture_size_bounds_the_quads_texture) {
  const TriMesh t = tri_sphere(16, 24);
  MeshFile layer{t.positions, t.faces, {}};
  layer.texture_coordinates = true;
  layer.texture.images = {"card"};
  for (const auto& f : t.faces) {
    std::array<TexCoord, 3> uv;
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = t.positions[f[k]].normalized();
      uv[k] = {float(0.5 + std::atan2(p.y(), p.x()) / (2 * M_PI)), float(0.5 + 0.5 * p.z())};
    }
    layer.texture.triangles.push_back(f);
    layer.texture.coords.push_back(uv);
    layer.texture.image.push_back(0);
  }
  Image card;
  card.width = card.height = 1024;
  card.rgba.assign(4u * 1024 * 1024, 200);
  SimplifyParams params;
  params.target_faces = 200;
  const auto side = [](const LayerQuads& q) { return std::max(q.texture.image.width, q.texture.image.height); };
  Outcome o;
  const LayerQuads wide = run_simplification(layer, "ball", params, {}, o, {card});
  const LayerQuads narrow = run_simplification(layer, "ball", params, {}, o, {card}, 128);
  ASSERT_FALSE(wide.texture.empty());
  ASSERT_FALSE(narrow.texture.empty());
  EXPECT_GT(side(wide), 128);
  EXPECT_LE(side(wide), TextureBakeOptions().max_side);
  EXPECT_LE(side(narrow), 128);
  EXPECT_EQ(quads_of(wide.mesh), quads_of(narrow.mesh));  // the quads are the same
  const LayerQuads converted = run_conversion(layer, "ball", 0, o, {card}, 64);
  ASSERT_FALSE(converted.texture.empty());
  EXPECT_GT(side(run_conversion(layer, "ball", 0, o, {card})), 64);
  EXPECT_LE(side(converted), 64);
}

// The conversion filter's quads are its result, as `quadsimp convert`'s are: pairs greedy
// pairing would not make are re-paired where the pairing allows, and the log says how many
// are left. The simplification starts from the plain pairing, as the CLI's does.
TEST(PluginRunner, the_conversion_keeps_its_quads_convex_where_it_can) {
  const TriMesh t = jittered(tri_sphere(24, 36), 0.04, 1);
  const MeshFile layer{t.positions, t.faces, {}};
  Outcome o;
  const QuadMesh q = run_conversion(layer, "noisy", 0, o).mesh;
  const Input plain = prepare_input(layer, "noisy", convert_options(SimplifyParams()));
  EXPECT_LT(quad_quality(q).nonconvex_faces, quad_quality(plain.quads).nonconvex_faces);
  const auto said = std::find_if(o.log.begin(), o.log.end(), [](const std::string& line) {
    return line.find("quads non-convex or bent over 60 degrees, after") != std::string::npos;
  });
  ASSERT_NE(said, o.log.end());
  EXPECT_LE(double(quad_quality(q).nonconvex_faces), std::stod(said->substr(said->find(": ") + 2)));
}

TEST(PluginRunner, a_crease_angle_reaches_the_conversion_and_the_simplification) {
  // A cube: its edges are kept with the crease angle (its corners stay corners of the
  // quads), the CLI's way, and rounded off without.
  const TriMesh t = tri_cube(12);
  const MeshFile layer{t.positions, t.faces, {}};
  auto corners = [](const QuadMesh& q) {
    int n = 0;
    for (Index v = 0; v < q.vertex_capacity(); ++v) {
      int sides = 0;
      for (int k = 0; k < 3; ++k) sides += q.position(v)[k] == 0.0 || q.position(v)[k] == 1.0;
      n += q.is_vertex_live(v) && sides == 3;
    }
    return n;
  };
  SimplifyParams params;
  params.target_faces = 100;
  for (double angle : {0.0, 30.0}) {
    params.crease_angle = angle;
    Outcome o;
    const QuadMesh q = run_simplification(layer, "cube", params, {}, o).mesh;
    EXPECT_EQ(corners(q), angle > 0 ? 8 : 0);
    Input in = prepare_input(layer, "cube", convert_options(params));
    const ReferenceSurface ref(std::move(in.reference));
    simplify_input(in, ref, params);
    EXPECT_EQ(quads_of(in.quads), quads_of(q));
  }
  // The conversion: a roof's ridge at 24 degrees is paired across without a crease angle.
  TriMesh roof = tri_grid(9, 9);
  for (Vec3& p : roof.positions) p.z() = 0.15 * (1 - std::abs(p.x() + p.y() - 1));
  Outcome plain, kept;
  const Index across = run_conversion({roof.positions, roof.faces, {}}, "roof", 0, plain).mesh.n_faces();
  const Index apart = run_conversion({roof.positions, roof.faces, {}}, "roof", 15, kept).mesh.n_faces();
  EXPECT_EQ(across, 81u);
  EXPECT_EQ(apart, 82u);  // a ridge edge split: 81 triangles on either side
  EXPECT_THROW(run_conversion({roof.positions, roof.faces, {}}, "roof", 180, kept), std::invalid_argument);
}

}  // namespace
