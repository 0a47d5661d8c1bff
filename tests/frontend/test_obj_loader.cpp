// The OBJ loader (frontend/obj_loader.hpp): good files load with their MTL colours, malformed
// files are reported with file:line.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <cmath>
#include <random>

#include "frontend/error.hpp"
#include "frontend/obj_loader.hpp"

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
  CHECK(load_error(folder.write("nan.obj", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n")) == path_of("nan.obj") + ":2: coordinate 'nan' is not finite");
  CHECK(load_error(folder.write("inf.obj", "# a comment\nv 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n")) == path_of("inf.obj") + ":4: coordinate '1e999' is not finite");
  CHECK(load_error(folder.write("word.obj", "v 0 zero 0\n")) == path_of("word.obj") + ":1: 'zero' is not a number");
  CHECK(load_error(folder.write("short.obj", "v 0 0\n")) == path_of("short.obj") + ":1: 'v' needs 3 numbers");
  CHECK(load_error(folder.write("edge.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n")) == path_of("edge.obj") + ":3: a face needs at least 3 corners");
  CHECK(load_error(folder.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n")) == path_of("points.obj") + ": no faces (an OBJ mesh needs 'v' and 'f' lines)");
  CHECK(load_error(folder.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n")).find("every triangle is degenerate") != std::string::npos);
  CHECK(load_error(folder.root / "missing.obj") == path_of("missing.obj") + ": cannot open the OBJ file");
}
