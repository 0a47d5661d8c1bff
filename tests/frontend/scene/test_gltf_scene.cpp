// The glTF 2.0 reader and writer (frontend/scene/gltf_scene.hpp): a built-in scene written and
// read back is the same scene; Debian's assimp glTF2 test files each load or fail with a
// vplkit::error naming the file; hostile files fail with the problem named; strips, fans and
// Draco-compressed primitives give the triangles they stand for; glTF 1.0 is named.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <unordered_map>
#include <vector>

#include "frontend/core/error.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/scene/gltf_scene.hpp"

using namespace vplkit;
namespace fs = std::filesystem;

namespace {

void check_close(const glm::vec3& a, const glm::vec3& b, float tolerance) {
  for (int k = 0; k < 3; ++k) CHECK(a[k] == doctest::Approx(b[k]).epsilon(tolerance).scale(1.0));
}

}  // namespace

TEST_CASE("a built-in scene written as glTF and read back is the same scene (mesh, albedo, camera, light)") {
  for (const std::string name : {"cornell-box", "indirect-shadow", "occluder"}) {
    CAPTURE(name);
    const scene original = built_in_scene(name);
    const scene back = parse_gltf(gltf_text(original), false, name + ".gltf", {});
    REQUIRE(back.geometry.triangle_count() == original.geometry.triangle_count());
    // Triangles come back grouped by albedo, each group in its original order.
    std::size_t matched = 0;
    for (std::size_t t = 0; t < back.geometry.indices.size(); t += 3)
      for (std::size_t u = 0; u < original.geometry.indices.size(); u += 3) {
        bool same = true;
        for (int c = 0; c < 3 && same; ++c) {
          const vertex& a = back.geometry.vertices[back.geometry.indices[t + static_cast<std::size_t>(c)]];
          const vertex& b = original.geometry.vertices[original.geometry.indices[u + static_cast<std::size_t>(c)]];
          same = a.position == b.position && a.albedo == b.albedo && glm::length(a.normal - b.normal) < 1e-6f;
        }
        if (same) {
          ++matched;
          break;
        }
      }
    CHECK(matched == original.geometry.triangle_count());
    check_close(back.view.position, original.view.position, 1e-6f);
    check_close(glm::normalize(back.view.target - back.view.position), glm::normalize(original.view.target - original.view.position), 1e-6f);
    CHECK(back.view.vertical_fov_degrees == doctest::Approx(original.view.vertical_fov_degrees).epsilon(1e-6));
    REQUIRE(back.lights[0].kind == original.lights[0].kind);
    if (original.lights[0].kind == light_kind::spot) {
      check_close(back.lights[0].spot.position, original.lights[0].spot.position, 1e-6f);
      check_close(back.lights[0].spot.direction, original.lights[0].spot.direction, 1e-6f);
      check_close(back.lights[0].spot.intensity, original.lights[0].spot.intensity, 1e-6f);
      CHECK(back.lights[0].spot.cos_inner == doctest::Approx(original.lights[0].spot.cos_inner).epsilon(1e-6));
      CHECK(back.lights[0].spot.cos_outer == doctest::Approx(original.lights[0].spot.cos_outer).epsilon(1e-6));
    } else {
      check_close(back.lights[0].directional.direction, original.lights[0].directional.direction, 1e-6f);
      check_close(back.lights[0].directional.irradiance, original.lights[0].directional.irradiance, 1e-6f);
    }
  }
}

TEST_CASE("Debian's assimp glTF2 test files each load or fail with a vplkit::error naming the file") {
  const fs::path models = "/usr/share/assimp/models/glTF2";
  if (!fs::is_directory(models)) {
    MESSAGE("skipped: assimp-testmodels is not installed");
    return;
  }
  int loaded = 0, refused = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(models)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".gltf" && extension != ".glb") continue;
    CAPTURE(entry.path().string());
    try {
      const scene s = load_gltf(entry.path());
      check_scene(s);
      ++loaded;
    } catch (const vplkit::error& failure) {
      CHECK(std::string(failure.what()).find(entry.path().string()) == 0);
      ++refused;
    }
  }
  MESSAGE(loaded << " loaded, " << refused << " refused with a message");
  CHECK(loaded >= 20);  // the valid ones among them: boxes, the engine, cameras, skins...
}

TEST_CASE("hostile glTF: each problem is named, nothing else is thrown") {
  const auto fails_with = [](const std::string& text, const std::string& expected) {
    CAPTURE(expected);
    CHECK_THROWS_WITH_AS(parse_gltf(text, false, "t.gltf", {}), doctest::Contains(expected.c_str()), vplkit::error);
  };
  fails_with("{", "t.gltf: not a readable glTF 2.0 file");
  fails_with("not json at all", "t.gltf: not a readable glTF 2.0 file");
  fails_with(R"({"asset":{"version":"2.0"}})", "no triangles in its scene");
  const std::string buffer_from_file =
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":"triangle.bin"}]})";
  fails_with(buffer_from_file, "refused: the glTF was given from memory");
  CHECK_THROWS_WITH_AS(load_gltf("missing.gltf"), doctest::Contains("missing.gltf"), vplkit::error);
  CHECK_THROWS_WITH_AS(load_gltf("scene.obj"), doctest::Contains("a glTF file ends in .gltf or .glb"), vplkit::error);
  const fs::path regressions = fs::path(VPLKIT_TEST_SOURCE_DIR) / "fuzz" / "regressions" / "gltf";
  CHECK_THROWS_WITH_AS(load_gltf(regressions / "node-cycle.gltf"), doctest::Contains("reached twice"), vplkit::error);
  CHECK_THROWS_WITH_AS(load_gltf(regressions / "count-beyond-view.gltf"), doctest::Contains("do not fit in its buffer view"), vplkit::error);
}

namespace {

// A triangle in a glTF whose buffer is `uri` (byteLength 36: three float positions), with
// `nodes` for the node list and `extras` for the asset's extras.
std::string triangle_gltf(const std::string& uri, const std::string& nodes = R"([{"mesh": 0}])", const std::string& extras = "0") {
  return R"({"asset": {"version": "2.0", "extras": )" + extras + R"(}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": )" + nodes +
         R"(, "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, )"
         R"("type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}], "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36, "uri": ")" +
         uri + R"("}]})";
}

const std::string triangle_data_uri = "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";

struct gltf_folder {
  fs::path root = fs::temp_directory_path() / ("vplkit-gltf-" + std::to_string(std::random_device{}()));
  gltf_folder() {
    fs::create_directories(root / "scene" / "sub");
    fs::create_directories(root / "outside");
    const std::string triangle(36, '\0');
    for (const fs::path& bin : {root / "outside" / "x.bin", root / "scene" / "in.bin", root / "scene" / "sub" / "deep.bin"}) std::ofstream(bin, std::ios::binary) << triangle;
  }
  ~gltf_folder() {
    std::error_code ignored;
    fs::remove_all(root, ignored);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(root / "scene" / name) << text;
    return root / "scene" / name;
  }
};

std::string load_error(const fs::path& path, const gltf_limits& limits = {}) {
  try {
    load_gltf(path, limits);
  } catch (const vplkit::error& failure) {
    return failure.what();
  }
  return "(no error)";
}

}  // namespace

TEST_CASE("no recursion on the input's depth: a 20,000-node chain loads, JSON nested 20,000 deep is refused by its depth") {
  std::string chain = "[";
  for (int i = 0; i < 19999; ++i) chain += R"({"children": [)" + std::to_string(i + 1) + "]},";
  chain += R"({"mesh": 0, "translation": [1, 2, 3]}])";
  const scene deep = parse_gltf(triangle_gltf(triangle_data_uri, chain), false, "chain.gltf", {});
  CHECK(deep.geometry.triangle_count() == 3);  // the triangle and frame_mesh's floor
  CHECK(deep.geometry.vertices[0].position == glm::vec3(1, 2, 3));  // through all 20,000 transforms
  // A node reached twice is still named, however deep.
  CHECK_THROWS_WITH_AS(parse_gltf(triangle_gltf(triangle_data_uri, R"([{"children": [1]}, {"children": [2]}, {"children": [1], "mesh": 0}])"), false, "cycle.gltf", {}),
                       doctest::Contains("node 1 is reached twice"), vplkit::error);
  const std::string nested = std::string(20000, '[') + std::string(20000, ']');
  CHECK_THROWS_WITH_AS(parse_gltf(triangle_gltf(triangle_data_uri, R"([{"mesh": 0}])", nested), false, "deep.gltf", {}),
                       doctest::Contains("deep.gltf: its JSON nests arrays and objects more than 64 deep"), vplkit::error);
  // Brackets inside strings (escaped quotes too) are text, not nesting.
  const std::string in_string = R"(["\"[[[[)" + std::string(100, '[') + R"("])";
  CHECK(parse_gltf(triangle_gltf(triangle_data_uri, R"([{"mesh": 0}])", in_string), false, "text.gltf", {}).geometry.triangle_count() == 3);
  // 60 levels of extras (62 with the asset object and the root): within the limit.
  const std::string sixty = std::string(60, '[') + std::string(60, ']');
  CHECK(parse_gltf(triangle_gltf(triangle_data_uri, R"([{"mesh": 0}])", sixty), false, "sixty.gltf", {}).geometry.triangle_count() == 3);
  // GLB: the JSON chunk is measured too.
  std::string json = triangle_gltf(triangle_data_uri, R"([{"mesh": 0}])", nested);
  while (json.size() % 4 != 0) json += ' ';
  std::string glb = "glTF";
  const auto put = [&](std::uint32_t v) { glb.append(reinterpret_cast<const char*>(&v), 4); };
  put(2);
  put(static_cast<std::uint32_t>(20 + json.size()));
  put(static_cast<std::uint32_t>(json.size()));
  put(0x4E4F534Au);
  glb += json;
  CHECK_THROWS_WITH_AS(parse_gltf(glb, true, "deep.glb", {}), doctest::Contains("deep.glb: its JSON nests"), vplkit::error);
}

TEST_CASE("external files: only in the glTF's folder tree, percent-decoded once, one budget for all of them") {
  const gltf_folder folder;
  CHECK(load_gltf(folder.write("inside.gltf", triangle_gltf("in.bin"))).geometry.triangle_count() == 3);
  CHECK(load_gltf(folder.write("sub.gltf", triangle_gltf("sub/deep.bin"))).geometry.triangle_count() == 3);
  CHECK(load_gltf(folder.write("encoded.gltf", triangle_gltf("in%2Ebin"))).geometry.triangle_count() == 3);  // %2E is '.'
  CHECK(load_error(folder.write("dotdot.gltf", triangle_gltf("../outside/x.bin"))).find("external file '../outside/x.bin' refused: it has a '..' component") !=
        std::string::npos);
  CHECK(load_error(folder.write("percent.gltf", triangle_gltf("%2e%2e/outside/x.bin"))).find("'../outside/x.bin' refused: it has a '..' component") !=
        std::string::npos);
  CHECK(load_error(folder.write("middle.gltf", triangle_gltf("sub/../../outside/x.bin"))).find("has a '..' component") != std::string::npos);
  CHECK(load_error(folder.write("absolute.gltf", triangle_gltf((folder.root / "outside" / "x.bin").string()))).find("it is an absolute path") !=
        std::string::npos);
  // Decoded once: %252e is "%2e" on disk, not "." (and there is no such file).
  CHECK(load_error(folder.write("twice.gltf", triangle_gltf("%252e%252e/outside/x.bin"))).find("%2e%2e/outside/x.bin: no such glTF external file") != std::string::npos);
  // The current folder is never a fallback (tinygltf tries it after the glTF's): a name found
  // only there is looked for in the glTF's folder alone.
  if (fs::exists("CTestTestfile.cmake"))  // ctest runs the tests in their build folder
    CHECK(load_error(folder.write("cwd.gltf", triangle_gltf("CTestTestfile.cmake"))).find("scene/CTestTestfile.cmake: no such glTF external file") !=
          std::string::npos);
  // One budget: each of four 36-byte buffers fits 100 bytes, all of them do not.
  std::string four = triangle_gltf("in.bin");
  const std::string one_buffer = R"({"byteLength": 36, "uri": "in.bin"})";
  four.replace(four.find(one_buffer), one_buffer.size(), one_buffer + "," + one_buffer + "," + one_buffer + "," + one_buffer);
  gltf_limits budget;
  budget.max_external_bytes = 100;
  CHECK(load_error(folder.write("four.gltf", four), budget).find("external file 'in.bin' (36 bytes) would bring its external data to 108 bytes, more than the 100 bytes") !=
        std::string::npos);
  budget.max_external_bytes = 144;
  CHECK(load_gltf(folder.root / "scene" / "four.gltf", budget).geometry.triangle_count() == 3);
  // A 16 MiB data URI that does not decode is not echoed whole.
  const std::string huge = load_error(folder.write("huge.gltf", triangle_gltf("data:application/octet-stream;base64," + std::string(std::size_t{16} << 20, 'A') + "!")));
  CHECK(huge.find("not a readable glTF 2.0 file") != std::string::npos);
  CHECK(huge.size() < 1200);
}

TEST_CASE("sizes are checked before anything is read or widened; meshes with normals stay indexed") {
  // 3000 one-byte indices with a limit of 999 triangles: refused by the count, before reading.
  const std::string positions = "AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA";  // 36 bytes
  std::string indices_base64;
  for (int i = 0; i < 1000; ++i) indices_base64 += "AAEC";  // bytes 0, 1, 2
  const std::string many = R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}, {"bufferView": 1, "componentType": 5121, "count": 3000, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}, {"buffer": 1, "byteLength": 3000}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" + positions + R"("},
                {"byteLength": 3000, "uri": "data:application/octet-stream;base64,)" + indices_base64 + R"("}]})";
  gltf_limits limits;
  limits.max_triangles = 999;
  CHECK_THROWS_WITH_AS(parse_gltf(many, false, "many.gltf", {}, limits), "many.gltf: more than 999 triangles", vplkit::error);
  limits.max_triangles = 1000;
  const scene loaded = parse_gltf(many, false, "many.gltf", {}, limits);
  CHECK(loaded.geometry.triangle_count() == 1002);  // with frame_mesh's floor
  CHECK(loaded.geometry.vertices.size() == 3000 + 4);  // no NORMAL: flat normals, three vertices a triangle
  // With NORMAL, a vertex is shared by every triangle that uses it: 3 vertices for 1000 triangles.
  std::string with_normals = many;
  with_normals.replace(with_normals.find(R"({"POSITION": 0})"), 15, R"({"POSITION": 0, "NORMAL": 2})");
  with_normals.replace(with_normals.find(R"("type": "SCALAR"}])"), 18, R"("type": "SCALAR"}, {"bufferView": 2, "componentType": 5126, "count": 3, "type": "VEC3"}])");
  with_normals.replace(with_normals.find(R"({"buffer": 1, "byteLength": 3000}])"), 34, R"({"buffer": 1, "byteLength": 3000}, {"buffer": 2, "byteLength": 36}])");
  with_normals.replace(with_normals.rfind("]}"), 2, R"(, {"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"}]})");
  const scene shared = parse_gltf(with_normals, false, "shared.gltf", {}, limits);
  CHECK(shared.geometry.triangle_count() == 1002);
  CHECK(shared.geometry.vertices.size() == 3 + 4);
  for (std::size_t i = 0; i < 3000; ++i) {
    CHECK(shared.geometry.indices[i] == i % 3);
    if (i >= 3) break;
  }
  CHECK(shared.geometry.vertices[0].normal == glm::vec3(0, 0, 1));
  check_scene(shared);
}

TEST_CASE("a doubleSided material is noted: every surface is lit on its normal's side") {
  const auto notes_of = [](bool double_sided) {
    std::string text = triangle_gltf(triangle_data_uri);
    text.insert(text.size() - 1, std::string(R"(, "materials": [{"doubleSided": )") + (double_sided ? "true" : "false") + "}]");
    const std::string primitive = R"("attributes": {"POSITION": 0}})";
    text.replace(text.find(primitive), primitive.size(), R"("attributes": {"POSITION": 0}, "material": 0})");
    return parse_gltf(text, false, "sided.gltf", {}).notes;
  };
  const auto mentions = [](const std::vector<std::string>& notes) {
    for (const std::string& note : notes)
      if (note.find("doubleSided") != std::string::npos && note.find("the side its normal faces") != std::string::npos) return true;
    return false;
  };
  CHECK(mentions(notes_of(true)));
  CHECK_FALSE(mentions(notes_of(false)));
}

namespace {

std::string base64_of(const void* data, std::size_t size) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = static_cast<const unsigned char*>(data);
  std::string out;
  for (std::size_t i = 0; i < size; i += 3) {
    std::uint32_t group = static_cast<std::uint32_t>(bytes[i]) << 16;
    if (i + 1 < size) group |= static_cast<std::uint32_t>(bytes[i + 1]) << 8;
    if (i + 2 < size) group |= bytes[i + 2];
    out += alphabet[group >> 18 & 63];
    out += alphabet[group >> 12 & 63];
    out += i + 1 < size ? alphabet[group >> 6 & 63] : '=';
    out += i + 2 < size ? alphabet[group & 63] : '=';
  }
  return out;
}

// A glTF of one primitive in `mode` over `points` (z = 0), with byte `indices` when given.
std::string primitive_gltf(int mode, const std::vector<glm::vec2>& points, const std::vector<std::uint8_t>& indices) {
  std::vector<float> xyz;
  for (const glm::vec2& p : points) xyz.insert(xyz.end(), {p.x, p.y, 0.0f});
  const std::size_t bytes = xyz.size() * 4;
  std::string text = R"({"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "mode": )" +
                     std::to_string(mode) + (indices.empty() ? "" : R"(, "indices": 1)") + R"(}]}], "accessors": [{"bufferView": 0, "componentType": 5126, "count": )" +
                     std::to_string(points.size()) + R"(, "type": "VEC3"})";
  if (!indices.empty()) text += R"(, {"bufferView": 1, "componentType": 5121, "count": )" + std::to_string(indices.size()) + R"(, "type": "SCALAR"})";
  text += R"(], "bufferViews": [{"buffer": 0, "byteLength": )" + std::to_string(bytes) + "}";
  if (!indices.empty()) text += R"(, {"buffer": 1, "byteLength": )" + std::to_string(indices.size()) + "}";
  text += R"(], "buffers": [{"byteLength": )" + std::to_string(bytes) + R"(, "uri": "data:application/octet-stream;base64,)" + base64_of(xyz.data(), bytes) + R"("})";
  if (!indices.empty())
    text += R"(, {"byteLength": )" + std::to_string(indices.size()) + R"(, "uri": "data:application/octet-stream;base64,)" + base64_of(indices.data(), indices.size()) + R"("})";
  return text + "]}";
}

// The first `count` triangles of a loaded scene (frame_mesh's floor comes after them), as the
// points of their corners in order.
std::vector<std::array<glm::vec2, 3>> first_triangles(const scene& loaded, std::size_t count) {
  REQUIRE(loaded.geometry.triangle_count() >= count);
  std::vector<std::array<glm::vec2, 3>> out;
  for (std::size_t t = 0; t < count; ++t) {
    std::array<glm::vec2, 3> corners;
    for (std::size_t k = 0; k < 3; ++k) corners[k] = glm::vec2(loaded.geometry.vertices[loaded.geometry.indices[3 * t + k]].position);
    out.push_back(corners);
  }
  return out;
}

float signed_area(const std::array<glm::vec2, 3>& t) { return 0.5f * ((t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[1].y - t[0].y) * (t[2].x - t[0].x)); }

}  // namespace

TEST_CASE("triangle strips and fans are read as the glTF specification numbers them, indexed or not, every triangle wound as the first") {
  // A zigzag strip 0-1-2-3-4 along x: triangles (0 1 2), (1 3 2), (2 3 4); all clockwise seen
  // from +z, as the first is.
  const std::vector<glm::vec2> zigzag = {{0, 0}, {0, 1}, {1, 0}, {1, 1}, {2, 0}};
  const std::vector<std::array<glm::vec2, 3>> strip = {{{{0, 0}, {0, 1}, {1, 0}}}, {{{0, 1}, {1, 1}, {1, 0}}}, {{{1, 0}, {1, 1}, {2, 0}}}};
  CHECK(first_triangles(parse_gltf(primitive_gltf(5, zigzag, {}), false, "strip.gltf", {}), 3) == strip);
  // The same strip through indices into shuffled vertices.
  const std::vector<glm::vec2> shuffled = {zigzag[3], zigzag[0], zigzag[4], zigzag[1], zigzag[2]};
  const scene indexed = parse_gltf(primitive_gltf(5, shuffled, {1, 3, 4, 0, 2}), false, "strip.gltf", {});
  CHECK(first_triangles(indexed, 3) == strip);
  CHECK(indexed.geometry.triangle_count() == 3 + 2);  // and frame_mesh's floor
  for (const auto& t : strip) CHECK(signed_area(t) < 0.0f);
  // A fan around the origin: (1 2 0), (2 3 0), (3 4 0), all counter-clockwise.
  const std::vector<glm::vec2> around = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {-1, 1}};
  const std::vector<std::array<glm::vec2, 3>> fan = {{{{1, 0}, {1, 1}, {0, 0}}}, {{{1, 1}, {0, 1}, {0, 0}}}, {{{0, 1}, {-1, 1}, {0, 0}}}};
  CHECK(first_triangles(parse_gltf(primitive_gltf(6, around, {}), false, "fan.gltf", {}), 3) == fan);
  CHECK(first_triangles(parse_gltf(primitive_gltf(6, {around[4], around[3], around[2], around[1], around[0]}, {4, 3, 2, 1, 0}), false, "fan.gltf", {}), 3) == fan);
  for (const auto& t : fan) CHECK(signed_area(t) > 0.0f);
  // Fewer than three corners: nothing to draw, named as such.
  CHECK_THROWS_WITH_AS(parse_gltf(primitive_gltf(5, {{0, 0}, {1, 0}}, {}), false, "short.gltf", {}), doctest::Contains("no triangles in its scene"), vplkit::error);
  // Points and lines are still not drawn.
  CHECK_THROWS_WITH_AS(parse_gltf(primitive_gltf(1, zigzag, {}), false, "lines.gltf", {}), doctest::Contains("points and lines are not drawn"), vplkit::error);
}

TEST_CASE("Khronos' Asset-Generator strips and fans (Mesh_PrimitiveMode_04, 05, 11, 12) give the square the triangle lists (06, 13) give, facing +z") {
  const fs::path folder = "/usr/share/assimp/models/glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode";
  if (!fs::is_directory(folder)) {
    MESSAGE("skipped: assimp-testmodels is not installed");
    return;
  }
  for (const char* number : {"04", "05", "06", "11", "12", "13"}) {
    CAPTURE(number);
    const scene loaded = load_gltf(folder / ("Mesh_PrimitiveMode_" + std::string(number) + ".gltf"));
    REQUIRE(loaded.geometry.triangle_count() == 2 + 2);  // the square's two and frame_mesh's floor
    float area = 0.0f;
    for (const auto& t : first_triangles(loaded, 2)) {
      CHECK(signed_area(t) > 0.0f);  // counter-clockwise seen from +z: the side the samples show
      area += signed_area(t);
    }
    CHECK(area == doctest::Approx(1.0f));  // the unit square, covered once
    for (std::size_t i = 0; i < 6; ++i) CHECK(loaded.geometry.vertices[loaded.geometry.indices[i]].normal == glm::vec3(0, 0, 1));
  }
}

TEST_CASE("KHR_draco_mesh_compression: assimp's Draco 2CylinderEngine decodes to the triangles of its uncompressed GLB") {
  const fs::path compressed = "/usr/share/assimp/models/glTF2/draco/2CylinderEngine.gltf";
  const fs::path plain = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
  if (!fs::is_regular_file(compressed) || !fs::is_regular_file(plain)) {
    MESSAGE("skipped: assimp-testmodels is not installed");
    return;
  }
  const scene from_draco = load_gltf(compressed), from_glb = load_gltf(plain);
  for (const std::string& note : from_draco.notes) CHECK(note.find("KHR_draco_mesh_compression") == std::string::npos);  // read, not noted
  // The triangles as corner positions. Draco's encoder drops degenerate triangles and quantizes
  // positions (here by up to 0.11 in a model 836 across: 1.3 x 10^-4 of it): every triangle of
  // the GLB with area must have one of Draco's with every corner within 2.5 x 10^-4 of the
  // model's diagonal, in the same order up to rotation (so wound the same), each of Draco's
  // matched once (the closest unused one).
  const auto triangles_of = [](const scene& s, bool skip_degenerate) {
    std::vector<std::array<glm::vec3, 3>> out;
    const mesh& m = s.geometry;
    for (std::size_t t = 0; t + 6 < m.indices.size(); t += 3) {  // without frame_mesh's floor, the last two
      const std::array<glm::vec3, 3> corners = {m.vertices[m.indices[t]].position, m.vertices[m.indices[t + 1]].position, m.vertices[m.indices[t + 2]].position};
      if (skip_degenerate && glm::length(glm::cross(corners[1] - corners[0], corners[2] - corners[0])) == 0.0f) continue;
      out.push_back(corners);
    }
    return out;
  };
  const std::vector<std::array<glm::vec3, 3>> decoded = triangles_of(from_draco, false), expected = triangles_of(from_glb, true);
  CHECK(from_glb.geometry.triangle_count() - 2 > expected.size());  // the GLB has degenerate triangles Draco dropped
  REQUIRE(decoded.size() == expected.size());
  glm::vec3 low(1e30f), high(-1e30f);
  for (const auto& t : expected)
    for (const glm::vec3& p : t) low = glm::min(low, p), high = glm::max(high, p);
  const float tolerance = 2.5e-4f * glm::length(high - low), cell = 4.0f * tolerance;
  CHECK(tolerance < 0.25f);  // well under the GLB's shortest edges (1 % are under 1.1)
  const auto key = [&](const glm::vec3& p) {
    const glm::ivec3 c(glm::floor(p / cell));
    return (static_cast<std::int64_t>(c.x) * 73856093) ^ (static_cast<std::int64_t>(c.y) * 19349663) ^ (static_cast<std::int64_t>(c.z) * 83492791);
  };
  std::unordered_multimap<std::int64_t, std::size_t> by_cell;
  for (std::size_t i = 0; i < decoded.size(); ++i) by_cell.emplace(key((decoded[i][0] + decoded[i][1] + decoded[i][2]) / 3.0f), i);
  std::vector<bool> used(decoded.size(), false);
  std::size_t matched = 0;
  for (const auto& t : expected) {
    const glm::vec3 centre = (t[0] + t[1] + t[2]) / 3.0f;
    std::size_t best = decoded.size();
    float best_distance = tolerance;
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto [begin, end] = by_cell.equal_range(key(centre + cell * glm::vec3(dx, dy, dz)));
          for (auto at = begin; at != end; ++at) {
            if (used[at->second]) continue;
            const auto& d = decoded[at->second];
            for (std::size_t r = 0; r < 3; ++r) {
              const float distance = std::max({glm::length(d[r] - t[0]), glm::length(d[(r + 1) % 3] - t[1]), glm::length(d[(r + 2) % 3] - t[2])});
              if (distance < best_distance) best_distance = distance, best = at->second;
            }
          }
        }
    if (best < decoded.size()) {
      used[best] = true;
      ++matched;
    }
  }
  CHECK(matched == expected.size());
}

TEST_CASE("glTF 1.0 is named as such: its asset.version, a number 1 or a GLB container of version 1") {
  CHECK_THROWS_WITH_AS(parse_gltf(R"({"asset": {"version": "1.0"}, "meshes": {"box": {"primitives": []}}})", false, "old.gltf", {}),
                       doctest::Contains("old.gltf: a glTF 1.0 file (asset.version 1.0); vplkit reads glTF 2.0 only"), vplkit::error);
  CHECK_THROWS_WITH_AS(parse_gltf(R"({"asset": {"version": 1}, "accessors": {"a": {}}})", false, "old.gltf", {}),
                       doctest::Contains("old.gltf: a glTF 1.0 file (asset.version 1)"), vplkit::error);
  const std::string json = R"({"asset": {"version": "1.0"}})";
  std::string glb = "glTF";
  for (const std::uint32_t word : {1u, static_cast<std::uint32_t>(20 + json.size()), static_cast<std::uint32_t>(json.size()), 0u})
    glb.append(reinterpret_cast<const char*>(&word), 4);
  glb += json;
  CHECK_THROWS_WITH_AS(parse_gltf(glb, true, "old.glb", {}), doctest::Contains("old.glb: a glTF 1.0 file (GLB container version 1)"), vplkit::error);
  // 2.0 is not mistaken for it, nor a version that only starts with 1.
  CHECK_THROWS_WITH_AS(parse_gltf(R"({"asset": {"version": "2.0"}})", false, "new.gltf", {}), doctest::Contains("no triangles"), vplkit::error);
  CHECK_THROWS_WITH_AS(parse_gltf(R"({"asset": {"version": "10.0"}})", false, "odd.gltf", {}), doctest::Contains("no triangles"), vplkit::error);
  // assimp's glTF 1.0 files, where installed.
  const fs::path folder = "/usr/share/assimp/models/glTF";
  if (!fs::is_directory(folder)) return;
  int named = 0;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder)) {
    const std::string extension = entry.path().extension().string();
    if (extension != ".gltf" && extension != ".glb") continue;
    CAPTURE(entry.path().string());
    CHECK_THROWS_WITH_AS(load_gltf(entry.path()), doctest::Contains("a glTF 1.0 file"), vplkit::error);
    ++named;
  }
  CHECK(named == 7);
}

TEST_CASE("KHR_draco_mesh_compression in a .gltf and in a .glb (its JSON chunk rewritten): the same cube, edgebreaker and sequential") {
  // The fuzz seeds: a unit cube (12 triangles) encoded by libdraco, with normals (edgebreaker) and
  // without (sequential); the .glb holds the first's data in its binary chunk.
  const fs::path seeds = fs::path(VPLKIT_TEST_SOURCE_DIR) / "fuzz" / "corpus" / "gltf";
  const scene text = load_gltf(seeds / "draco-cube-edgebreaker-normals.gltf"), binary = load_gltf(seeds / "draco-cube-edgebreaker-normals.glb"),
              sequential = load_gltf(seeds / "draco-cube-sequential.gltf");
  for (const scene* s : {&text, &binary, &sequential}) {
    REQUIRE(s->geometry.triangle_count() == 12 + 2);  // and frame_mesh's floor
    // A closed cube: the triangles' areas add up to 6 and their area vectors cancel (all wound
    // outward or all inward; outward: each points away from the centre).
    double area = 0.0;
    for (std::size_t t = 0; t < 36; t += 3) {
      const glm::vec3 a = s->geometry.vertices[s->geometry.indices[t]].position, b = s->geometry.vertices[s->geometry.indices[t + 1]].position,
                      c = s->geometry.vertices[s->geometry.indices[t + 2]].position;
      const glm::vec3 normal = glm::cross(b - a, c - a);
      area += 0.5 * glm::length(normal);
      CHECK(glm::dot(normal, (a + b + c) / 3.0f - glm::vec3(0.5f)) > 0.0f);
    }
    CHECK(area == doctest::Approx(6.0).epsilon(1e-3));
  }
  // The decoded normals (quantized to 8 bits) are the faces' own.
  for (std::size_t t = 0; t < 36; ++t) {
    const vertex& v = binary.geometry.vertices[binary.geometry.indices[t]];
    CHECK(std::fabs(glm::dot(v.normal, glm::vec3(1.0f))) == doctest::Approx(1.0f).epsilon(0.02));  // a unit axis
  }
  for (std::size_t i = 0; i < text.geometry.vertices.size(); ++i) CHECK(text.geometry.vertices[i].position == binary.geometry.vertices[i].position);
  // Damaged Draco data is named.
  std::ifstream in(seeds / "draco-cube-sequential.gltf");
  std::string damaged((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t magic = damaged.find("RFJBQ08");  // "DRACO" in base64
  REQUIRE(magic != std::string::npos);
  damaged.replace(magic, 4, "QUJD");  // "ABC"
  CHECK_THROWS_WITH_AS(parse_gltf(damaged, false, "damaged.gltf", {}), doctest::Contains("damaged.gltf: mesh 0 primitive 0 KHR_draco_mesh_compression: not Draco data"),
                       vplkit::error);
}

namespace {

// A textured triangle glTF: one primitive per entry of `image_uris` (each its own material and
// texture, naming that image), positions and texture coordinates from uv.bin.
std::string textured_gltf(const std::vector<std::string>& image_uris) {
  std::string primitives, materials, textures, images;
  for (std::size_t i = 0; i < image_uris.size(); ++i) {
    const std::string n = std::to_string(i), comma = i == 0 ? "" : ",";
    primitives += comma + R"({"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": )" + n + "}";
    materials += comma + R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": )" + n + "}}}";
    textures += comma + R"({"source": )" + n + "}";
    images += comma + R"({"uri": ")" + image_uris[i] + R"("})";
  }
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}], "meshes": [{"primitives": [)" + primitives +
         R"(]}], "materials": [)" + materials + R"(], "textures": [)" + textures + R"(], "images": [)" + images +
         R"(], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},)"
         R"( {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}], "bufferViews": [{"buffer": 0, "byteLength": 36},)"
         R"( {"buffer": 0, "byteOffset": 36, "byteLength": 24}], "buffers": [{"byteLength": 60, "uri": "uv.bin"}]})";
}

// A w x h PNG of one grey `level`.
void write_png(const fs::path& path, int w, int h, std::uint8_t level) {
  const std::vector<std::uint8_t> bytes = encode_png(w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, level));
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

TEST_CASE("textures: one image file named by four images is decoded once; all of a scene's texels with mipmaps count against one budget") {
  const gltf_folder folder;
  {
    const float uv_bin[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    std::ofstream(folder.root / "scene" / "uv.bin", std::ios::binary).write(reinterpret_cast<const char*>(uv_bin), sizeof uv_bin);
  }
  write_png(folder.root / "scene" / "big.png", 64, 32, 100);
  write_png(folder.root / "scene" / "other.png", 64, 32, 200);
  // 64 x 32 with mipmaps: 4 x (2048 + 512 + 128 + 32 + 8 + 2 + 1) texels' bytes.
  CHECK(texture_bytes_with_mipmaps(64, 32) == 4 * (2048 + 512 + 128 + 32 + 8 + 2 + 1));
  const std::uint64_t one = texture_bytes_with_mipmaps(64, 32);

  // Four images (two spellings of the path among them) of one file: one texture, decoded once,
  // which every material samples; it fits a budget of one texture.
  gltf_limits limits;
  limits.textures.max_scene_bytes = one;
  const scene four = load_gltf(folder.write("four.gltf", textured_gltf({"big.png", "big.png", "./big.png", "big%2Epng"})), limits);
  REQUIRE(four.geometry.materials != nullptr);
  const material_library& library = *four.geometry.materials;
  CHECK(library.textures.size() == 1);
  REQUIRE(library.materials.size() == 4);
  for (const surface_material& material : library.materials) CHECK(material.texture == 0);

  // Two different files do not fit that budget: the second is refused, naming it and the budget.
  const std::string refused = load_error(folder.write("two.gltf", textured_gltf({"big.png", "other.png"})), limits);
  CHECK(refused.find("two.gltf: image 1 (other.png): its 64x32 texels with mipmaps (" + std::to_string(one) + " bytes) would bring the scene's decoded textures to " +
                     std::to_string(2 * one) + " bytes, more than the " + std::to_string(one) + " bytes budget for a scene's textures "
                     "(gltf_limits::textures.max_scene_bytes)") != std::string::npos);
  limits.textures.max_scene_bytes = 2 * one;
  CHECK(load_gltf(folder.root / "scene" / "two.gltf", limits).geometry.materials->textures.size() == 2);

  // The header's claim is charged before decoding: a PNG claiming 8192 x 8192, with no data at all,
  // is refused by a smaller budget, not by the decoder (which would name the missing data).
  std::string claim = "\x89PNG\r\n\x1a\n";
  claim += std::string("\0\0\0\x0dIHDR\0\0\x20\0\0\0\x20\0\x08\x06\0\0\0", 21);
  claim += std::string(4, '\0');  // CRC, never checked: the budget refuses first
  std::ofstream(folder.root / "scene" / "claim.png", std::ios::binary) << claim;
  limits.textures.max_scene_bytes = std::uint64_t{1} << 28;
  CHECK(load_error(folder.write("claim.gltf", textured_gltf({"claim.png"})), limits)
            .find("image 0 (claim.png): its 8192x8192 texels with mipmaps (357913940 bytes) would bring the scene's decoded textures to 357913940 bytes, more than "
                  "the 256 MiB budget") != std::string::npos);
}

TEST_CASE("named nodes: each names the run of triangles it and its children added, in the walk's order") {
  const fs::path scenes = fs::path(VPLKIT_TEST_SOURCE_DIR) / ".." / "bench" / "scenes";
  // room-a: "table" is a parent of its top and four legs (five boxes of 12 triangles), rotated.
  const scene room = load_gltf(scenes / "room-a.gltf");
  const auto find = [&](const scene& s, const std::string& name) {
    const auto found = std::find_if(s.nodes.begin(), s.nodes.end(), [&](const scene_node& n) { return n.name == name; });
    REQUIRE(found != s.nodes.end());
    return *found;
  };
  const scene_node table = find(room, "table"), top = find(room, "table top"), leg = find(room, "table leg 3"), sofa = find(room, "sofa seat");
  CHECK(table.index_count == 5u * 36u);
  CHECK(top.index_count == 36u);
  CHECK(top.first_index >= table.first_index);
  CHECK(leg.first_index + leg.index_count <= table.first_index + table.index_count);
  CHECK((sofa.first_index + sofa.index_count <= table.first_index || sofa.first_index >= table.first_index + table.index_count));
  CHECK(find(room, "camera").index_count == 0u);
  // Every vertex of the top's run lies in the table top's box (1.2 x 0.04 x 0.7 at height 0.73).
  for (std::uint32_t i = top.first_index; i < top.first_index + top.index_count; ++i)
    CHECK(std::abs(room.geometry.vertices[room.geometry.indices[i]].position.y - 0.73f) <= 0.0201f);

  // fg-studio: the vase's run is its box, in its ceramic colour.
  const scene studio = load_gltf(scenes / "fg-studio.gltf");
  const scene_node vase = find(studio, "vase");
  CHECK(vase.index_count == 36u);
  for (std::uint32_t i = vase.first_index; i < vase.first_index + vase.index_count; ++i) {
    const vertex& v = studio.geometry.vertices[studio.geometry.indices[i]];
    CHECK(v.albedo == glm::vec3(0.75f, 0.3f, 0.55f));
    CHECK(std::abs(v.position.x + 1.3f) <= 0.0801f);
    CHECK(std::abs(v.position.y - 0.9f) <= 0.1301f);
  }
  // A built-in scene and an OBJ have no nodes.
  CHECK(built_in_scene("cornell-box").nodes.empty());
}

namespace {

// A triangle with order.size() KHR_lights_punctual lights: array entry j is a point light, a spot
// or a sun as j % 3 is 0, 1 or 2, of intensity 2 + j, at (j, 3, -j). Node k + 1 holds entry
// order[k], so that the order the nodes meet and the array's order differ.
std::string lit_triangle_gltf(const std::vector<int>& order) {
  std::string lights, nodes = R"([{"mesh": 0})", scene_nodes = "[0";
  const int count = static_cast<int>(order.size());
  for (int k = 0; k < count; ++k) {
    const std::string intensity = std::to_string(2 + k);
    if (k % 3 == 0) lights += R"({"type": "point", "color": [1, 0.5, 0.25], "intensity": )" + intensity + R"(, "range": 4})";
    if (k % 3 == 1) lights += R"({"type": "spot", "intensity": )" + intensity + R"(, "spot": {"innerConeAngle": 0.2, "outerConeAngle": 0.5}})";
    if (k % 3 == 2) lights += R"({"type": "directional", "color": [0.5, 1, 1], "intensity": )" + intensity + "}";
    if (k + 1 < count) lights += ", ";
    // Light k at (k, 3, -k); the spots turned -90 degrees about x, aiming down (-z becomes -y).
    const std::string rotation = order[static_cast<std::size_t>(k)] % 3 == 1 ? R"(, "rotation": [-0.70710678, 0, 0, 0.70710678])" : "";
    nodes += R"(, {"extensions": {"KHR_lights_punctual": {"light": )" + std::to_string(order[static_cast<std::size_t>(k)]) +
             R"(}}, "translation": [)" + std::to_string(order[static_cast<std::size_t>(k)]) + ", 3, " +
             std::to_string(-order[static_cast<std::size_t>(k)]) + "]" + rotation + "}";
    scene_nodes += ", " + std::to_string(k + 1);
  }
  return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": )" + scene_nodes + R"(]}], "nodes": )" + nodes +
         R"(], "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, )"
         R"("type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}], "bufferViews": [{"buffer": 0, "byteLength": 36}], "buffers": [{"byteLength": 36, "uri": ")" +
         triangle_data_uri + R"("}], "extensionsUsed": ["KHR_lights_punctual"], "extensions": {"KHR_lights_punctual": {"lights": [)" + lights + "]}}}";
}

void check_same_lights(const std::vector<scene_light>& a, const std::vector<scene_light>& b) {
  REQUIRE(a.size() == b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    CAPTURE(k);
    REQUIRE(a[k].kind == b[k].kind);
    check_close(light_power(a[k]), light_power(b[k]), 1e-6f);
    if (a[k].kind == light_kind::point) check_close(a[k].point.position, b[k].point.position, 1e-6f);
    if (a[k].kind == light_kind::spot) {
      check_close(a[k].spot.position, b[k].spot.position, 1e-6f);
      check_close(a[k].spot.direction, b[k].spot.direction, 1e-6f);
      CHECK(a[k].spot.cos_inner == doctest::Approx(b[k].spot.cos_inner).epsilon(1e-6));
      CHECK(a[k].spot.cos_outer == doctest::Approx(b[k].spot.cos_outer).epsilon(1e-6));
    }
    if (a[k].kind == light_kind::directional) check_close(a[k].directional.direction, b[k].directional.direction, 1e-6f);
  }
}

}  // namespace

TEST_CASE("three KHR_lights_punctual lights (point, spot, sun) are read in the order the nodes meet them, with their values, and written back") {
  // The nodes meet entries 2, 0, 1 of the array: the scene's lights are in that order.
  const scene read = parse_gltf(lit_triangle_gltf({2, 0, 1}), false, "lit.gltf", {});
  REQUIRE(read.lights.size() == 3);
  REQUIRE(read.lights[0].kind == light_kind::directional);
  REQUIRE(read.lights[1].kind == light_kind::point);
  REQUIRE(read.lights[2].kind == light_kind::spot);
  // Photometric values one to one: intensity x colour, no unit conversion.
  check_close(read.lights[0].directional.irradiance, glm::vec3(4.0f) * glm::vec3(0.5f, 1.0f, 1.0f), 1e-6f);
  check_close(read.lights[0].directional.direction, glm::vec3(0, 0, -1), 1e-6f);
  check_close(read.lights[1].point.intensity, glm::vec3(2.0f) * glm::vec3(1.0f, 0.5f, 0.25f), 1e-6f);
  check_close(read.lights[1].point.position, glm::vec3(0, 3, 0), 1e-6f);
  check_close(read.lights[2].spot.intensity, glm::vec3(3.0f), 1e-6f);
  check_close(read.lights[2].spot.position, glm::vec3(1, 3, -1), 1e-6f);
  check_close(read.lights[2].spot.direction, glm::vec3(0, -1, 0), 1e-6f);
  CHECK(read.lights[2].spot.cos_inner == doctest::Approx(std::cos(0.2)).epsilon(1e-6));
  CHECK(read.lights[2].spot.cos_outer == doctest::Approx(std::cos(0.5)).epsilon(1e-6));
  // The range is not read: noted, never applied.
  CHECK(std::any_of(read.notes.begin(), read.notes.end(), [](const std::string& note) { return note.find("light range") != std::string::npos; }));

  const scene back = parse_gltf(gltf_text(read), false, "back.gltf", {});
  check_same_lights(back.lights, read.lights);
}

TEST_CASE("a glTF with 9 lights reads; check_scene and the writer refuse it naming --lights; two chosen lights pass, 8 round-trip") {
  scene many = parse_gltf(lit_triangle_gltf({0, 1, 2, 3, 4, 5, 6, 7, 8}), false, "nine.gltf", {});
  REQUIRE(many.lights.size() == 9);
  CHECK_THROWS_WITH_AS(check_scene(many), doctest::Contains("9 lights, at most 8 are rendered (choose some with --lights)"), vplkit::error);
  const std::vector<scene_light> all = many.lights;
  many.lights = {all[0], all[2]};
  CHECK_NOTHROW(check_scene(many));
  // The writer checks the scene as every consumer does: 9 lights are refused there too, 8 written and read back in order.
  many.lights = all;
  CHECK_THROWS_WITH_AS(gltf_text(many), doctest::Contains("choose some with --lights"), vplkit::error);
  many.lights.pop_back();
  check_same_lights(parse_gltf(gltf_text(many), false, "eight-back.gltf", {}).lights, many.lights);
}

namespace {

// The textured triangle of textured_gltf (uv.bin) with one material given as JSON.
std::string emissive_gltf(const std::string& material, const std::string& textures = "") {
  std::string text = R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],)"
                     R"( "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1, "TEXCOORD_1": 1}, "material": 0}]}], "materials": [)" +
                     material + "],";
  if (!textures.empty()) text += textures + ",";
  return text + R"( "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},)"
                R"( {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}], "bufferViews": [{"buffer": 0, "byteLength": 36},)"
                R"( {"buffer": 0, "byteOffset": 36, "byteLength": 24}], "buffers": [{"byteLength": 60, "uri": "uv.bin"}]})";
}

struct emissive_folder : gltf_folder {
  emissive_folder() {
    const float uv_bin[15] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    std::ofstream(root / "scene" / "uv.bin", std::ios::binary).write(reinterpret_cast<const char*>(uv_bin), sizeof uv_bin);
    write_png(root / "scene" / "glow.png", 4, 4, 200);
    write_png(root / "scene" / "base.png", 4, 4, 100);
  }
};

}  // namespace

TEST_CASE("emissive materials: emission = emissiveFactor x KHR_materials_emissive_strength, its texture with its own sampler, set and transform") {
  const emissive_folder folder;
  const auto material_of = [&](const std::string& name, const std::string& material, const std::string& textures = "") {
    const scene loaded = load_gltf(folder.write(name, emissive_gltf(material, textures)));
    REQUIRE(loaded.geometry.materials != nullptr);
    REQUIRE(loaded.geometry.materials->materials.size() == 1);
    CHECK(has_emission(loaded.geometry));
    return std::make_pair(loaded.geometry.materials->materials.front(), loaded);
  };
  // The factor alone: an untextured, opaque material that is kept for its emission.
  const auto [plain, plain_scene] = material_of("factor.gltf", R"({"emissiveFactor": [0.25, 0.5, 1]})");
  check_close(plain.emission, {0.25f, 0.5f, 1.0f}, 1e-6f);
  CHECK(plain.emission_texture == -1);
  CHECK(plain.texture == -1);
  // The strength multiplies the factor (both ways of writing the number).
  const auto [strong, strong_scene] =
      material_of("strength.gltf", R"({"emissiveFactor": [0.25, 0.5, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 40}}})");
  check_close(strong.emission, {10.0f, 20.0f, 40.0f}, 1e-6f);
  // A note says that it is drawn and lights nothing; none of the old "not read" lines.
  bool drawn_note = false;
  for (const std::string& note : strong_scene.notes) {
    CHECK(note.find("not read (surfaces do not emit)") == std::string::npos);
    CHECK(note.find("KHR_materials_emissive_strength") == std::string::npos);
    drawn_note = drawn_note || note.find("emissive materials are drawn as seen, but they do not light the scene") != std::string::npos;
  }
  CHECK(drawn_note);
  // The emissive texture: its own sampler (nearest), TEXCOORD_1 through KHR_texture_transform, scaled by 2.
  const std::string textures = R"("textures": [{"source": 0, "sampler": 0}, {"source": 1}], "samplers": [{"magFilter": 9728, "minFilter": 9728}],)"
                               R"( "images": [{"uri": "glow.png"}, {"uri": "base.png"}])";
  const auto [glowing, glowing_scene] = material_of(
      "texture.gltf",
      R"({"emissiveFactor": [1, 0.5, 0.25], "emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": 1, "scale": [2, 2]}}}})",
      textures);
  REQUIRE(glowing.emission_texture >= 0);
  CHECK(glowing.emission_sampler.mag == texture_filter::nearest);
  CHECK(glowing.emission_texture_matrix[0][0] == doctest::Approx(2.0));
  CHECK(glowing.emission_texture_matrix[1][1] == doctest::Approx(2.0));
  // The closed form at any point of the triangle: factor x the grey's linear value.
  const glm::vec3 seen = surface_emission(glowing_scene.geometry, 0, {0.25f, 0.25f});
  check_close(seen, glm::vec3(1.0f, 0.5f, 0.25f) * srgb8_to_linear(200), 1e-5f);
  // Beside a base colour texture on another set, the emission texture is left out with a note;
  // on the same set it is kept.
  const auto [apart, apart_scene] = material_of(
      "apart.gltf", R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}, "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0, "texCoord": 1}})",
      textures);
  CHECK(apart.emission_texture == -1);
  CHECK(apart.texture >= 0);
  CHECK(std::any_of(apart_scene.notes.begin(), apart_scene.notes.end(),
                    [](const std::string& note) { return note.find("emissiveTexture on another TEXCOORD set") != std::string::npos; }));
  const auto [together, together_scene] = material_of(
      "together.gltf", R"({"pbrMetallicRoughness": {"baseColorTexture": {"index": 1}}, "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0}})", textures);
  CHECK(together.emission_texture >= 0);
  CHECK(together.texture >= 0);
  // A zero factor with a texture does not emit: no emission pass is needed.
  const scene dark = load_gltf(folder.write("dark.gltf", emissive_gltf(R"({"emissiveTexture": {"index": 0}})", textures)));
  CHECK_FALSE(has_emission(dark.geometry));
}

TEST_CASE("emissive materials: a negative, too large or non-finite factor or strength is refused naming the file and the material") {
  const emissive_folder folder;
  const auto refused = [&](const std::string& material) { return load_error(folder.write("bad.gltf", emissive_gltf(material))); };
  const auto strength = [](const std::string& value) {
    return R"({"name": "lamp", "emissiveFactor": [1, 1, 1], "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": )" + value + "}}}";
  };
  const std::string factor_range = "bad.gltf: material 0 'lamp': emissiveFactor must be 3 finite numbers in [0, 1]";
  CHECK(refused(R"({"name": "lamp", "emissiveFactor": [-0.5, 0, 0]})").find(factor_range + ", not [-0.5, 0, 0]") != std::string::npos);
  CHECK(refused(R"({"name": "lamp", "emissiveFactor": [2, 0, 0]})").find(factor_range) != std::string::npos);
  CHECK(refused(R"({"name": "lamp", "emissiveFactor": [1e400, 0, 0]})").find("bad.gltf") != std::string::npos);  // JSON's overflow: named, whoever refuses it
  const std::string two = refused(R"({"name": "lamp", "emissiveFactor": [1, 0]})");  // tinygltf's own check: named, with the file
  CHECK(two.find("bad.gltf") != std::string::npos);
  CHECK(two.find("emissiveFactor") != std::string::npos);
  const std::string strength_range = "bad.gltf: material 0 'lamp': KHR_materials_emissive_strength's emissiveStrength must be a finite number >= 0";
  CHECK(refused(strength("-1")).find(strength_range + ", not -1") != std::string::npos);
  CHECK(refused(strength("\"bright\"")).find(strength_range) != std::string::npos);
  CHECK(refused(strength("1e300")).find("bad.gltf: material 0 'lamp': emissiveFactor x emissiveStrength must be at most 60000 per channel") != std::string::npos);
  CHECK(refused(strength("1e400")).find("bad.gltf") != std::string::npos);
  // A texture slot's bad KHR_texture_transform texCoord names the slot it is in.
  const std::string textures = R"("textures": [{"source": 0}], "images": [{"uri": "glow.png"}])";
  const std::string tex_coord = load_error(folder.write(
      "bad.gltf", emissive_gltf(R"({"name": "lamp", "emissiveFactor": [1, 1, 1], "emissiveTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"texCoord": "one"}}}})",
                                textures)));
  CHECK(tex_coord.find("bad.gltf: material 0 'lamp' emissiveTexture KHR_texture_transform texCoord must be a finite number") != std::string::npos);
  // The largest allowed emission loads; a strength of 0 loads and does not emit.
  CHECK(load_gltf(folder.write("max.gltf", emissive_gltf(strength("60000")))).geometry.materials->materials.front().emission.r == 60000.0f);
  CHECK_FALSE(has_emission(load_gltf(folder.write("off.gltf", emissive_gltf(strength("0")))).geometry));
}
