// Users' scenes as authored (issue 25), through the RSM pipeline: a floor textured half red, half
// blue (PNG and JPEG, through the OBJ reader's map_Kd) shows its colours; a red-textured wall
// tints the white floor's indirect light; a closed room without camera or light is seen lit from
// inside; the indirect light is linear in the light's intensity.
#include <doctest/doctest.h>

#include <turbojpeg.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "frontend/image/image_files.hpp"
#include "frontend/scene/obj_loader.hpp"
#include "frontend/techniques/rsm/rsm_pipeline.hpp"
#include <vplkit/parity/doctest.hpp>

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

struct scene_folder {
  fs::path root = fs::temp_directory_path() / ("vplkit-scenes-" + std::to_string(std::random_device{}()));
  scene_folder() { fs::create_directories(root); }
  ~scene_folder() { fs::remove_all(root); }
  fs::path write(const std::string& name, const std::string& bytes) const {
    std::ofstream(root / name, std::ios::binary) << bytes;
    return root / name;
  }
};

// w x h RGBA8: `left` in the left half, `right` in the right half.
std::vector<std::uint8_t> halves(int w, int h, glm::u8vec3 left, glm::u8vec3 right) {
  std::vector<std::uint8_t> rgba;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::u8vec3 c = x < w / 2 ? left : right;
      rgba.insert(rgba.end(), {c.r, c.g, c.b, 255});
    }
  return rgba;
}

std::string png_bytes(int w, int h, const std::vector<std::uint8_t>& rgba) {
  const std::vector<std::uint8_t> png = encode_png(w, h, rgba);
  return std::string(png.begin(), png.end());
}

std::string jpeg_bytes(int w, int h, const std::vector<std::uint8_t>& rgba) {
  tjhandle encoder = tjInitCompress();
  unsigned char* out = nullptr;
  unsigned long size = 0;
  REQUIRE(tjCompress2(encoder, rgba.data(), w, 0, h, TJPF_RGBA, &out, &size, TJSAMP_444, 90, 0) == 0);
  std::string bytes(reinterpret_cast<const char*>(out), size);
  tjFree(out);
  tjDestroy(encoder);
  return bytes;
}

rsm_pipeline_settings small_rsm_settings() {
  rsm_pipeline_settings settings;
  settings.width = settings.height = 64;
  settings.rsm_size = 128;
  return settings;
}

scene posed(std::string name, mesh geometry, glm::vec3 eye, glm::vec3 target, glm::vec3 light_position, glm::vec3 light_target, float intensity) {
  scene s;
  s.name = std::move(name);
  s.geometry = std::move(geometry);
  s.view.position = eye;
  s.view.target = target;
  s.lights.emplace_back();
  s.lights[0].spot.position = light_position;
  s.lights[0].spot.direction = glm::normalize(light_target - light_position);
  s.lights[0].spot.intensity = glm::vec3(intensity);
  s.lights[0].spot.cos_inner = std::cos(glm::radians(50.0f));
  s.lights[0].spot.cos_outer = std::cos(glm::radians(70.0f));
  return s;
}

// Mean linear RGB over the pixels [x0, x1) x [y0, y1) (rows from the bottom, as the image stores them).
glm::vec3 mean_of(const image& picture, int x0, int x1, int y0, int y1) {
  glm::dvec3 sum(0.0);
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) sum += glm::dvec3(picture.at(x, y));
  return glm::vec3(sum / double((x1 - x0) * (y1 - y0)));
}

}  // namespace

TEST_CASE("authored scenes: a floor textured half red, half blue shows red and blue (PNG and JPEG)") {
  const scene_folder folder;
  const std::vector<std::uint8_t> rgba = halves(64, 64, {220, 20, 20}, {20, 20, 220});
  folder.write("halves.png", png_bytes(64, 64, rgba));
  folder.write("halves.jpg", jpeg_bytes(64, 64, rgba));
  for (const std::string format : {"png", "jpg"}) {
    CAPTURE(format);
    folder.write("floor.mtl", "newmtl floor\nKd 1 1 1\nmap_Kd halves." + format + "\n");
    const fs::path obj = folder.write("floor.obj", "mtllib floor.mtl\nv -2 0 2\nv 2 0 2\nv 2 0 -2\nv -2 0 -2\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                                   "vn 0 1 0\nusemtl floor\nf 1/1/1 2/2/1 3/3/1 4/4/1\n");
    // Seen from straight above, -x on the left: u = 0 at x = -2 is the texture's red half.
    rsm_pipeline pipeline(parity::test_shaders(), posed("floor", load_obj(obj), {0, 4, 0.001f}, {0, 0, 0}, {0, 3, 0.001f}, {0, 0, 0}, 2.0f), small_rsm_settings());
    const image radiance = pipeline.render().radiance;
    const glm::vec3 left = mean_of(radiance, 8, 24, 16, 48), right = mean_of(radiance, 40, 56, 16, 48);
    CAPTURE(left);
    CAPTURE(right);
    CHECK(left.r >= 2.0f * left.b);
    CHECK(right.b >= 2.0f * right.r);
  }
}

TEST_CASE("authored scenes: a red-textured wall on a white material tints the floor's indirect light") {
  const scene_folder folder;
  folder.write("red.png", png_bytes(8, 8, halves(8, 8, {230, 10, 10}, {230, 10, 10})));
  folder.write("wall.mtl", "newmtl white\nKd 0.8 0.8 0.8\nnewmtl wall\nKd 1 1 1\nmap_Kd red.png\n");
  const fs::path obj = folder.write("wall.obj", "mtllib wall.mtl\nv -3 0 3\nv 3 0 3\nv 3 0 -3\nv -3 0 -3\nv -3 0 -1\nv 3 0 -1\nv 3 3 -1\nv -3 3 -1\n"
                                                "vt 0 1\nvt 1 1\nvt 1 0\nvt 0 0\nvn 0 1 0\nvn 0 0 1\nusemtl white\nf 1//1 2//1 3//1 4//1\n"
                                                "usemtl wall\nf 5/1/2 6/2/2 7/3/2 8/4/2\n");
  rsm_pipeline pipeline(parity::test_shaders(), posed("wall", load_obj(obj), {0, 2.5f, 4}, {0, 0.3f, -1}, {0, 4, 3}, {0, 0, -1}, 10.0f), small_rsm_settings());
  const glm::vec3 floor = mean_of(pipeline.render().indirect, 16, 48, 0, 20);  // the bottom of the image: the floor
  CAPTURE(floor);
  CHECK(floor.r >= 1.5f * floor.b);
}

TEST_CASE("authored scenes: a closed room without camera or light is seen lit from inside") {
  mesh room;
  {
    mesh box;
    add_box(box, {0.0f, 1.5f, 0.0f}, {6.0f, 3.0f, 5.0f}, 0.0f, glm::vec3(0.73f));
    for (vertex& v : box.vertices) v.normal = -v.normal;  // the walls face inwards
    for (std::size_t i = 0; i < box.indices.size(); i += 3) std::swap(box.indices[i + 1], box.indices[i + 2]);
    room = box;
  }
  add_box(room, {0.0f, 0.4f, 0.0f}, {2.0f, 0.8f, 1.2f}, 0.0f, glm::vec3(0.73f));
  add_box(room, {1.9f, 0.6f, 1.4f}, {0.8f, 1.2f, 0.8f}, 20.0f, glm::vec3(0.73f));
  rsm_pipeline pipeline(parity::test_shaders(), frame_mesh("room", room), small_rsm_settings());
  const image radiance = pipeline.render().radiance;
  std::size_t black = 0;
  double sum = 0.0;
  for (int y = 0; y < radiance.height; ++y)
    for (int x = 0; x < radiance.width; ++x) {
      const glm::vec3 c(radiance.at(x, y));
      black += glm::max(c.r, glm::max(c.g, c.b)) < 1e-3f ? 1 : 0;
      sum += (c.r + c.g + c.b) / 3.0;
    }
  const double pixels = double(radiance.width * radiance.height);
  CHECK(double(black) / pixels < 0.05);
  CHECK(sum / pixels > 0.05);
}

TEST_CASE("authored scenes: doubling the light's intensity doubles the indirect light") {
  scene source = built_in_scene("cornell-box");
  rsm_pipeline_settings settings = small_rsm_settings();
  settings.format = texel_format::rgba32f;
  const image once = rsm_pipeline(parity::test_shaders(), source, settings).render().indirect;
  source.lights[0].spot.intensity *= 2.0f;
  const image twice = rsm_pipeline(parity::test_shaders(), source, settings).render().indirect;
  double a = 0.0, b = 0.0;
  for (std::size_t i = 0; i < once.texels.size(); ++i) {
    a += once.texels[i].r + once.texels[i].g + once.texels[i].b;
    b += twice.texels[i].r + twice.texels[i].g + twice.texels[i].b;
  }
  REQUIRE(a > 0.0);
  CHECK(b / a == doctest::Approx(2.0).epsilon(0.01));
}
