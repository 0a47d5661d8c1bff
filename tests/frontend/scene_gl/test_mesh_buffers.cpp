// mesh_buffers' chunked draws (frontend/scene_gl/mesh_buffers.hpp): a run of more triangles than
// draw_chunking's threshold is drawn in chunks with fences between them, which must draw every
// triangle once, in the mesh's order. The defaults only chunk runs of 2^20 triangles; here tiny
// chunks put a small mesh on that path.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <random>

#include <vplkit/gl/program.hpp>
#include <vplkit/parity/parity.hpp>

#include "frontend/core/error.hpp"
#include "frontend/gl/debug_output.hpp"
#include "frontend/gl/gl_object.hpp"
#include "frontend/gl/render_target.hpp"
#include "frontend/scene_gl/mesh_buffers.hpp"

using namespace vplkit;

namespace {

constexpr int target_side = 64;  // pixels of the render target

// Coplanar axis-aligned rectangles (two triangles each) of random albedo, overlapping, each
// covering the pixels [x0, x1] x [y0, y1] (edges a quarter pixel outside the outer pixel centres,
// so no centre lies on an edge; the diagonal's centres go to one triangle of the two by GL's
// rasterization rules). Quads 400..799 form a material range (untextured, opaque), so draw()
// runs three segments: plain, material, plain (of 800, 800 and 2 x (count - 800) triangles).
struct quad_mesh {
  mesh geometry;
  std::vector<glm::ivec4> rectangles;  // x0, y0, x1, y1
};

quad_mesh make_quads(int count, bool reversed) {
  std::mt19937 random(36);
  std::uniform_int_distribution<int> coordinate(0, target_side - 1);
  std::uniform_real_distribution<float> channel(0.0f, 1.0f);
  quad_mesh out;
  for (int q = 0; q < count; ++q) {
    int x0 = coordinate(random), x1 = coordinate(random), y0 = coordinate(random), y1 = coordinate(random);
    if (x0 > x1) std::swap(x0, x1);
    if (y0 > y1) std::swap(y0, y1);
    out.rectangles.push_back({x0, y0, x1, y1});
  }
  std::vector<glm::vec3> albedos;
  for (int q = 0; q < count; ++q) albedos.push_back({channel(random), channel(random), channel(random)});
  const auto ndc = [](float pixel) { return pixel / target_side * 2.0f - 1.0f; };
  for (int i = 0; i < count; ++i) {
    const int q = reversed ? count - 1 - i : i;
    const glm::ivec4 r = out.rectangles[static_cast<std::size_t>(q)];
    const float left = ndc(static_cast<float>(r.x) + 0.25f), right = ndc(static_cast<float>(r.z) + 0.75f);
    const float bottom = ndc(static_cast<float>(r.y) + 0.25f), top = ndc(static_cast<float>(r.w) + 0.75f);
    const auto first = static_cast<std::uint32_t>(out.geometry.vertices.size());
    for (const glm::vec2 corner : {glm::vec2(left, bottom), glm::vec2(right, bottom), glm::vec2(right, top), glm::vec2(left, top)})
      out.geometry.vertices.push_back({glm::vec3(corner, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f), albedos[static_cast<std::size_t>(q)]});
    for (const std::uint32_t corner : {0u, 1u, 2u, 0u, 2u, 3u}) out.geometry.indices.push_back(first + corner);
  }
  auto library = std::make_shared<material_library>();
  library->materials.push_back(surface_material{});
  library->materials.back().name = "plain material";
  out.geometry.materials = library;
  if (count >= 800) out.geometry.material_ranges.push_back({400 * 6, 400 * 6, 0});
  return out;
}

// The mesh drawn into an RGBA32F target: RGB blended "over" with a constant alpha of 1/2, so that
// the image depends on the order of the triangles; alpha added, so that it counts the fragments
// at each pixel. Also the primitives the vertex stage sent on (GL_PRIMITIVES_GENERATED).
struct drawn_mesh {
  image texels;
  std::uint64_t primitives = 0;
};

drawn_mesh draw_quads(const mesh& geometry, draw_chunking chunking) {
  const shader_library& shaders = parity::test_shaders();
  const program surfaces = link_program(
      "chunked draw test",
      {{shader_stage::vertex, shaders.expand_file("scene.vert")},
       {shader_stage::fragment, shaders.expand_text("#version 330 core\n"
                                                    "#include \"surface_material.glsl\"\n"
                                                    "in vec3 surface_albedo;\n"
                                                    "out vec4 colour;\n"
                                                    "void main() { colour = vec4(material_albedo(surface_albedo), 1.0); }\n",
                                                    "chunked draw test.frag")}});
  surfaces.use();
  surfaces.set("view_projection", glm::mat4(1.0f));
  const mesh_buffers buffers(geometry, chunking);
  framebuffer target(target_side, target_side, {texel_format::rgba32f}, false);
  target.bind();
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  glEnable(GL_BLEND);
  glBlendColor(0.0f, 0.0f, 0.0f, 0.5f);
  glBlendFuncSeparate(GL_CONSTANT_ALPHA, GL_ONE_MINUS_CONSTANT_ALPHA, GL_ONE, GL_ONE);
  const gl_query query(generate_query());
  glBeginQuery(GL_PRIMITIVES_GENERATED, query.get());
  buffers.draw(surfaces);
  glEndQuery(GL_PRIMITIVES_GENERATED);
  glDisable(GL_BLEND);
  drawn_mesh out;
  GLuint64 primitives = 0;
  glGetQueryObjectui64v(query.get(), GL_QUERY_RESULT, &primitives);
  out.primitives = primitives;
  out.texels = target.read_image(0);
  check_gl("the chunked draw test");
  return out;
}

bool same_bits(const image& a, const image& b) {
  return a.width == b.width && a.height == b.height && a.texels.size() == b.texels.size() &&
         std::memcmp(a.texels.data(), b.texels.data(), a.texels.size() * sizeof(glm::vec4)) == 0;
}

}  // namespace

TEST_CASE("chunked draws draw every triangle once, in order: the same image bit for bit as one draw call") {
  constexpr int quads = 1500;  // 3000 triangles in runs of 800, 800 and 1400
  const quad_mesh scene = make_quads(quads, false);
  // Fragments per pixel: one for each rectangle over its centre (of its two triangles, one).
  std::vector<int> expected_count(target_side * target_side, 0);
  for (const glm::ivec4& r : scene.rectangles)
    for (int y = r.y; y <= r.w; ++y)
      for (int x = r.x; x <= r.z; ++x) ++expected_count[static_cast<std::size_t>(y * target_side + x)];
  const auto check_counts = [&](const drawn_mesh& result) {
    REQUIRE(result.texels.texels.size() == expected_count.size());
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < expected_count.size(); ++i) wrong += result.texels.texels[i].a != static_cast<float>(expected_count[i]);
    CHECK(wrong == 0);
    CHECK(result.primitives == 2 * quads);
  };

  const drawn_mesh whole = draw_quads(scene.geometry, draw_chunking{});  // the defaults: one draw call per run
  check_counts(whole);
  // The order is visible: the same triangles drawn back to front give another image (else the
  // comparisons below could not see a chunk drawn out of order).
  const drawn_mesh reversed = draw_quads(make_quads(quads, true).geometry, draw_chunking{});
  check_counts(reversed);
  CHECK_FALSE(same_bits(whole.texels, reversed.texels));

  // Chunks of 1, 7 (runs not a multiple of it), 64 and 4096 triangles (one chunk, more than a run).
  for (const GLsizei chunk : {1, 7, 64, 4096}) {
    CAPTURE(chunk);
    const drawn_mesh chunked = draw_quads(scene.geometry, draw_chunking{0, chunk});
    check_counts(chunked);
    CHECK(same_bits(chunked.texels, whole.texels));
  }
  // At the threshold a run is one draw call; one triangle above it, chunked.
  for (const GLsizei threshold : {800, 799}) {
    CAPTURE(threshold);
    const drawn_mesh result = draw_quads(scene.geometry, draw_chunking{threshold, 7});
    check_counts(result);
    CHECK(same_bits(result.texels, whole.texels));
  }
}

TEST_CASE("a draw chunking outside its ranges is refused, naming it") {
  parity::test_shaders();
  const mesh geometry = make_quads(2, false).geometry;
  for (const draw_chunking bad : {draw_chunking{0, 0}, draw_chunking{-1, 7}, draw_chunking{0, -5}, draw_chunking{0, 1 << 30}}) {
    CAPTURE(bad.threshold_triangles);
    CAPTURE(bad.chunk_triangles);
    CHECK_THROWS_WITH_AS(mesh_buffers(geometry, bad), doctest::Contains("mesh draw chunking: the threshold must be"), error);
  }
}
