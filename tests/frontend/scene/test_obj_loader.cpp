// The OBJ loader (frontend/scene/obj_loader.hpp): good files load with their MTL colours, malformed
// files are reported with file:line.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/scene/obj_loader.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

struct scratch_folder {
  fs::path root = fs::temp_directory_path() / ("vplkit-obj-" + std::to_string(std::random_device{}()));
  scratch_folder() { fs::create_directories(root); }
  ~scratch_folder() { fs::remove_all(root); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(root / name) << text;
    return root / name;
  }
};

std::string load_error(const fs::path& path) {
  try {
    load_obj(path);
  } catch (const vplkit::error& failure) {
    return failure.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("an OBJ quad with a material loads as two triangles with the Kd albedo and face normals") {
  scratch_folder folder;
  folder.write("red.mtl", "newmtl red\nKd 0.8 0.1 0.05\n");
  const fs::path obj = folder.write("quad.obj", "mtllib red.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nusemtl red\nf 1 2 3 4\n");
  const mesh m = load_obj(obj);
  REQUIRE(m.triangle_count() == 2);
  for (const vertex& v : m.vertices) {
    CHECK(v.albedo.x == doctest::Approx(0.8));
    CHECK(v.albedo.z == doctest::Approx(0.05));
    CHECK(v.normal.z == doctest::Approx(1.0));  // counter-clockwise seen from +z
  }
  // Without a material: grey; negative (relative) indices and v//vn corners work.
  const fs::path relative = folder.write("relative.obj", "v 0 0 0\nv 0 0 1\nv 0 1 0\nvn 1 0 0\nf -3//1 -2//1 -1//1\n");
  const mesh r = load_obj(relative);
  REQUIRE(r.triangle_count() == 1);
  CHECK(r.vertices[0].albedo.y == doctest::Approx(0.73));
  CHECK(r.vertices[0].normal.x == doctest::Approx(1.0));
}

TEST_CASE("without normals in the file, shared vertices get the area-weighted mean of their faces' normals") {
  scratch_folder folder;
  // Two triangles folded along the x axis: one in the z = 0 plane, one rising at 90 degrees.
  const mesh m = load_obj(folder.write("fold.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\n"));
  REQUIRE(m.triangle_count() == 2);
  // Vertex 1 (the origin) is shared: its normal is halfway between +z and +y.
  const glm::vec3 shared = m.vertices[0].normal;
  CHECK(shared.y == doctest::Approx(std::sqrt(0.5)));
  CHECK(shared.z == doctest::Approx(std::sqrt(0.5)));
  CHECK(m.vertices[2].normal.z == doctest::Approx(1.0));  // vertex 3 belongs to one face only
}

TEST_CASE("malformed OBJ files are reported as file:line") {
  scratch_folder folder;
  const auto path_of = [&](const char* name) { return (folder.root / name).string(); };
  CHECK(load_error(folder.write("index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n")) ==
        path_of("index.obj") + ":4: face vertex index 4 is out of range (3 defined so far)");
  CHECK(load_error(folder.write("zero.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n")).find(path_of("zero.obj") + ":4: face vertex index 0") == 0);
  CHECK(load_error(folder.write("normal.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1//2 2//2 3//2\n")).find(path_of("normal.obj") + ":4: face normal index 2") == 0);
  CHECK(load_error(folder.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")) == path_of("nan.obj") + ":2: number 'nan' is not finite");
  CHECK(load_error(folder.write("inf.obj", "# a comment\nv 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n")) == path_of("inf.obj") + ":4: number '1e999' is outside the float range");
  CHECK(load_error(folder.write("word.obj", "v 0 zero 0\n")) == path_of("word.obj") + ":1: 'zero' is not a number");
  CHECK(load_error(folder.write("short.obj", "v 0 0\n")) == path_of("short.obj") + ":1: 'v' needs 3 to 7 numbers, got 2");
  CHECK(load_error(folder.write("edge.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n")) == path_of("edge.obj") + ":3: a face needs at least 3 corners");
  CHECK(load_error(folder.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")) == path_of("points.obj") + ": no faces (an OBJ mesh needs 'v' and 'f' lines)");
  CHECK(load_error(folder.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n")).find("every triangle is degenerate") != std::string::npos);
  CHECK(load_error(folder.root / "missing.obj") == path_of("missing.obj") + ": no such OBJ file");
}

namespace {

std::string parse_error(const std::string& text, const std::string& library = "") {
  try {
    parse_obj(text, "t.obj", [&](const std::string& name) -> std::string {
      if (library.empty()) throw vplkit::error(name + ": no such MTL file");
      return library;
    });
  } catch (const vplkit::error& failure) {
    return failure.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("the OBJ parser sees every byte the way an editor does: no control characters but tab, LF and CRLF") {
  // Each reached out-of-bounds reads or writes when a line validator and a second parser disagreed.
  CHECK(parse_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1// 2 3\n") == "t.obj:4: face corner '1//' is not v, v/vt, v//vn or v/vt/vn");
  CHECK(parse_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n#\rf 1 2 100000\n").find("t.obj:5: control character 0x0d") == 0);
  CHECK(parse_error("v 0 0 0\nv 1 0 0\nv\v0 1 0\nf 1 2 3\n").find("t.obj:3: control character 0x0b") == 0);
  CHECK(parse_error(std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3") + '\0' + "\n").find("t.obj:4: control character 0x00") == 0);
  // CRLF line ends and tabs are fine; a comment may follow a statement.
  CHECK(parse_obj("v\t0 0 0\r\nv 1 0 0 # x\r\nv 0 1 0\r\nf 1 2 3\r\n", "t.obj", {}).triangle_count() == 1);
}

TEST_CASE("OBJ numbers are checked as the floats they become") {
  CHECK(parse_error("v 1e39 0 0\n") == "t.obj:1: number '1e39' is outside the float range");
  CHECK(parse_error("v " + std::string(100, '1') + " 0 0\n").find("is outside the float range") != std::string::npos);
  CHECK(parse_error("v 2e6 0 0\n").find("t.obj:1: number '2e6' is larger than 1000000 in magnitude") == 0);
  CHECK(parse_error("v 0 0 0\nvn inf 0 0\n") == "t.obj:2: number 'inf' is not finite");
  CHECK(parse_error("v 0x10 0 0\n") == "t.obj:1: '0x10' is not a number");
  CHECK(parse_error("mtllib m.mtl\n", "newmtl a\nKd 1e999 0 0\n") == "t.obj:1: mtllib m.mtl: m.mtl:2: number '1e999' is outside the float range");
  // 0e999 is zero, not NaN: the material loads black in that channel.
  const mesh m = parse_obj("mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n", "t.obj",
                           [](const std::string&) { return std::string("newmtl a\nKd 0e999 0.5 +2\n"); });
  CHECK(m.vertices[0].albedo == glm::vec3(0.0f, 0.5f, 1.0f));
}

TEST_CASE("OBJ faces: indices resolved and range-checked, convex polygons fanned, vertex colours and w ignored") {
  CHECK(parse_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99999999999999999999\n").find("t.obj:4: face corner '99999999999999999999' is not an index") == 0);
  CHECK(parse_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2 3\n") == "t.obj:4: face texture coordinate index 1 is out of range (0 defined so far)");
  CHECK(parse_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2/3/4 2 3\n") == "t.obj:4: face corner '1/2/3/4' has more than 3 indices (v/vt/vn)");
  CHECK(parse_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 2 3\n") == "t.obj:4: face vertex index -4 is out of range (3 defined so far)");
  const mesh fan = parse_obj("v 0 0 0 1\nv 1 0 0 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 0.5 0\nf 1 2 3 4 5\n", "t.obj", {});
  CHECK(fan.triangle_count() == 3);
  CHECK(parse_error("usemtl missing\n") == "t.obj:1: material 'missing' is not in the material libraries read so far (none)");
  CHECK(parse_error("mtllib a.mtl\n").find("t.obj:1: mtllib a.mtl: a.mtl: no such MTL file") == 0);
  CHECK(parse_error("mtllib a.mtl\n", "Kd 1 1 1\n") == "t.obj:1: mtllib a.mtl: a.mtl:1: 'Kd' before any 'newmtl'");
}

TEST_CASE("OBJ limits are checked before the memory is spent, naming the file") {
  obj_limits small;
  small.max_triangles = 2;
  CHECK_THROWS_WITH_AS(parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\nf 1 2 3\n", "t.obj", {}, small),
                       "t.obj:6: more than 2 triangles (the most vplkit loads)", vplkit::error);
  scratch_folder folder;
  small.max_obj_bytes = 8;
  const fs::path big = folder.write("big.obj", "v 0 0 0\nv 1 0 0\n");
  CHECK(load_error(big).find("no faces") != std::string::npos);  // the default limit reads it
  CHECK_THROWS_WITH_AS(load_obj(big, small), (big.string() + ": the OBJ file is 16 bytes, more than the 8 bytes vplkit reads").c_str(), vplkit::error);
  // A library that is not a regular file (here a folder; /dev/zero is refused the same way).
  fs::create_directories(folder.root / "folder.mtl");
  const fs::path uses_folder = folder.write("uses-folder.obj", "mtllib folder.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  CHECK(load_error(uses_folder).find("folder.mtl: not a regular file (expected an MTL file)") != std::string::npos);
}

TEST_CASE("a loaded OBJ stays indexed: corners with the same position, normal and albedo share a vertex") {
  // An n x n grid of quads without normals: one vertex per position, six indices per quad.
  const int n = 20;
  std::string text;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) text += "v " + std::to_string(i) + " 0 " + std::to_string(-j) + "\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i + 1, b = a + 1, c = a + n + 1, d = c + 1;
      text += "f " + std::to_string(a) + " " + std::to_string(b) + " " + std::to_string(d) + " " + std::to_string(c) + "\n";
    }
  const mesh grid = parse_obj(text, "grid.obj", [](const std::string&) -> std::string { throw vplkit::error("no library"); });
  CHECK(grid.triangle_count() == 2 * n * n);
  CHECK(grid.vertices.size() == (n + 1) * (n + 1));
  for (const vertex& v : grid.vertices) CHECK(v.normal == glm::vec3(0, 1, 0));  // a flat grid's smooth normal
  // A second material splits the vertices it shares with the first; given normals split by index.
  const std::string two = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nvn 0 1 0\nvn 0 1 0\nusemtl a\nf 1//1 2//1 3//1\nusemtl b\nf 1//1 3//1 4//2\n";
  const mesh split = parse_obj(two, "two.obj", [](const std::string&) { return std::string("newmtl a\nKd 1 0 0\nnewmtl b\nKd 0 1 0\n"); });
  CHECK(split.triangle_count() == 2);
  CHECK(split.vertices.size() == 6);  // 3 + 3: the second triangle shares no (position, normal, albedo)
  const mesh same = parse_obj("v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nvn 0 1 0\nf 1//1 2//1 3//1\nf 1//1 3//1 4//1\n", "same.obj",
                              [](const std::string&) -> std::string { throw vplkit::error("no library"); });
  CHECK(same.vertices.size() == 4);
  // A crease folded over itself (the same triangle both ways round): the smooth normals cancel,
  // so every corner takes its face's normal and a vertex of its own.
  const mesh folded = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 3 2\n", "fold.obj",
                                [](const std::string&) -> std::string { throw vplkit::error("no library"); });
  REQUIRE(folded.vertices.size() == 6);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(folded.vertices[folded.indices[k]].normal == glm::vec3(0, 0, 1));
    CHECK(folded.vertices[folded.indices[3 + k]].normal == glm::vec3(0, 0, -1));
  }
}

TEST_CASE("a triangle soup gets a vertex per corner, shared corners still share, and the floor frame_mesh adds reallocates nothing") {
  // Two soup triangles (each `v` line used once, as STL conversions write) and a quad whose
  // diagonal two triangles share.
  const std::string text = "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 2 0 0\nv 3 0 0\nv 2 0 -1\nv 5 0 0\nv 6 0 0\nv 6 0 -1\nv 5 0 -1\n"
                           "f 1 2 3\nf 4 5 6\nf 7 8 9 10\n";
  mesh soup = parse_obj(text, "soup.obj", [](const std::string&) -> std::string { throw vplkit::error("no library"); });
  CHECK(soup.triangle_count() == 4);
  CHECK(soup.vertices.size() == 10);  // 3 + 3 + the quad's 4, shared by its two triangles
  // Room for the framing's floor: adding it must not reallocate the arrays (a reallocation holds
  // the old and the new array at once: 277 MB twice for a faceted 2^21-triangle mesh).
  CHECK(soup.vertices.capacity() >= soup.vertices.size() + framing_floor_vertices);
  CHECK(soup.indices.capacity() >= soup.indices.size() + framing_floor_indices);
  const vertex* vertices_before = soup.vertices.data();
  const std::uint32_t* indices_before = soup.indices.data();
  const scene framed = frame_mesh("soup", std::move(soup));
  REQUIRE(framed.geometry.vertices.size() == 10 + framing_floor_vertices);  // the floor was added
  CHECK(framed.geometry.vertices.data() == vertices_before);
  CHECK(framed.geometry.indices.data() == indices_before);
}

namespace {

// The summed area of a mesh's triangles.
double mesh_area(const mesh& m) {
  double area = 0.0;
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::dvec3 a(m.vertices[m.indices[t]].position), b(m.vertices[m.indices[t + 1]].position), c(m.vertices[m.indices[t + 2]].position);
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  return area;
}

}  // namespace

TEST_CASE("a concave OBJ face is triangulated inside its outline: assimp's ring keeps its hole") {
  // A ring in the xz plane traced as one face (outer circle, slit, inner circle back, slit), the
  // way assimp's OBJ/concave_polygon.obj is written: its area is the annulus polygon's, not the
  // disk a fan from corner 1 fills.
  const int sides = 16;
  const double outer = 2.0, inner = 1.5, pi = 3.14159265358979323846;
  std::string text;
  for (const double radius : {outer, inner})
    for (int i = 0; i < sides; ++i) {
      // Appended piece by piece: GCC 12 gives a false -Wrestrict on "v " + std::string (bug 105329).
      text += "v ";
      text += std::to_string(radius * std::cos(2 * pi * i / sides));
      text += " 0 ";
      text += std::to_string(-radius * std::sin(2 * pi * i / sides));
      text += "\n";
    }
  text += "f";
  for (int i = 0; i <= sides; ++i) {
    text += ' ';
    text += std::to_string(i % sides + 1);
  }
  for (int i = 0; i <= sides; ++i) {
    text += ' ';
    text += std::to_string(sides + (sides - i) % sides + 1);
  }
  text += "\n";
  const mesh ring = parse_obj(text, "ring.obj", {});
  const double annulus = 0.5 * sides * std::sin(2 * pi / sides) * (outer * outer - inner * inner);
  CHECK(ring.triangle_count() == 2 * sides);
  CHECK(mesh_area(ring) == doctest::Approx(annulus).epsilon(1e-5));
  for (const vertex& v : ring.vertices) CHECK(v.normal.y > 0.99f);  // wound as the face: up
  // A face whose edges cross is named with its line.
  CHECK_THROWS_WITH_AS(parse_obj("v 0 0 0\nv 3 0 -1\nv 3 0 0\nv 0 0 -2\nf 1 2 3\nf 1 2 3 4\n", "t.obj", {}),
                       doctest::Contains("t.obj:6: the face crosses itself"), vplkit::error);

  // assimp's own file, where installed: the loaded area is the face's shoelace area in its plane
  // (x = -1.146; corners in (y, z)), read from the file here.
  const fs::path file = "/usr/share/assimp/models/OBJ/concave_polygon.obj";
  if (!fs::is_regular_file(file)) {
    MESSAGE("skipped the assimp file: assimp-testmodels is not installed");
    return;
  }
  std::ifstream in(file);
  std::vector<glm::dvec2> corners, face;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) == 0) {
      double x = 0, y = 0, z = 0;
      REQUIRE(std::sscanf(line.c_str(), "v %lf %lf %lf", &x, &y, &z) == 3);
      CHECK(x == -1.146);
      corners.emplace_back(y, z);
    } else if (line.rfind("f ", 0) == 0) {
      std::istringstream words(line.substr(2));
      for (std::string word; words >> word;) face.push_back(corners.at(static_cast<std::size_t>(std::stoi(word) - 1)));
    }
  }
  REQUIRE(face.size() == 66);
  double twice = 0.0;
  for (std::size_t i = 0; i < face.size(); ++i) twice += face[i].x * face[(i + 1) % face.size()].y - face[i].y * face[(i + 1) % face.size()].x;
  const mesh loaded = load_obj(file);
  CHECK(mesh_area(loaded) == doctest::Approx(0.5 * std::fabs(twice)).epsilon(1e-4));
  CHECK(mesh_area(loaded) < 0.3 * 3.14159 * 0.74 * 0.74);  // well under the disk the fan filled (outer radius about 0.74)
}
