// The glTF 2.0 reader and writer (frontend/scene/gltf_scene.hpp): a built-in scene written and
// read back is the same scene; Debian's assimp glTF2 test files each load or fail with a
// vplkit::error naming the file; hostile files fail with the problem named.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "frontend/core/error.hpp"
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
    REQUIRE(back.light.kind == original.light.kind);
    if (original.light.kind == light_kind::spot) {
      check_close(back.light.spot.position, original.light.spot.position, 1e-6f);
      check_close(back.light.spot.direction, original.light.spot.direction, 1e-6f);
      check_close(back.light.spot.intensity, original.light.spot.intensity, 1e-6f);
      CHECK(back.light.spot.cos_inner == doctest::Approx(original.light.spot.cos_inner).epsilon(1e-6));
      CHECK(back.light.spot.cos_outer == doctest::Approx(original.light.spot.cos_outer).epsilon(1e-6));
    } else {
      check_close(back.light.directional.direction, original.light.directional.direction, 1e-6f);
      check_close(back.light.directional.irradiance, original.light.directional.irradiance, 1e-6f);
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
