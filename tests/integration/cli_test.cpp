// quadsimp: adaptive quad mesh simplification. SPDX-License-Identifier: GPL-3.0-or-later
// Runs the real quadsimp binary: exit codes, messages, and what lands on disk.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fixtures/shapes.h"
#include "quadsimp/io/images.h"
#include "quadsimp/io/load_input.h"
#include "quadsimp/io/mesh_io.h"
#include "quadsimp/mesh/quad_geometry.h"
#include "quadsimp/metrics/metrics.h"

using namespace qs;
namespace fs = std::filesystem;

namespace {

struct CliRun {
  int code;
  std::string out;  // stdout and stderr together
};

CliRun capture(const std::string& command) {
  CliRun r{-1, {}};
  FILE* p = ::popen(command.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  while (std::size_t n = std::fread(buf, 1, sizeof buf, p)) r.out.append(buf, n);
  const int status = ::pclose(p);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Under timeout(1), so that a run that never ends fails its test (code 124) instead of the suite.
CliRun run(const std::string& args) {
  return capture("timeout 600 " + fixtures::cli_path() + " " + args + " 2>&1");
}

// The same on a terminal: script(1) (util-linux, on every Debian) gives the command a
// pseudo-terminal and copies what it writes there.
CliRun run_on_terminal(const std::string& args) {
  return capture("script -qec '" + fixtures::cli_path() + " " + args + "' /dev/null");
}

// One per-vertex property of a binary little-endian PLY file, as floats (empty if the
// file has no such property): the fields `quadsimp fitmap` writes.
std::vector<float> ply_vertex_property(const std::string& path, const std::string& name) {
  std::ifstream in(path, std::ios::binary);
  const std::map<std::string, int> sizes = {{"char", 1}, {"uchar", 1}, {"short", 2}, {"ushort", 2},
                                            {"int", 4},  {"uint", 4},  {"float", 4}, {"double", 8}};
  std::size_t count = 0, stride = 0, offset = 0;
  std::string line, type, found_type;
  bool in_vertex = false;
  while (std::getline(in, line) && line != "end_header") {
    std::istringstream words(line);
    std::string word, element;
    words >> word;
    if (word == "element") {
      words >> element;
      in_vertex = element == "vertex";
      if (in_vertex) words >> count;
    } else if (word == "property" && in_vertex) {
      std::string property;
      words >> type >> property;
      if (property == name) offset = stride, found_type = type;
      stride += sizes.at(type);
    }
  }
  if (found_type != "float") return {};
  std::vector<char> data(count * stride);
  in.read(data.data(), std::streamsize(data.size()));
  std::vector<float> values(count);
  for (std::size_t i = 0; i < count; ++i) std::memcpy(&values[i], &data[i * stride + offset], sizeof(float));
  return values;
}

// The number a JSON object gives `key` (NaN without one, which fails any comparison).
double json_number(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\": ");
  return at == std::string::npos ? std::nan("") : std::stod(json.substr(at + key.size() + 4));
}

// The indices of a JSON object's "flawed_faces" list (empty without one).
std::vector<std::size_t> flawed_faces_in(const std::string& json) {
  std::vector<std::size_t> ids;
  const std::string key = "\"flawed_faces\": [";
  const std::size_t at = json.find(key);
  if (at == std::string::npos) return ids;
  std::istringstream in(json.substr(at + key.size(), json.find(']', at) - at - key.size()));
  for (std::string id; std::getline(in, id, ',');) ids.push_back(std::stoul(id));
  return ids;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("qs_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    input_ = p("sphere.ply");
    write_tri_mesh_ply(input_, fixtures::tri_sphere(10, 12));
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string p(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(p(name)) << text;
    return p(name);
  }
  std::string read(const std::string& name) const {
    std::ifstream in(p(name), std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  fs::path dir_;
  std::string input_;
};

}  // namespace

TEST_F(Cli, help_for_every_subcommand) {
  EXPECT_EQ(run("--help").code, 0);
  for (const char* command : {"convert", "simplify", "fitmap", "stats"}) {
    const CliRun r = run(std::string(command) + " --help");
    EXPECT_EQ(r.code, 0) << command;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << command << ": " << r.out;
  }
  EXPECT_NE(run("simplify --help").out.find("--adaptive"), std::string::npos);
}

TEST_F(Cli, convert_writes_quads) {
  for (const char* ext : {"ply", "obj", "off"}) {
    const std::string out = p(std::string("out.") + ext);
    const CliRun r = run("convert " + input_ + " " + out);
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("quads"), std::string::npos);
    const MeshFile f = read_mesh(out);
    EXPECT_TRUE(f.is_pure_quad());
  }
}

// `convert` writes quads for their own sake: the pairs greedy pairing would not make
// (non-convex, or bent over 60 degrees) are re-paired where the pairing allows, and it says
// how many are left. The simplifier starts from the plain pairing, with more of them.
TEST_F(Cli, convert_keeps_its_quads_convex_where_it_can_and_says_how_many_are_not) {
  const std::string in = p("noisy.ply");
  write_tri_mesh_ply(in, fixtures::jittered(fixtures::tri_sphere(24, 36), 0.04, 1));
  const CliRun r = run("convert " + in + " " + p("q.ply"));
  ASSERT_EQ(r.code, 0) << r.out;
  const std::size_t at = r.out.find(" non-convex or bent over 60 degrees, after ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const double left = std::stod(r.out.substr(r.out.rfind("; ", at) + 2));
  const CliRun s = run("stats " + in + " " + p("q.ply") + " --json --samples 1000");
  ASSERT_EQ(s.code, 0) << s.out;
  const double nonconvex = json_number(s.out, "nonconvex_faces");
  EXPECT_LE(nonconvex, left);
  EXPECT_LT(nonconvex, quad_quality(load_input(in).quads).nonconvex_faces);
}

// A PLY's vertex colours reach the quads (each vertex the colour at its closest point on
// the input, as the MeshLab filters give it), in every format written; a mesh without
// colours gives quads without.
TEST_F(Cli, vertex_colours_reach_the_quads) {
  const TriMesh sphere = fixtures::tri_sphere(24, 32);
  std::string ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(sphere.n_vertices()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\n"
                    "property uchar green\nproperty uchar blue\nelement face " +
                    std::to_string(sphere.n_faces()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  // Red along x, green along y, over the unit sphere's [-1, 1].
  const auto shade = [](double t) { return std::lround(127.5 * (t + 1)); };
  for (const Vec3& v : sphere.positions)
    ply += std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + " " +
           std::to_string(shade(v.x())) + " " + std::to_string(shade(v.y())) + " 0\n";
  for (const auto& f : sphere.faces)
    ply += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
  const std::string in = write("coloured.ply", ply);
  // The last run takes the converted quads (a pure quad input, kept apart from its quads).
  struct Run {
    std::string command, input, output, options;
  };
  const Run runs[] = {{"simplify", in, p("simplify.ply"), "--faces 150"},
                      {"convert", in, p("convert.ply"), ""},
                      {"simplify", p("convert.ply"), p("quads.ply"), "--faces 100"}};
  for (const Run& c : runs) {
    const std::string command = c.command + " " + c.input + " " + c.output + " " + c.options + " -q";
    const CliRun r = run(command);
    ASSERT_EQ(r.code, 0) << r.out;
    const MeshFile f = read_mesh(c.output);
    ASSERT_EQ(f.colours.size(), f.positions.size()) << command;
    double worst = 0;
    for (std::size_t i = 0; i < f.positions.size(); ++i) {
      const Vec3& x = f.positions[i];
      worst = std::max({worst, std::abs(f.colours[i][0] - 127.5 * (x.x() + 1)),
                        std::abs(f.colours[i][1] - 127.5 * (x.y() + 1))});
      EXPECT_EQ(f.colours[i][2], 0);
      EXPECT_EQ(f.colours[i][3], 255);
    }
    // Quads over a sphere of 24 x 32 cells: their vertices lie on its triangles, whose
    // colours vary linearly between corners a few units of 255 apart.
    EXPECT_LT(worst, 3.0) << command;
  }
  ASSERT_EQ(run("simplify " + in + " " + p("out.obj") + " --faces 150 -q").code, 0);
  ASSERT_EQ(run("simplify " + in + " " + p("out.off") + " --faces 150 -q").code, 0);
  const std::string obj = read("out.obj"), off = read("out.off");
  const std::size_t v_at = obj.find("\nv ") + 1;
  const std::string first_v = obj.substr(v_at, obj.find('\n', v_at) - v_at);
  EXPECT_EQ(std::count(first_v.begin(), first_v.end(), ' '), 6) << first_v;  // v x y z r g b
  EXPECT_EQ(off.rfind("COFF", 0), 0u);
  ASSERT_EQ(run("simplify " + input_ + " " + p("plain.ply") + " --faces 60 -q").code, 0);
  const MeshFile plain = read_mesh(p("plain.ply"));
  EXPECT_TRUE(plain.colours.empty());
  EXPECT_FALSE(plain.has_face_colours());
  EXPECT_EQ(read("plain.ply").find("red"), std::string::npos);
}

// A PLY's face colours reach the quads (each quad the colour of the input face closest
// to its centre), in every format written (OBJ's as materials in a file beside it).
TEST_F(Cli, face_colours_reach_the_quads) {
  const TriMesh sphere = fixtures::tri_sphere(24, 32);
  std::string ply = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(sphere.n_vertices()) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                    std::to_string(sphere.n_faces()) +
                    "\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\n"
                    "property uchar blue\nend_header\n";
  for (const Vec3& v : sphere.positions)
    ply += std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
  // The northern half red, the southern half blue.
  for (const auto& f : sphere.faces) {
    const bool north = sphere.positions[f[0]].z() + sphere.positions[f[1]].z() + sphere.positions[f[2]].z() > 0;
    ply += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
           (north ? " 255 0 0\n" : " 0 0 255\n");
  }
  const std::string in = write("faces.ply", ply);
  // The last run takes the converted quads: face colours read from OFF and carried on,
  // then written to OBJ.
  const std::pair<std::string, std::string> runs[] = {
      {"simplify " + in + " " + p("s.ply") + " --faces 150", p("s.ply")},
      {"convert " + in + " " + p("c.off"), p("c.off")},
      {"simplify " + p("c.off") + " " + p("a.obj") + " --adaptive --auto-halt", p("a.obj")}};
  for (const auto& [command, output] : runs) {
    SCOPED_TRACE(command);
    ASSERT_EQ(run(command + " -q").code, 0);
    const MeshFile f = read_mesh(output);
    ASSERT_TRUE(f.triangle_colours.empty());
    ASSERT_EQ(f.quad_colours.size(), f.quads.size());
    // Quads across the equator may take either colour; the others their half's.
    std::size_t reds = 0, blues = 0;
    for (std::size_t i = 0; i < f.quads.size(); ++i) {
      double z = 0;
      for (Index v : f.quads[i]) z += f.positions[v].z() / 4;
      const Colour c = f.quad_colours[i];
      EXPECT_TRUE(c == (z > 0 ? Colour{255, 0, 0, 255} : Colour{0, 0, 255, 255}) || std::abs(z) < 0.2) << z;
      reds += c[0] == 255;
      blues += c[2] == 255;
    }
    EXPECT_EQ(reds + blues, f.quads.size());
    EXPECT_GT(std::min(reds, blues), f.quads.size() / 3);
  }
  EXPECT_TRUE(fs::exists(p("a.obj.mtl")));
}

// A texture (an OBJ's or a PLY's) reaches OBJ and PLY quads as one of their own: a tile
// per quad, each texel the input's texture under it. On a sphere mapped by longitude and height (a seam where the
// longitude wraps), with an image whose red is the longitude and green the height, the texel at each quad's middle has
// the colour of the point of the sphere under it. OFF takes no texture, and says so.
TEST_F(Cli, a_texture_reaches_obj_and_ply_quads) {
  const TriMesh sphere = fixtures::tri_sphere(24, 32);
  const auto lon_lat = [](const Vec3& p) {
    const Vec3 d = p.normalized();
    return TexCoord{float(std::atan2(d.y(), d.x()) / (2 * M_PI) + 0.5), float((d.z() + 1) / 2)};
  };
  // As OBJ (vt, a material's map_Kd) and as PLY (MeshLab's TextureFile and texcoord).
  std::string obj = "mtllib t.mtl\n", ply_vertices, ply_faces;
  for (const Vec3& v : sphere.positions) {
    const std::string xyz = std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + "\n";
    obj += "v " + xyz;
    ply_vertices += xyz;
  }
  obj += "usemtl lonlat\n";
  int vt = 0;
  for (const auto& f : sphere.faces) {
    // Corners across the seam take the longitude of the triangle's side of it.
    std::array<TexCoord, 3> uv;
    float lowest = 1, highest = 0;
    for (int k = 0; k < 3; ++k) {
      uv[k] = lon_lat(sphere.positions[f[k]]);
      lowest = std::min(lowest, uv[k][0]), highest = std::max(highest, uv[k][0]);
    }
    for (auto& c : uv)
      if (highest - lowest > 0.5f && c[0] < 0.5f) c[0] += 1;
    for (const TexCoord& c : uv) obj += "vt " + std::to_string(c[0]) + " " + std::to_string(c[1]) + "\n";
    obj += "f";
    ply_faces += "3";
    for (int k = 0; k < 3; ++k) {
      obj += " " + std::to_string(f[k] + 1) + "/" + std::to_string(vt + k + 1);
      ply_faces += " " + std::to_string(f[k]);
    }
    ply_faces += " 6";
    for (const TexCoord& c : uv) ply_faces += " " + std::to_string(c[0]) + " " + std::to_string(c[1]);
    obj += "\n";
    ply_faces += "\n";
    vt += 3;
  }
  const std::string in = write("lonlat.obj", obj);
  const std::string in_ply = write("lonlat.ply", "ply\nformat ascii 1.0\ncomment TextureFile lonlat.png\n"
                                                 "element vertex " + std::to_string(sphere.n_vertices()) +
                                                 "\nproperty float x\nproperty float y\nproperty float z\n"
                                                 "element face " + std::to_string(sphere.n_faces()) +
                                                 "\nproperty list uchar int vertex_indices\n"
                                                 "property list uchar float texcoord\nend_header\n" +
                                                 ply_vertices + ply_faces);
  write("t.mtl", "newmtl lonlat\nKd 1 1 1\nmap_Kd lonlat.png\n");
  Image image;
  image.width = 256, image.height = 256;
  for (int y = 0; y < 256; ++y)
    for (int x = 0; x < 256; ++x) image.rgba.insert(image.rgba.end(), {std::uint8_t(x), std::uint8_t(255 - y), 0, 255});
  write_png(p("lonlat.png"), image);

  const std::pair<std::string, std::string> runs[] = {
      {"simplify " + in + " " + p("u.obj") + " --faces 150", p("u.obj")},
      {"simplify " + in + " " + p("a.obj") + " --adaptive --auto-halt", p("a.obj")},
      {"convert " + in + " " + p("c.obj"), p("c.obj")},
      {"simplify " + in_ply + " " + p("p.obj") + " --faces 150", p("p.obj")},
      {"simplify " + in + " " + p("q.ply") + " --faces 150", p("q.ply")}};
  for (const auto& [command, output] : runs) {
    SCOPED_TRACE(command);
    const CliRun r = run(command);
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("not carried"), std::string::npos) << r.out;
    const MeshFile f = read_mesh(output);
    ASSERT_EQ(f.texture.triangles.size(), 2 * f.quads.size());
    ASSERT_EQ(f.texture.images, std::vector<std::string>{texture_path_of(output)});
    const Image baked = read_image(f.texture.images[0]);
    std::size_t checked = 0;
    for (std::size_t i = 0; i < f.quads.size(); ++i) {
      // The middle of the tile is the middle of the quad's diagonal 0-2 (its first triangle's
      // corners 0 and 2), as the fan splits it.
      const auto& c = f.texture.coords[2 * i];
      const auto& t = f.texture.triangles[2 * i];
      const Vec3 mid = (f.positions[t[0]] + f.positions[t[2]]) / 2;
      const TexCoord want = lon_lat(mid);
      // At the seam either side's red; at the poles the input's own longitudes are skewed.
      if (want[0] < 0.05f || want[0] > 0.95f || std::abs(mid.normalized().z()) > 0.9) continue;
      const int x = int((c[0][0] + c[2][0]) / 2 * float(baked.width));
      const int y = int((1 - (c[0][1] + c[2][1]) / 2) * float(baked.height));
      const std::uint8_t* got = &baked.rgba[4 * std::size_t(y * baked.width + x)];
      EXPECT_NEAR(got[0], 256 * want[0] - 0.5, 6) << "quad " << i << " at " << mid.transpose();
      EXPECT_NEAR(got[1], 256 * want[1] - 0.5, 6) << "quad " << i << " at " << mid.transpose();
      ++checked;
    }
    EXPECT_GT(checked, f.quads.size() / 2);  // the others lie at a pole or the seam
  }
  // An output whose texture would be written over the input's image is refused, and the
  // image is left as it was.
  std::string globe = read("lonlat.ply");
  globe.replace(globe.find("lonlat.png"), 10, "globe_texture.png");
  const std::string image_before = read("lonlat.png");
  write("globe_texture.png", image_before);
  const CliRun clash = run("simplify " + write("globe.ply", globe) + " " + p("globe.obj") + " --faces 150");
  EXPECT_EQ(clash.code, 2) << clash.out;
  EXPECT_NE(clash.out.find("would be written over the input's texture image"), std::string::npos) << clash.out;
  EXPECT_EQ(read("globe_texture.png"), image_before);
  EXPECT_FALSE(fs::exists(p("globe.obj")));
  const CliRun convert_clash = run("convert " + p("globe.ply") + " " + p("globe.obj"));  // checked on its own
  EXPECT_EQ(convert_clash.code, 2) << convert_clash.out;
  EXPECT_NE(convert_clash.out.find("quadsimp convert: the quads' texture"), std::string::npos) << convert_clash.out;
  EXPECT_EQ(read("globe_texture.png"), image_before);
  EXPECT_FALSE(fs::exists(p("globe.obj")));
  // --texture-size bounds the atlas (and is refused out of its range).
  ASSERT_EQ(run("simplify " + in + " " + p("small.obj") + " --faces 150 --texture-size 64 -q").code, 0);
  const Image small = read_image(texture_path_of(p("small.obj")));
  EXPECT_LE(std::max(small.width, small.height), 64);
  EXPECT_GE(std::max(small.width, small.height), 13 * 3);  // 13 tiles a row, of 3 texels at least
  // A size the quads' least tiles cannot keep to is passed, and the log says so.
  const CliRun tiny = run("simplify " + in + " " + p("tiny.obj") + " --faces 150 --texture-size 16");
  ASSERT_EQ(tiny.code, 0) << tiny.out;
  const Image over = read_image(texture_path_of(p("tiny.obj")));
  EXPECT_GT(std::max(over.width, over.height), 16);
  EXPECT_NE(tiny.out.find("tiny.obj: the quads' texture is " + std::to_string(over.width) + " x " +
                          std::to_string(over.height) + " texels, past the texture size of 16: too many quads"),
            std::string::npos)
      << tiny.out;
  const CliRun within = run("simplify " + in + " " + p("small2.obj") + " --faces 150 --texture-size 64");
  EXPECT_EQ(within.out.find("past the texture size"), std::string::npos) << within.out;
  EXPECT_EQ(run("convert " + in + " " + p("c2.obj") + " --texture-size 8").code, 2);
  const CliRun r = run("simplify " + in + " " + p("plain.off") + " --faces 150");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("OFF keeps no texture; the input's is written with .obj or .ply output"), std::string::npos)
      << r.out;
  EXPECT_FALSE(fs::exists(p("plain_texture.png")));
}

// An OBJ textured in part (a material with an image on the left half of a grid, one with
// only a Kd on the right half) keeps both on its quads: the atlas shows the image on the
// left and the colour on the right.
TEST_F(Cli, an_obj_textured_in_part_keeps_its_colours_beside_its_texture) {
  const int n = 10;
  std::string obj = "mtllib m.mtl\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      obj += "v " + std::to_string(double(i) / n) + " " + std::to_string(double(j) / n) + " 0\nvt 0.5 0.5\n";
  for (const bool textured : {true, false}) {
    obj += textured ? "usemtl image\n" : "usemtl red\n";
    const auto corner = [&](int v) { return " " + std::to_string(v) + (textured ? "/" + std::to_string(v) : ""); };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const int a = j * (n + 1) + i + 1;
        if ((i < n / 2) == textured)
          obj += "f" + corner(a) + corner(a + 1) + corner(a + n + 2) + corner(a + n + 1) + "\n";
      }
  }
  const std::string in = write("part.obj", obj);
  write("m.mtl", "newmtl image\nKd 1 1 1\nmap_Kd blue.png\nnewmtl red\nKd 1 0 0\n");
  Image blue;
  blue.width = blue.height = 4;
  for (int k = 0; k < 16; ++k) blue.rgba.insert(blue.rgba.end(), {0, 0, 255, 255});
  write_png(p("blue.png"), blue);
  const CliRun r = run("simplify " + in + " " + p("q.obj") + " --faces 20");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out.find("not carried"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("part.obj: 100 of its 200 triangles have no texture (no coordinates, or a material without an "
                       "image): the quads' texture shows their face colour there"),
            std::string::npos)
      << r.out;
  const MeshFile f = read_mesh(p("q.obj"));
  ASSERT_FALSE(f.texture.empty());
  const Image baked = read_image(f.texture.images[0]);
  int left = 0, right = 0;
  for (std::size_t t = 0; t < f.texture.triangles.size(); ++t) {
    double x = 0, u = 0, v = 0;
    for (int k = 0; k < 3; ++k) {
      x += f.positions[f.texture.triangles[t][std::size_t(k)]].x() / 3;
      u += f.texture.coords[t][std::size_t(k)][0] / 3, v += f.texture.coords[t][std::size_t(k)][1] / 3;
    }
    if (std::abs(x - 0.5) < 0.2) continue;  // quads across the middle hold both
    const std::size_t row = std::size_t((1 - v) * baked.height), column = std::size_t(u * baked.width);
    const std::size_t at = 4 * (row * std::size_t(baked.width) + column);
    const Colour c{baked.rgba[at], baked.rgba[at + 1], baked.rgba[at + 2], baked.rgba[at + 3]};
    EXPECT_EQ(c, x < 0.5 ? (Colour{0, 0, 255, 255}) : (Colour{255, 0, 0, 255})) << x;
    ++(x < 0.5 ? left : right);
  }
  EXPECT_GT(std::min(left, right), 4);

  // Where the texture is not written (OFF; an image that cannot be read), the faces keep
  // their colours as face colours, the textured ones their material's.
  for (const std::string out : {"q.off", "no_image.obj"}) {
    SCOPED_TRACE(out);
    if (out == "no_image.obj") fs::remove(p("blue.png"));
    const CliRun again = run("simplify " + in + " " + p(out) + " --faces 20");
    ASSERT_EQ(again.code, 0) << again.out;
    EXPECT_NE(again.out.find(": its quads take the colours of the input's faces instead"), std::string::npos)
        << again.out;
    const MeshFile q = read_mesh(p(out));
    EXPECT_TRUE(q.texture.empty());
    ASSERT_EQ(q.quad_colours.size(), q.quads.size());
    int white = 0, red = 0;
    for (std::size_t f = 0; f < q.quads.size(); ++f) {
      double x = 0;
      for (Index v : q.quads[f]) x += q.positions[v].x() / 4;
      if (std::abs(x - 0.5) < 0.2) continue;
      EXPECT_EQ(q.quad_colours[f], x < 0.5 ? (Colour{255, 255, 255, 255}) : (Colour{255, 0, 0, 255})) << x;
      ++(x < 0.5 ? white : red);
    }
    EXPECT_GT(std::min(white, red), 2);
  }
}

// Texture coordinates without an image for every face are not carried: the log says so,
// and names MeshLab's transfer.
TEST_F(Cli, texture_coordinates_left_behind_are_logged) {
  const std::string obj = write("t.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\n"
                                         "f 1/1 2/2 3/2\nf 1/1 3/2 4/1\n");
  const CliRun r = run("convert " + obj + " " + p("t.ply"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("its texture coordinates are not carried to the quads (not every face has coordinates and "
                       "an image); MeshLab's \"Transfer: Texture to Vertex Color"), std::string::npos) << r.out;
  EXPECT_EQ(run("convert " + input_ + " " + p("s.ply")).out.find("not carried"), std::string::npos);
}

TEST_F(Cli, bad_arguments_exit_2) {
  EXPECT_EQ(run("").code, 2);
  EXPECT_EQ(run("convert").code, 2);
  EXPECT_EQ(run("convert " + input_).code, 2);
  EXPECT_EQ(run("convert " + p("nope.ply") + " " + p("o.ply")).code, 2);
  EXPECT_EQ(run("convert " + input_ + " " + p("o.stl")).code, 2);
  EXPECT_EQ(run("frobnicate").code, 2);
  // Numbers out of range say what is wanted (CLI11's own check printed the largest
  // double in 309 digits).
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"simplify " + input_ + " " + p("o.ply") + " --faces 0", "--faces: '0' is not a whole number from 1"},
           {"simplify " + input_ + " " + p("o.ply") + " --faces 2.5", "--faces: '2.5' is not a whole number from 1"},
           {"simplify " + input_ + " " + p("o.ply") + " --faces 0%", "--faces: '0%' is not a share above 0%"},
           {"simplify " + input_ + " " + p("o.ply") + " --adaptive",
            "the adaptive mode needs a target number of faces or automatic halting"},
           {"simplify " + input_ + " " + p("o.ply") + " --faces 100.5%",
            "'100.5%' is not a share above 0% and at most 100%"},
           {"simplify " + input_ + " " + p("o.ply") + " --faces ten%", "--faces: 'ten%' is not a share"},
           {"simplify " + input_ + " " + p("o.ply") + " --faces 10 --m-factor 0",
            "--m-factor: '0' is not a number above 0"},
           {"stats " + input_ + " " + input_ + " --samples 0", "--samples: '0' is not a whole number from 1"}}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
    EXPECT_LT(r.out.size(), 200u) << r.out;
  }
  // Never over the input, and the input is untouched; fitmaps go to PLY only.
  const auto before = fs::file_size(input_);
  for (const std::string command : {"convert", "simplify", "fitmap"}) {
    const CliRun r = run(command + " " + input_ + " " + input_ + (command == "simplify" ? " --faces 10" : ""));
    EXPECT_EQ(r.code, 2) << command;
    EXPECT_NE(r.out.find("quadsimp " + command + ": "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("over the input"), std::string::npos) << r.out;
  }
  EXPECT_EQ(fs::file_size(input_), before);
  const CliRun r = run("fitmap " + input_ + " " + p("f.obj"));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("quadsimp fitmap: the output must be a .ply file"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(p("f.obj")));
}

// --faces P% asks for that share of the quads the input converts to, in either mode; with
// automatic halting it is refused like a count.
TEST_F(Cli, faces_as_a_share_of_the_input) {
  ASSERT_EQ(run("convert " + input_ + " " + p("c.ply") + " -q").code, 0);
  const long quads = long(read_mesh(p("c.ply")).quads.size());
  ASSERT_GT(quads, 100);
  for (const std::string mode : {"", " --adaptive"}) {
    const CliRun r = run("simplify " + input_ + " " + p("s.ply") + " --faces 62.5% --json -q --samples 1000" + mode);
    ASSERT_EQ(r.code, 0) << r.out;
    const auto number = [&r](const std::string& key) { return json_number(r.out, key); };
    EXPECT_EQ(number("faces"), double(std::lround(0.625 * double(quads)))) << mode;
    EXPECT_EQ(number("target_faces"), number("faces"));
    // The share is of the quads the input converts to (converted_faces), which input_faces,
    // counted after the loop's first doublet cleaning, may be under.
    EXPECT_EQ(number("converted_faces"), double(quads));
    EXPECT_LE(number("input_faces"), double(quads));
  }
  const CliRun r = run("simplify " + input_ + " " + p("s.ply") + " --faces 10% --adaptive --auto-halt");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.out.find("give either a target number of faces or automatic halting"), std::string::npos) << r.out;
}

// --edge-length L asks for the quads of about that edge that cover the surface (its area over
// L squared), in either mode; it is refused beside another target.
TEST_F(Cli, faces_from_an_edge_length) {
  const TriMesh sphere = fixtures::tri_sphere(40, 48);
  const std::string in = p("fine.ply");
  write_tri_mesh_ply(in, sphere);
  const long want = std::lround(surface_area(sphere) / (0.2 * 0.2));
  ASSERT_GT(want, 200);
  for (const std::string mode : {"", " --adaptive"}) {
    const CliRun r = run("simplify " + in + " " + p("e.ply") + " --edge-length 0.2 --json --samples 1000" + mode);
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("a target of " + std::to_string(want) + " quads"), std::string::npos) << r.out;
    const auto number = [&r](const std::string& key) { return json_number(r.out, key); };
    EXPECT_EQ(number("target_faces"), double(want)) << mode;
    EXPECT_EQ(number("faces"), double(want)) << mode;
    // Near-square quads: the mean edge comes out near the one asked for (1.002 measured
    // in uniform mode; adaptive mode's sizes vary around their mean).
    EXPECT_NEAR(number("mean_edge"), 0.2, 0.01) << mode;
  }
  // With --remesh the remeshing makes enough triangles for that count: a strip of 10 by
  // 0.5 remeshed at its default edge (1% of its diagonal, 0.1) gives 600 quads, under the
  // 781 asked for.
  TriMesh grid = fixtures::tri_grid(100, 5);
  for (Vec3& x : grid.positions) x = Vec3(10 * x.x(), 0.5 * x.y(), x.z());
  const std::string strip = p("strip.ply");
  write_tri_mesh_ply(strip, grid);
  const CliRun remeshed =
      run("simplify " + strip + " " + p("r.ply") + " --edge-length 0.08 --remesh --json --samples 1000");
  ASSERT_EQ(remeshed.code, 0) << remeshed.out;
  EXPECT_NE(remeshed.out.find("\"faces\": 781,"), std::string::npos) << remeshed.out;
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {" --edge-length 0.2 --faces 100", "--faces excludes --edge-length"},
           {" --edge-length 0", "--edge-length: '0' is not a number above 0"},
           {" --edge-length 0.2 --adaptive --auto-halt",
            "give either a target number of faces or automatic halting, not both"}}) {
    const CliRun r = run("simplify " + in + " " + p("x.ply") + args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
  }
  EXPECT_FALSE(fs::exists(p("x.ply")));
}

// Several values of --faces (counts or shares) or --edge-length give levels of detail in one
// run, most quads first, each in OUT with its count before the extension; a JSON line each.
TEST_F(Cli, levels_of_detail_in_one_run) {
  const TriMesh sphere = fixtures::tri_sphere(40, 48);
  const std::string in = p("fine.ply");
  write_tri_mesh_ply(in, sphere);
  ASSERT_EQ(run("convert " + in + " " + p("c.ply") + " -q").code, 0);
  const long quads = long(read_mesh(p("c.ply")).quads.size());
  const long share = std::lround(0.1 * double(quads));
  ASSERT_LT(share, 300);
  fs::create_directories(p("lod"));
  for (const std::string mode : {"", " --adaptive"}) {
    const CliRun r = run("simplify " + in + " " + p("lod/s.obj") + " --faces 300,10%,600 --json --samples 1000" + mode);
    ASSERT_EQ(r.code, 0) << r.out;
    std::istringstream lines(r.out);
    std::vector<std::string> json;
    for (std::string line; std::getline(lines, line);)
      if (line.rfind("{", 0) == 0) json.push_back(line);
    ASSERT_EQ(json.size(), 3u) << r.out;
    const std::vector<long> counts = {600, 300, share};
    double seconds = 0;
    for (std::size_t i = 0; i < counts.size(); ++i) {
      SCOPED_TRACE(counts[i]);
      EXPECT_EQ(json_number(json[i], "target_faces"), double(counts[i]));
      EXPECT_EQ(json_number(json[i], "faces"), double(counts[i]));
      EXPECT_EQ(json_number(json[i], "converted_faces"), double(quads));
      // Each level's loop starts from the one before's quads.
      EXPECT_EQ(json_number(json[i], "input_faces"), i == 0 ? json_number(json[0], "input_faces") : counts[i - 1]);
      EXPECT_GE(json_number(json[i], "seconds"), seconds);
      seconds = json_number(json[i], "seconds");
      EXPECT_EQ(read_mesh(p("lod/s_" + std::to_string(counts[i]) + ".obj")).quads.size(), std::size_t(counts[i]));
    }
    EXPECT_FALSE(fs::exists(p("lod/s.obj")));
  }
  // Edge lengths the same way, the log giving each count.
  const long fine = std::lround(surface_area(sphere) / (0.2 * 0.2)), coarse = std::lround(surface_area(sphere) / 0.16);
  CliRun r = run("simplify " + in + " " + p("e.ply") + " --edge-length 0.4,0.2");
  ASSERT_EQ(r.code, 0) << r.out;
  for (const long n : {fine, coarse}) {
    EXPECT_NE(r.out.find("a target of " + std::to_string(n) + " quads"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" -> " + p("e_" + std::to_string(n) + ".ply") + ": " + std::to_string(n) + " faces"),
              std::string::npos)
        << r.out;
  }
  EXPECT_LT(r.out.find("e_" + std::to_string(fine)), r.out.find("e_" + std::to_string(coarse))) << r.out;
  // Either option before IN and OUT takes one word (a list option would take them too), and
  // given twice adds levels.
  r = run("simplify --edge-length 0.4 " + in + " " + p("before.ply") + " -q");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(read_mesh(p("before.ply")).quads.size(), std::size_t(coarse));
  r = run("simplify --faces 300 --faces 200 " + in + " " + p("twice.ply") + " -q");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(read_mesh(p("twice_200.ply")).quads.size(), 200u);
  // A level's notes name its file (a closed sphere cannot come down to 1 quad).
  r = run("simplify " + in + " " + p("t.ply") + " --faces 300,1");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: " + p("t_1.ply") + ": stopped at "), std::string::npos) << r.out;
  // One level writes OUT itself, as before.
  r = run("simplify " + in + " " + p("one.ply") + " --faces 300 -q");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(read_mesh(p("one.ply")).quads.size(), 300u);
  EXPECT_FALSE(fs::exists(p("one_300.ply")));
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {" --faces 300,300", "two levels ask for 300 quads"},
           {" --faces 10%,600," + std::to_string(share), "two levels ask for " + std::to_string(share) + " quads"},
           {" --faces ''", "--faces: '' is not a whole number from 1"},
           {" --faces 300,0", "--faces: '0' is not a whole number from 1"},
           {" --edge-length 0.2,0", "--edge-length: '0' is not a number above 0"},
           {" --faces 300,200 --adaptive --auto-halt", "automatic halting, not both"}}) {
    r = run("simplify " + in + " " + p("x.ply") + args);
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_NE(r.out.find(message), std::string::npos) << args << ": " << r.out;
  }
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().rfind("x", 0), std::string::npos) << entry.path();
}

TEST_F(Cli, simplify_stats_and_fitmap) {
  const std::string out = p("s.ply");
  CliRun r = run("simplify " + input_ + " " + out + " --faces 60 --stats --samples 2000");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("60 faces"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("Hausdorff"), std::string::npos);
  EXPECT_NE(r.out.find("(0 on the border, in 0 loops)"), std::string::npos) << r.out;  // a closed sphere
  r = run("stats " + input_ + " " + out + " --json --samples 2000");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("\"faces\": 60"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"border_loops\": 0"), std::string::npos) << r.out;
  r = run("stats " + input_ + " " + out + " --samples 2000");  // the same, as text
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("faces 60, vertices 62 (0 on the border, in 0 loops), pure quad: yes"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("projectability"), std::string::npos) << r.out;
  r = run("stats " + input_ + " " + input_);  // triangles: not a quad mesh
  EXPECT_EQ(r.code, 1);
  // A quad file converts to itself.
  r = run("convert " + out + " " + p("again.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("already pure quad, 60 quads written to " + p("again.obj")), std::string::npos) << r.out;
  EXPECT_EQ(read_mesh(p("again.obj")).quads.size(), 60u);
  r = run("fitmap " + input_ + " " + p("f.ply") + " -q");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(p("f.ply")));
  // Parameter combinations that make no sense are bad arguments.
  EXPECT_EQ(run("simplify " + input_ + " " + out + " --auto-halt").code, 2);
  EXPECT_EQ(run("simplify " + input_ + " " + out).code, 2);
  EXPECT_EQ(run("simplify " + input_ + " " + out + " --adaptive --auto-halt --faces 10").code, 2);
  EXPECT_EQ(run("simplify " + input_ + " " + out + " --adaptive --auto-halt -q").code, 0);
}

// --threads caps the parallel parts (fitmaps, distance sampling, Embree's builds), before or
// after the subcommand's name, and changes no output: the moai's adaptive run, its fitmaps
// and its distances are byte for byte the same on one thread, on two and on the default.
TEST_F(Cli, threads_cap_the_parallel_parts_and_change_no_output) {
  const std::string moai = fixtures::shared_dataset("moai");
  if (moai.empty()) GTEST_SKIP() << "../shared/datasets not found";
  const std::string args = " simplify " + moai + " --adaptive --auto-halt --json --samples 20000 -q ";
  std::vector<std::string> json;
  for (const std::string& command :
       {"-j 1" + args + p("one.ply"), args + p("two.ply") + " --threads 2", args + p("all.ply")}) {
    const CliRun r = run(command);
    ASSERT_EQ(r.code, 0) << command << ": " << r.out;
    json.push_back(r.out);
  }
  // The cap in force, as TBB reports it: on the machine's own count without one.
  EXPECT_EQ(json_number(json[0], "threads"), 1) << json[0];
  EXPECT_EQ(json_number(json[1], "threads"), 2) << json[1];
  EXPECT_GE(json_number(json[2], "threads"), 1) << json[2];
  EXPECT_GT(read("one.ply").size(), 1000u);
  EXPECT_EQ(read("one.ply"), read("two.ply"));
  EXPECT_EQ(read("one.ply"), read("all.ply"));
  for (const std::string key : {"faces", "rms_e3", "hausdorff_e3", "projectability"})
    EXPECT_EQ(json_number(json[0], key), json_number(json[1], key)) << key;
  EXPECT_EQ(run("-j 1 fitmap " + moai + " " + p("f1.ply") + " -q").code, 0);
  EXPECT_EQ(run("fitmap " + moai + " " + p("f2.ply") + " -q --threads 2").code, 0);
  EXPECT_GT(read("f1.ply").size(), 1000u);
  EXPECT_EQ(read("f1.ply"), read("f2.ply"));
  const CliRun one = run("--threads 1 stats " + moai + " " + p("one.ply") + " --json --samples 20000");
  const CliRun two = run("stats " + moai + " " + p("one.ply") + " --json --samples 20000 -j 2");
  EXPECT_EQ(one.code, 0) << one.out;
  EXPECT_EQ(one.out, two.out);
  for (const std::string bad : {"-1", "1.5", "lots", "1025"}) {
    const CliRun r = run("--threads " + bad + " simplify " + moai + " " + p("x.ply") + " -f 100");
    EXPECT_EQ(r.code, 2) << bad;
    EXPECT_NE(r.out.find("--threads: '" + bad + "' is not a whole number from 0 to 1024"), std::string::npos)
        << r.out;
  }
  EXPECT_FALSE(fs::exists(p("x.ply")));
}

// A terminal sees each stage's bar, redrawn in place once per percent; a pipe (a log
// file, the tests above) sees none, and neither does --quiet.
TEST_F(Cli, a_terminal_gets_a_progress_bar_and_a_pipe_none) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "script(1) not found";
  const std::string args = "simplify " + input_ + " " + p("s.ply") + " --adaptive --faces 60";
  CliRun r = run_on_terminal(args);
  ASSERT_EQ(r.code, 0) << r.out;
  for (const char* stage : {"\rfitmaps    [", "\rsimplify   ["})
    EXPECT_NE(r.out.find(stage), std::string::npos) << r.out;
  EXPECT_EQ(run(args).out.find('\r'), std::string::npos);
  EXPECT_EQ(run_on_terminal(args + " -q").out.find('['), std::string::npos);
  // The loop reports every 256 collapses: 28,000 of them are more reports than percents.
  write_tri_mesh_ply(p("big.ply"), fixtures::tri_sphere(160, 180));
  r = run_on_terminal("simplify " + p("big.ply") + " " + p("s.ply") + " --faces 100");
  ASSERT_EQ(r.code, 0) << r.out;
  // The simplification's percentages, in the order drawn: each once, rising to 100.
  std::vector<int> drawn;
  for (std::size_t at = r.out.find("\rsimplify   ["); at != std::string::npos;
       at = r.out.find("\rsimplify   [", at + 1))
    drawn.push_back(std::stoi(r.out.substr(r.out.find('%', at) - 3, 3)));
  ASSERT_FALSE(drawn.empty());
  EXPECT_TRUE(std::adjacent_find(drawn.begin(), drawn.end(), std::greater_equal<int>()) == drawn.end())
      << ::testing::PrintToString(drawn);
  EXPECT_EQ(drawn.back(), 100);
  EXPECT_NE(r.out.find("[########################################] 100%"), std::string::npos) << r.out;
}

TEST_F(Cli, a_target_the_mesh_cannot_reach_is_reported) {
  // With its border kept, a grid cannot lose the faces along it.
  const std::string grid = p("grid.ply");
  write_tri_mesh_ply(grid, fixtures::tri_grid(12, 12));
  CliRun r = run("simplify " + grid + " " + p("g.ply") + " --faces 4 --preserve-boundary");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: stopped at "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("quads, above the target of 4: every remaining collapse was refused"), std::string::npos)
      << r.out;
  r = run("simplify " + grid + " " + p("g.ply") + " --faces 4 --preserve-boundary -q");
  EXPECT_EQ(r.out.find("above the target"), std::string::npos) << r.out;
  r = run("simplify " + input_ + " " + p("s.ply") + " --faces 60");
  EXPECT_EQ(r.out.find("above the target"), std::string::npos) << r.out;
  // A target above what the input converts to leaves nothing to do, and says so.
  r = run("simplify " + grid + " " + p("g.ply") + " --faces 100000");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: the target of 100000 quads is above the "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("the input converts to: nothing was simplified"), std::string::npos) << r.out;
  // Two quads sharing two edges round a vertex (a doublet) are one quad once cleaning has
  // merged them: the note counts what is left, not what was read.
  const std::string doublet =
      write("doublet.obj", "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nv 0.8 1.2 0\nf 1 2 3 5\nf 1 5 3 4\n");
  r = run("simplify " + doublet + " " + p("d.obj") + " --faces 2");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: the target of 2 quads is above the 1 left of the 2 the input converts to once their "
                       "doublets (two quads sharing two edges) are merged"),
            std::string::npos)
      << r.out;
}

TEST_F(Cli, a_cad_cone_keeps_a_quad_per_segment) {
  // A cone of an odd number of segments has a rim edge split, which the log reports; it
  // was merged down to two quads on four corners whatever the target.
  write_tri_mesh_ply(p("cone.ply"), fixtures::cad_cone(13));
  CliRun r = run("convert " + p("cone.ply") + " " + p("q.obj"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("28 triangles -> 14 quads"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("; cone rims split: 1)"), std::string::npos) << r.out;
  r = run("simplify " + p("cone.ply") + " " + p("s.obj") + " --faces 7");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(read_mesh(p("s.obj")).quads.size(), 14u) << r.out;
  EXPECT_NE(r.out.find("note: stopped at 14 quads, above the target of 7"), std::string::npos) << r.out;
}

TEST_F(Cli, remesh_makes_a_cad_cylinder_even_quads) {
  // One row of long triangles round its side, fans on its caps: as it is, the quads keep
  // the caps' poles and fold, and loading says to remesh.
  write_tri_mesh_ply(p("cyl.ply"), fixtures::cad_cylinder(64, 1, 2.0));
  CliRun r = run("simplify " + p("cyl.ply") + " " + p("a.obj") + " --faces 100");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("remesh first for even quads (quadsimp's --remesh;"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" folded "), std::string::npos) << r.out;
  r = run("simplify " + p("cyl.ply") + " " + p("b.obj") + " --faces 100 --remesh --json --samples 20000");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: " + p("cyl.ply") + ": remeshed 256 triangles into "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("edges of 1% of the diagonal"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("long, thin"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"faces\": 100,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"folded_faces\": 0,"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"max_valence\": 5,"), std::string::npos) << r.out;
  // The distances are from the file's own surface, as `stats` measures them: the same
  // samples on it (the other way, the quads read back are sampled in another order).
  const std::string rms = "\"rms_from_ref_e3\": ";
  const CliRun s = run("stats " + p("cyl.ply") + " " + p("b.obj") + " --json --samples 20000");
  ASSERT_EQ(s.code, 0) << s.out;
  auto rms_of = [&](const std::string& out) { return std::stod(out.substr(out.find(rms) + rms.size())); };
  EXPECT_DOUBLE_EQ(rms_of(r.out), rms_of(s.out)) << r.out << s.out;
  EXPECT_EQ(read_mesh(p("b.obj")).quads.size(), 100u);
  // convert too; --remesh-edge sets the length and needs --remesh.
  r = run("convert " + p("cyl.ply") + " " + p("c.obj") + " --remesh --remesh-edge 4");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("edges of 4% of the diagonal"), std::string::npos) << r.out;
  EXPECT_EQ(run("convert " + p("cyl.ply") + " " + p("d.obj") + " --remesh-edge 4").code, 2);
}

TEST_F(Cli, simplifies_a_non_orientable_surface_cut_open) {
  // A Moebius strip was refused; it is cut open across its twist on loading, and said so.
  write_tri_mesh_ply(p("moebius.ply"), fixtures::tri_moebius(96, 8));
  CliRun r = run("simplify " + p("moebius.ply") + " " + p("a.obj") + " --faces 150 --json --samples 20000");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: " + p("moebius.ply") + ": the surface is not orientable (a Moebius-like strip): cut "
                       "open along "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("the cut stays open, a border, in the quads"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\"faces\": 150,"), std::string::npos) << r.out;
  for (const char* none : {"\"nonconvex_faces\": 0,", "\"flipped_faces\": 0,", "\"folded_faces\": 0,"})
    EXPECT_NE(r.out.find(none), std::string::npos) << none << "\n" << r.out;
  EXPECT_EQ(read_mesh(p("a.obj")).quads.size(), 150u);
  // Adaptive mode, the conversion, the fitmaps and stats load it alike.
  for (const std::string& args :
       {"simplify " + p("moebius.ply") + " " + p("b.ply") + " --adaptive --auto-halt",
        "convert " + p("moebius.ply") + " " + p("c.ply"), "fitmap " + p("moebius.ply") + " " + p("d.ply"),
        "stats " + p("moebius.ply") + " " + p("a.obj") + " --samples 20000"}) {
    r = run(args);
    EXPECT_EQ(r.code, 0) << args << "\n" << r.out;
  }
}

TEST_F(Cli, automatic_halting_that_runs_out_of_collapses_says_so) {
  // Faces may not grow past F_M / 1000: every collapse is refused before any share of
  // the surface is added to what the M-fitmap blocks, so the rule never halts the run.
  CliRun r = run("simplify " + input_ + " " + p("a.ply") + " --adaptive --auto-halt --m-factor 1000");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: automatic halting stopped at 108 quads (the input converts to 108) before the "
                       "M-fitmap blocked its share of the surface: every remaining collapse was refused"),
            std::string::npos)
      << r.out;
  r = run("simplify " + input_ + " " + p("a.ply") + " --adaptive --auto-halt --m-factor 1000 -q");
  EXPECT_EQ(r.out.find("automatic halting stopped"), std::string::npos) << r.out;
  // The paper's rule runs until nothing is left: that is its halt, not a shortfall.
  r = run("simplify " + input_ + " " + p("a.ply") + " --adaptive --auto-halt --m-factor 1000 --halt-share 1");
  EXPECT_EQ(r.out.find("automatic halting stopped"), std::string::npos) << r.out;
}

TEST_F(Cli, the_reach_holds_quads_on_the_input_and_says_so) {
  // The M-fitmap made powerless (--m-factor 0.001), a sphere asked for 6 quads would be a
  // cube, its faces' centres far inside: the reach refuses that, and the note names it.
  const std::string args = "simplify " + input_ + " " + p("a.ply") + " --adaptive --faces 6 --m-factor 0.001";
  CliRun r = run(args);
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("0 M-fitmap; "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find(" 0 reach)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" reach)"), std::string::npos) << r.out;
  r = run(args + " --reach 0");
  EXPECT_NE(r.out.find(" 0 reach)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("stopped at 8 quads"), std::string::npos) << r.out;
  EXPECT_EQ(run(args + " --reach 2").code, 2);
}

TEST_F(Cli, the_m_slack_reaches_the_loop_for_faces_under_the_reach) {
  // With the bound at F_M / 1.5 the M-fitmap holds the sphere's faces (33 quads for a
  // target of 6). With the reach at the whole diagonal, above every face, a slack of 1.25
  // refuses what a bound of F_M / 1.2 does: the same file (19 quads); without the slack,
  // another. At the default reach those faces are larger than it, and without the reach
  // no face is under it: the slack leaves them alone, the same file as without it.
  const std::string args = "simplify " + input_ + " --adaptive --faces 6";
  ASSERT_EQ(run(args + " " + p("s.ply") + " --m-factor 1.5 --m-slack 1.25 --reach 1").code, 0);
  ASSERT_EQ(run(args + " " + p("f.ply") + " --m-factor 1.2 --m-slack 1 --reach 1").code, 0);
  ASSERT_EQ(run(args + " " + p("b.ply") + " --m-factor 1.5 --m-slack 1 --reach 1").code, 0);
  EXPECT_EQ(read("s.ply"), read("f.ply"));
  EXPECT_NE(read("s.ply"), read("b.ply"));
  ASSERT_EQ(run(args + " " + p("d.ply") + " --m-factor 1.5 --m-slack 1.25").code, 0);
  ASSERT_EQ(run(args + " " + p("e.ply") + " --m-factor 1.5 --m-slack 1").code, 0);
  EXPECT_EQ(read("d.ply"), read("e.ply"));
  ASSERT_EQ(run(args + " " + p("g.ply") + " --m-factor 1.5 --m-slack 1.25 --reach 0").code, 0);
  ASSERT_EQ(run(args + " " + p("h.ply") + " --m-factor 1.5 --m-slack 1 --reach 0").code, 0);
  EXPECT_EQ(read("g.ply"), read("h.ply"));
  EXPECT_EQ(run(args + " " + p("x.ply") + " --m-slack 0.5").code, 2);
}

TEST_F(Cli, faces_left_beyond_the_reach_are_reported) {
  // The paper's halting rule runs the smooth moai on to 38 quads, and the rotations and
  // smoothing after its collapses (not checked) leave some faces beyond the reach (10 of
  // 38). The sphere halted as the pipeline does: none, and no note.
  const std::string moai = fixtures::shared_dataset("moai");
  if (moai.empty()) GTEST_SKIP() << "../shared/datasets not found";
  const std::string args = "simplify " + moai + " " + p("m.ply") + " --adaptive --auto-halt";
  CliRun r = run(args + " --halt-share 1");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: of the result's "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" beyond the reach (missing the input along their normals)"), std::string::npos) << r.out;
  // --json lists them with the flawed quads; `stats`, which has no reach, lists those alone.
  r = run(args + " --halt-share 1 --json --samples 1000 -q");
  const std::vector<std::size_t> listed = flawed_faces_in(r.out);
  r = run("stats " + moai + " " + p("m.ply") + " --json --samples 1000");
  const std::vector<std::size_t> flawed = flawed_faces_in(r.out);
  EXPECT_GT(listed.size(), flawed.size());
  EXPECT_TRUE(std::includes(listed.begin(), listed.end(), flawed.begin(), flawed.end()));
  r = run("simplify " + input_ + " " + p("s.ply") + " --adaptive --auto-halt");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_EQ(r.out.find("beyond the reach"), std::string::npos) << r.out;
}

TEST_F(Cli, a_result_crowded_with_holes_says_so) {
  // A grid with 3% of its triangles taken out keeps every hole open: asked for 300 quads
  // it stops above them with most of its vertices on the border, and the log says so,
  // with the remedy. The sphere, closed, gets no such note.
  write_tri_mesh_ply(p("holey.ply"), fixtures::with_holes(fixtures::tri_grid(60, 60), 0.03, 5));
  CliRun r = run("simplify " + p("holey.ply") + " " + p("h.ply") + " --faces 300");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find(" holes or outlines, and "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("close them first (MeshLab: \"Close Holes\""), std::string::npos) << r.out;
  r = run("simplify " + input_ + " " + p("s.ply") + " --faces 60");
  EXPECT_EQ(r.out.find("holes or outlines"), std::string::npos) << r.out;
}

TEST_F(Cli, a_result_with_folded_quads_says_so) {
  // A CAD cylinder of one row of long triangles with fan caps comes out with quads folded
  // over its rims (README, Limits). The log says how many, unless told to be quiet; a
  // result of sound quads gets no such note.
  const std::string cylinder = p("cylinder.ply");
  write_tri_mesh_ply(cylinder, fixtures::cad_cylinder(64, 1, 2.0));
  CliRun r = run("simplify " + cylinder + " " + p("c.ply") + " --faces 100");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("note: of the result's 100 quads, "), std::string::npos) << r.out;
  const std::string note = " folded (bent by more than 90 degrees); see Limits in quadsimp's README";
  EXPECT_NE(r.out.find(note), std::string::npos) << r.out;
  r = run("simplify " + cylinder + " " + p("c.ply") + " --faces 100 -q");
  EXPECT_EQ(r.out.find("of the result's"), std::string::npos) << r.out;
  r = run("simplify " + input_ + " " + p("s.ply") + " --faces 60");
  EXPECT_EQ(r.out.find("of the result's"), std::string::npos) << r.out;

  // --json and `stats --json` list them, as indices of the file's quads: every folded quad
  // of the file, and the same list from either.
  r = run("simplify " + cylinder + " " + p("c.ply") + " --faces 100 --json --samples 1000 -q");
  ASSERT_NE(r.out.find("\"flawed_faces\": ["), std::string::npos) << r.out;
  const std::vector<std::size_t> flawed = flawed_faces_in(r.out);
  const MeshFile quads = read_mesh(p("c.ply"));
  std::size_t folded = 0;
  for (std::size_t i = 0; i < quads.quads.size(); ++i) {
    const auto& c = quads.quads[i];
    const auto& x = quads.positions;
    if (!quad_folds(x[c[0]], x[c[1]], x[c[2]], x[c[3]])) continue;
    ++folded;
    EXPECT_TRUE(std::count(flawed.begin(), flawed.end(), i)) << "folded quad " << i << " not listed";
  }
  EXPECT_GT(folded, 0u);
  r = run("stats " + cylinder + " " + p("c.ply") + " --json --samples 1000");
  EXPECT_EQ(flawed_faces_in(r.out), flawed) << r.out;
  r = run("stats " + input_ + " " + p("s.ply") + " --json --samples 1000");
  EXPECT_NE(r.out.find("\"flawed_faces\": []"), std::string::npos) << r.out;
}

TEST_F(Cli, a_strip_one_quad_wide_reaches_its_target_by_chord_collapses) {
  TriMesh strip = fixtures::tri_grid(60, 1);
  for (Vec3& q : strip.positions) q = Vec3(q.x(), q.y() / 60, 0.2 * std::sin(M_PI * q.x()));
  write_tri_mesh_ply(p("strip.ply"), strip);
  const CliRun r = run("simplify " + p("strip.ply") + " " + p("st.ply") + " --faces 15");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find(": 15 faces"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" chord collapses, "), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("above the target"), std::string::npos) << r.out;
}

TEST_F(Cli, fit_to_input_lowers_the_distance) {
  // The JSON's RMS distance, with and without the fit, on the same simplification.
  auto rms = [&](const std::string& extra) {
    const CliRun r = run("simplify " + input_ + " " + p("s.ply") + " --faces 60 --json -q --samples 20000" + extra);
    EXPECT_EQ(r.code, 0) << r.out;
    const double x = json_number(r.out, "rms_e3");
    EXPECT_FALSE(std::isnan(x)) << r.out;
    return std::isnan(x) ? 0.0 : x;
  };
  const double plain = rms(""), fitted = rms(" --fit-to-input");
  EXPECT_GT(plain, 0.0);
  EXPECT_LT(fitted, 0.8 * plain);
}

TEST_F(Cli, keep_tips_holds_a_vertex_on_each_spike) {
  // Three spikes on a sphere: with --keep-tips the JSON counts three tips and the quads
  // have a corner on each apex; without it the smoothing cuts them back.
  write_tri_mesh_ply(p("spiky.ply"), fixtures::spiky_sphere(30, 60, 1.0, 0.25));
  const Vec3 apexes[3] = {{0, 0, 2}, {0, 0, -2}, {2, 0, 0}};
  for (bool keep : {false, true}) {
    const CliRun r = run("simplify " + p("spiky.ply") + " " + p("s.ply") + " --faces 100 --json -q" +
                         (keep ? " --keep-tips" : ""));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find(keep ? "\"tips\": 3," : "\"tips\": 0,"), std::string::npos) << r.out;
    const MeshFile out = read_mesh(p("s.ply"));
    int on = 0;
    for (const Vec3& a : apexes)
      on += std::any_of(out.positions.begin(), out.positions.end(),
                        [&](const Vec3& x) { return (x - a).norm() < 1e-6; });
    EXPECT_EQ(on, keep ? 3 : 0) << "keep " << keep;
  }
}

TEST_F(Cli, crease_angle_keeps_a_cubes_edges) {
  // --crease-angle 30: the cube's 8 corners are corners of the quads and its edges are
  // kept, with no distance to it (JSON); without, its edges are rounded off.
  write_tri_mesh_ply(p("cube.ply"), fixtures::tri_cube(16));
  for (bool creases : {false, true}) {
    const CliRun r = run("simplify " + p("cube.ply") + " " + p("c.obj") + " --faces 150 --json -q" +
                         (creases ? " --crease-angle 30" : ""));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.find("\"crease_collapses\": 0,") == std::string::npos, creases) << r.out;
    const MeshFile out = read_mesh(p("c.obj"));
    int corners = 0;
    for (const Vec3& x : out.positions) {
      int sides = 0;
      for (int k = 0; k < 3; ++k) sides += x[k] == 0.0 || x[k] == 1.0;
      corners += sides == 3;
    }
    EXPECT_EQ(corners, creases ? 8 : 0);
    EXPECT_EQ(r.out.find("\"hausdorff_e3\": 0.0000,") != std::string::npos, creases) << r.out;
  }
  // The conversion alone pairs no triangles across them, and says what it split.
  const CliRun c = run("convert " + p("cube.ply") + " " + p("q.ply") + " --crease-angle 30");
  ASSERT_EQ(c.code, 0) << c.out;
  EXPECT_NE(c.out.find("crease splits: 0 parity, 0 unmatchable"), std::string::npos) << c.out;
  EXPECT_EQ(run("simplify " + p("cube.ply") + " " + p("c.obj") + " --faces 150 --crease-angle 180").code, 2);
  EXPECT_EQ(run("convert " + p("cube.ply") + " " + p("c.obj") + " --crease-angle -1").code, 2);
}

TEST_F(Cli, fitmap_marks_the_tips_keep_tips_holds) {
  // The same spiky sphere: `fitmap --tips 100` marks its three apexes (per-vertex `tip`),
  // which simplify's --keep-tips holds at 100 quads, and nothing else.
  const TriMesh spiky = fixtures::spiky_sphere(30, 60, 1.0, 0.25);
  write_tri_mesh_ply(p("spiky.ply"), spiky);
  CliRun r = run("fitmap " + p("spiky.ply") + " " + p("f.ply") + " --tips 100 -q");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("fitmap_s, fitmap_m, tip; colour = S; 3 tips at 100 quads"), std::string::npos) << r.out;
  const std::vector<float> tip = ply_vertex_property(p("f.ply"), "tip");
  ASSERT_EQ(tip.size(), spiky.positions.size());
  std::vector<Vec3> marked;
  for (std::size_t v = 0; v < tip.size(); ++v)
    if (tip[v] != 0.f) marked.push_back(spiky.positions[v]);
  ASSERT_EQ(marked.size(), 3u);
  for (const Vec3& apex : {Vec3(0, 0, 2), Vec3(0, 0, -2), Vec3(2, 0, 0)})
    EXPECT_TRUE(std::any_of(marked.begin(), marked.end(), [&](const Vec3& x) { return (x - apex).norm() < 1e-6; }))
        << apex.transpose();
  EXPECT_EQ(ply_vertex_property(p("f.ply"), "fitmap_s").size(), spiky.positions.size());
  // Without --tips: no such property.
  r = run("fitmap " + p("spiky.ply") + " " + p("g.ply") + " -q");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(ply_vertex_property(p("g.ply"), "tip").empty());
  EXPECT_EQ(run("fitmap " + p("spiky.ply") + " " + p("g.ply") + " --tips 0").code, 2);
}

TEST_F(Cli, fitmap_writes_the_stretch_of_adaptive_quads) {
  // A torus of radii 1 and 0.3: on its outer equator quads may grow about sqrt(1.3 / 0.3)
  // = 2.08 times longer along the ring than around the tube (the metric's radius at 1,200
  // quads is 0.2, which the estimate takes in), and the long side runs along the ring.
  const TriMesh torus = fixtures::tri_torus(120, 40, 1.0, 0.3);
  write_tri_mesh_ply(p("torus.ply"), torus);
  CliRun r = run("fitmap " + p("torus.ply") + " " + p("f.ply") + " --metric 1200 -q");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("fitmap_s, fitmap_m, aspect, long_x, long_y, long_z; colour = S; aspect at 1200 quads"),
            std::string::npos)
      << r.out;
  const std::vector<float> aspect = ply_vertex_property(p("f.ply"), "aspect");
  std::vector<float> along[3];
  for (int k = 0; k < 3; ++k) along[k] = ply_vertex_property(p("f.ply"), std::string("long_") + "xyz"[k]);
  ASSERT_EQ(aspect.size(), torus.positions.size());
  std::size_t outer = 0;
  for (std::size_t v = 0; v < aspect.size(); ++v) {
    const Vec3& x = torus.positions[v];
    if (x.head<2>().norm() < 1.29) continue;
    ++outer;
    const Vec3 ring = Vec3(-x.y(), x.x(), 0).normalized();
    EXPECT_NEAR(aspect[v], 2.08, 0.2) << x.transpose();
    EXPECT_GT(std::abs(ring.dot(Vec3(along[0][v], along[1][v], along[2][v]))), 0.99) << x.transpose();
  }
  EXPECT_EQ(outer, 3 * 120u);  // the equator and the rows 9 degrees around the tube either side
  // --max-aspect bounds it, as simplify's does.
  r = run("fitmap " + p("torus.ply") + " " + p("g.ply") + " --metric 1200 --max-aspect 1.5 -q");
  ASSERT_EQ(r.code, 0) << r.out;
  const std::vector<float> bounded = ply_vertex_property(p("g.ply"), "aspect");
  EXPECT_LE(*std::max_element(bounded.begin(), bounded.end()), 1.5f + 1e-5f);
  r = run("fitmap " + p("torus.ply") + " " + p("h.ply") + " -q");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(ply_vertex_property(p("h.ply"), "aspect").empty());
  EXPECT_EQ(run("fitmap " + p("torus.ply") + " " + p("h.ply") + " --metric 0").code, 2);
}

TEST_F(Cli, json_reports_the_count_automatic_halting_predicts) {
  // The count the metric and the tips are taken at when no target is given: what
  // `fitmap --metric N` needs to show a halted run's metric. 0 with a target.
  write_tri_mesh_ply(p("torus.ply"), fixtures::tri_torus(120, 40, 1.0, 0.3));
  auto predicted = [&](const std::string& mode) {
    const CliRun r = run("simplify " + p("torus.ply") + " " + p("s.ply") + " " + mode + " --json -q --samples 2000");
    EXPECT_EQ(r.code, 0) << r.out;
    const auto at = r.out.find("\"predicted_faces\": ");
    EXPECT_NE(at, std::string::npos) << r.out;
    return at == std::string::npos ? -1 : std::stoi(r.out.substr(at + 19));
  };
  EXPECT_GT(predicted("--adaptive --auto-halt"), 0);
  EXPECT_EQ(predicted("--adaptive --faces 200"), 0);
  EXPECT_EQ(predicted("--faces 200"), 0);
}

TEST_F(Cli, fitmap_auto_takes_the_count_automatic_halting_predicts) {
  // `--metric auto` and `--tips auto`: at the count simplify --adaptive --auto-halt
  // reports as predicted_faces, where it takes its metric and tips; the same metric as
  // `--metric` at that count.
  write_tri_mesh_ply(p("torus.ply"), fixtures::tri_torus(120, 40, 1.0, 0.3));
  CliRun r = run("simplify " + p("torus.ply") + " " + p("s.ply") + " --adaptive --auto-halt --json -q --samples 2000");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto at = r.out.find("\"predicted_faces\": ");
  ASSERT_NE(at, std::string::npos) << r.out;
  const std::string predicted = std::to_string(std::stoi(r.out.substr(at + 19)));
  r = run("fitmap " + p("torus.ply") + " " + p("f.ply") + " --metric auto --tips auto -q");
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("automatic halting predicted at " + predicted + " quads; 0 tips at " + predicted +
                       " quads; aspect at " + predicted + " quads"),
            std::string::npos)
      << r.out << " (predicted " << predicted << ")";
  ASSERT_EQ(run("fitmap " + p("torus.ply") + " " + p("g.ply") + " --metric " + predicted + " -q").code, 0);
  const std::vector<float> aspect = ply_vertex_property(p("f.ply"), "aspect");
  EXPECT_FALSE(aspect.empty());
  EXPECT_EQ(aspect, ply_vertex_property(p("g.ply"), "aspect"));
  EXPECT_EQ(ply_vertex_property(p("f.ply"), "tip").size(), aspect.size());
  // A word that is neither; and a prediction under half a quad (faces may grow to a
  // thousand times F_M), which gives no count to take them at.
  EXPECT_EQ(run("fitmap " + p("torus.ply") + " " + p("h.ply") + " --metric automatic").code, 2);
  r = run("fitmap " + p("torus.ply") + " " + p("h.ply") + " --tips auto --m-factor 0.001");
  EXPECT_EQ(r.code, 1) << r.out;
  EXPECT_NE(r.out.find("automatic halting predicts under half a quad here"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(p("h.ply")));
}

TEST_F(Cli, a_fin_on_an_edge_is_removed_and_reported) {
  // Three triangles on edge 1-2 (the OBJ's numbering): the fin goes, though it is the
  // largest, and the plane's two triangles stay.
  const std::string in =
      write("fin.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0.5 0 3\nf 1 2 3\nf 2 1 4\nf 1 2 5\n");
  const CliRun r = run("convert " + in + " " + p("quad.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("fin.obj: 1 faces removed at edges shared by more than two triangles"), std::string::npos)
      << r.out;
  const qs::MeshFile out = qs::read_mesh(p("quad.obj"));
  EXPECT_EQ(out.quads.size(), 1u);  // the plane's two triangles, as one quad
  for (const qs::Vec3& x : out.positions) EXPECT_EQ(x.z(), 0.0);  // not the fin's tip
}

TEST_F(Cli, a_cap_is_mended_and_reported) {
  // Vertex 3 stands 1e-5 above the middle of edge 1-2, which the triangle below shares:
  // that edge is flipped, and nothing moves.
  const std::string in = write("cap.obj",
                               "v 0 0 0\nv 2 0 0\nv 1 1e-5 0\nv 1 -1 0\nv 1 1 0\n"
                               "f 1 2 3\nf 2 1 4\nf 1 3 5\nf 3 2 5\n");
  const CliRun r = run("convert " + in + " " + p("quad.obj"));
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("cap.obj: 1 edges flipped to mend caps"), std::string::npos) << r.out;
  const qs::MeshFile out = qs::read_mesh(p("quad.obj"));
  EXPECT_TRUE(out.is_pure_quad());
  EXPECT_EQ(out.positions.size(), 5u);
}

TEST_F(Cli, a_folded_patch_is_laid_flat_and_reported) {
  // A strip of triangles folded back onto a grid (folded_grid()): cleaning moves the
  // pushed vertices back between their neighbours, and says so.
  const std::string in = p("folded.ply");
  write_tri_mesh_ply(in, fixtures::folded_grid(128));
  const CliRun r = run("simplify " + in + " " + p("quad.ply") + " --faces 1000");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("folded.ply: 1 patches of triangles folded back onto the surface laid flat"), std::string::npos)
      << r.out;
  EXPECT_TRUE(qs::read_mesh(p("quad.ply")).is_pure_quad());
}

TEST_F(Cli, a_crack_of_t_junctions_in_an_stl_is_closed_and_reported) {
  // Two patches of a bowl meshed apart, as a CAD tessellation writes them to STL: every
  // triangle with its own corners, and along the common side every third vertex of the
  // finer patch a copy of one of the coarser's, the others along its edges. Welded, the
  // side is a crack; closed, the result's only border is the bowl's outline.
  const TriMesh t = fixtures::patches_meshed_apart(12, 0.5);
  std::string stl = "solid patches\n";
  for (const auto& f : t.faces) {
    stl += "facet normal 0 0 0\nouter loop\n";
    for (Index v : f) {
      char line[96];
      std::snprintf(line, sizeof line, "vertex %.9g %.9g %.9g\n", t.positions[v].x(), t.positions[v].y(),
                    t.positions[v].z());
      stl += line;
    }
    stl += "endloop\nendfacet\n";
  }
  const std::string in = write("patches.stl", stl + "endsolid patches\n");
  const CliRun r = run("simplify " + in + " " + p("quad.obj") + " --faces 40");
  EXPECT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("taken into that edge, closing the crack"), std::string::npos) << r.out;
  const qs::MeshFile out = qs::read_mesh(p("quad.obj"));
  ASSERT_TRUE(out.is_pure_quad());
  std::map<std::pair<Index, Index>, int> edges;
  for (const auto& q : out.quads)
    for (int k = 0; k < 4; ++k) ++edges[std::minmax(q[k], q[(k + 1) % 4])];
  const auto on_outline = [&](Index v) {
    const Vec3& x = out.positions[v];
    return std::min({std::abs(x.x()), std::abs(x.x() - 2), std::abs(x.y()), std::abs(x.y() - 1)}) < 1e-6;
  };
  for (const auto& [e, faces] : edges) {
    if (faces == 1) {
      EXPECT_TRUE(on_outline(e.first) && on_outline(e.second)) << "a border edge inside the bowl";
    }
  }
}

TEST_F(Cli, bad_input_exits_1_and_writes_nothing) {
  const std::vector<std::string> bad = {
      write("cloud.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                         "property float z\nend_header\n0 0 0\n1 0 0\n"),
      write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n"),
      write("empty.off", ""),
      write("junk.ply", "garbage\n"),
      // vcglib's STL reader looped for ever on files without a line break that are not a
      // binary STL of the size their facet count gives.
      write("line.stl", "solid a facet normal 0 0 1 outer loop vertex 0 0 0 vertex 1 0 0 vertex 1 1 0 endloop "
                        "endfacet endsolid a"),
      write("cut.stl", std::string(80, '\0') + std::string("\5\0\0\0", 4) + std::string(60, '\0')),
      // Every triangle has an area, but the weld of its borders leaves none.
      write("thread.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1e-7 0\nv 1 1e-7 0\nv 2 1e-7 0\n"
                          "f 1 2 5\nf 1 5 4\nf 2 3 6\nf 2 6 5\n"),
  };
  for (const auto& in : bad) {
    SCOPED_TRACE(in);
    const std::string out = p("result.ply");
    const CliRun r = run("convert " + in + " " + out);
    EXPECT_EQ(r.code, 1) << r.out;
    EXPECT_NE(r.out.find(in), std::string::npos) << "the error names the file: " << r.out;
    EXPECT_FALSE(fs::exists(out));
  }
  for (const auto& e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".result"), std::string::npos) << "temporary left: " << e.path();
}
