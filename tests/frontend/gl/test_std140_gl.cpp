// vplkit/std140.hpp against a GL driver: every settings struct's std140_block, compiled with the
// shipped lib files that declare the twins, has every field at the offset (and array stride)
// std140.hpp gives, by GL_UNIFORM_OFFSET, and the size std140_size, by
// GL_UNIFORM_BLOCK_DATA_SIZE; a kernel fed by a uniform buffer of std140_bytes (through
// program::set_uniform_block) matches its C++ twin in the parity harness, and a buffer packed as
// the C++ struct lies does not; the example of docs/glsl-twins.md ("std140 from C++ and GLSL"),
// taken from the page at configure time, compiles and links.
//
// The checks need a GL 4.5 core context (the targets of issue 37; llvmpipe offers it): on less
// they are skipped, saying so. The offsets are checked in `#version 450 core` shaders; the
// UBO-fed kernel runs in the parity harness's GLSL 3.30, where std140 is the same.
#include <doctest/doctest.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "frontend/core/error.hpp"
#include "frontend/gl/gl.hpp"
#include <vplkit/parity/doctest.hpp>
#include <vplkit/parity/parity.hpp>
#include <vplkit/std140.hpp>

// The C++ half of the page's example, verbatim (tests/CMakeLists.txt extracts it).
#include "doc_examples/std140_upload.cpp"

using namespace vplkit;
using namespace vplkit::parity;

namespace {

// Empty when the current context is GL 4.5 or later, else why the checks are skipped.
std::string gl45_missing() {
  test_shaders();  // makes the context
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor >= 45) return "";
  return "skipped: the context is GL " + std::to_string(major) + "." + std::to_string(minor) + " (" + test_context_kind() +
         "), the std140 checks need 4.5 core";
}

// Every lib file that declares a settings twin, with the defines they need.
const char* const lib_prelude =
    "#version 450 core\n"
    "#define VPLKIT_RSM_PATTERN 0\n"
    "#define VPLKIT_VISIBILITY 6\n"
    "#include \"lib/rsm_gather.glsl\"\n"
    "#include \"lib/rsm_packing.glsl\"\n"
    "#include \"lib/shadow.glsl\"\n"
    "#include \"lib/bilateral.glsl\"\n"
    "#include \"lib/direct_light.glsl\"\n"
    "#include \"lib/lightwave.glsl\"\n"
    "#include \"lib/temporal_accumulation.glsl\"\n"
    "#include \"lib/voxel_visibility.glsl\"\n"
    // The fetches the lib files' kernels call (they are not run here, but the linker resolves them).
    "rsm_texel rsm_fetch(ivec2 texel) { return rsm_texel(vec3(0.0), vec3(0.0), vec3(0.0)); }\n"
    "float rsm_depth_fetch(ivec2 texel) { return 0.0; }\n"
    "bilateral_tap bilateral_fetch(ivec2 texel) { return bilateral_tap(vec3(0.0), 0.0, vec3(0.0)); }\n"
    "uvec4 voxel_fetch(ivec2 texel) { return uvec4(0u); }\n";

program link_with_vertex(const std::string& name, const std::string& fragment) {
  const shader_library& library = test_shaders();
  return link_program(name, {{shader_stage::vertex, library.expand_text("#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n", "v.vert")},
                             {shader_stage::fragment, library.expand_text(fragment, name + ".frag")}});
}

// The GLSL expression of a field's first number, for a main that reads every field (a std140
// block's members are all active once the block is, but reading each one says so outright).
std::string first_number(const std::string& member, const std140_field& field) {
  std::string value = member + "." + field.path + (field.array_size ? "[0]" : "");
  const char last = field.glsl_type.back();
  if (last >= '2' && last <= '4') value += ".x";
  return "float(" + value + ")";
}

template <typename Settings>
void check_offsets_against_gl() {
  const std::string name = settings_description<Settings>::name;
  const std::string block = name + "_block";
  const std::string member = "value";
  const std::vector<std140_field> fields = std140_fields<Settings>();
  std::string source = std::string(lib_prelude) + std140_block<Settings>(block, member) + "out vec4 colour;\nvoid main() {\n  colour = vec4(0.0";
  for (const std140_field& field : fields) source += " + " + first_number(member, field);
  source += ");\n}\n";
  const program linked = link_with_vertex("std140 " + name, source);

  const GLuint block_index = glGetUniformBlockIndex(linked.id(), block.c_str());
  REQUIRE(block_index != GL_INVALID_INDEX);
  GLint data_size = 0, active = 0;
  glGetActiveUniformBlockiv(linked.id(), block_index, GL_UNIFORM_BLOCK_DATA_SIZE, &data_size);
  glGetActiveUniformBlockiv(linked.id(), block_index, GL_UNIFORM_BLOCK_ACTIVE_UNIFORMS, &active);
  CHECK(static_cast<std::size_t>(data_size) == std140_size<Settings>);
  CHECK(static_cast<std::size_t>(active) == fields.size());  // GL has no member std140_fields lacks
  for (const std140_field& field : fields) {
    const std::string gl_name = member + "." + field.path + (field.array_size ? "[0]" : "");
    CAPTURE(gl_name);
    const char* names[] = {gl_name.c_str()};
    GLuint index = GL_INVALID_INDEX;
    glGetUniformIndices(linked.id(), 1, names, &index);
    REQUIRE_MESSAGE(index != GL_INVALID_INDEX, "GL has no uniform " << gl_name);
    GLint offset = -1, stride = -1, size = -1, in_block = -1;
    glGetActiveUniformsiv(linked.id(), 1, &index, GL_UNIFORM_OFFSET, &offset);
    glGetActiveUniformsiv(linked.id(), 1, &index, GL_UNIFORM_ARRAY_STRIDE, &stride);
    glGetActiveUniformsiv(linked.id(), 1, &index, GL_UNIFORM_SIZE, &size);
    glGetActiveUniformsiv(linked.id(), 1, &index, GL_UNIFORM_BLOCK_INDEX, &in_block);
    CHECK(in_block == static_cast<GLint>(block_index));
    CHECK(static_cast<std::size_t>(offset) == field.offset);
    CHECK(static_cast<std::size_t>(size) == (field.array_size ? field.array_size : 1u));
    CHECK(static_cast<std::size_t>(stride) == field.array_stride);  // 0 for a field that is not an array
  }
}

}  // namespace

TEST_CASE("std140: every settings struct's offsets, array strides and size are GL's (GL_UNIFORM_OFFSET, GL_UNIFORM_BLOCK_DATA_SIZE)") {
  if (const std::string missing = gl45_missing(); !missing.empty()) {
    MESSAGE(missing);
    return;
  }
  int checked = 0;
  for_each_glsl_twin_type([&](const auto& settings) {
    using settings_type = std::decay_t<decltype(settings)>;
    const std::string name = settings_description<settings_type>::name;
    CAPTURE(name);
    check_offsets_against_gl<settings_type>();
    ++checked;
  });
  CHECK(checked == static_cast<int>(glsl_twin_settings::size));
  MESSAGE("std140 offsets checked against GL for " << checked << " settings structs on " << test_context_kind());
}

// elevation_slots is where packing by hand goes wrong: a float[15] with a 16-byte stride.
TEST_CASE("parity: elevation_bucket with its slots from a uniform buffer of std140_bytes, exact; the C++ struct's bytes are not") {
  if (const std::string missing = gl45_missing(); !missing.empty()) {
    MESSAGE(missing);
    return;
  }
  random_inputs random(37);
  kernel_inputs inputs = grid_of(64, 64, 2);
  const elevation_slots<float> table = make_elevation_slots<float>(9);
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    inputs.floats[0][i] = glm::vec4(random.point(2.0f), 0.0f);
    inputs.floats[1][i] = glm::vec4(random.point(2.0f), 0.0f);
  }
  kernel_source source;
  source.name = "elevation_bucket (std140 block)";
  source.includes = {"lib/micro_linear_buffer.glsl"};
  source.declarations = std140_block<elevation_slots<float>>("slots_block", "slots");
  source.body = "uout0 = uvec4(uint(elevation_bucket(fin0.xyz, fin1.xyz, slots)), 0u, 0u, 0u);";
  source.uint_outputs = 1;
  std::vector<glm::uvec4> cpu(inputs.size());
  for (std::size_t i = 0; i < inputs.size(); ++i)
    cpu[i] = glm::uvec4(static_cast<unsigned>(elevation_bucket(glm::vec3(inputs.floats[0][i]), glm::vec3(inputs.floats[1][i]), table)), 0u, 0u, 0u);

  const kernel_outputs gpu = run_fragment(source, inputs, [&](const program& p) { p.set_uniform_block("slots_block", std140_bytes(table)); });
  // The same arithmetic as the default-block parity test of elevation_bucket: no flip allowed.
  require_parity(compare_exact("elevation_bucket from a std140 uniform buffer", gpu.uints[0], cpu, inputs, 0.0, 1));

  // The C++ struct's own bytes (tangents 4 apart), padded to the block's size: the GPU reads
  // tangents 16 bytes apart and buckets differently. The check above would catch such a writer.
  std::vector<std::byte> as_in_memory(std140_size<elevation_slots<float>>, std::byte{0});
  std::memcpy(as_in_memory.data(), &table, sizeof table);
  const kernel_outputs wrong = run_fragment(source, inputs, [&](const program& p) {
    p.set_uniform_block("slots_block", as_in_memory.data(), as_in_memory.size());
  });
  CHECK_FALSE(compare_exact("elevation_bucket from the C++ struct's bytes", wrong.uints[0], cpu, inputs, 0.0, 1).passed());
}

TEST_CASE("the std140 example of docs/glsl-twins.md compiles, links, and its upload fills the block") {
  if (const std::string missing = gl45_missing(); !missing.empty()) {
    MESSAGE(missing);
    return;
  }
  std::ifstream file(VPLKIT_DOC_EXAMPLES_DIR "/std140_gather.frag");
  REQUIRE(file);
  std::stringstream glsl;
  glsl << file.rdbuf();
  // The page's shader stops before main: read the block, so that it is active.
  const program linked = link_with_vertex("docs std140 example",
                                          glsl.str() + "out vec4 colour;\nvoid main() { colour = vec4(gather.slots.boundary_tangent[3]); }\n");
  rsm_gather_settings<float> settings;
  settings.slots = make_elevation_slots<float>(7);
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  upload_gather_settings(linked.id(), buffer, settings);
  GLint size = 0;
  glGetBufferParameteriv(GL_UNIFORM_BUFFER, GL_BUFFER_SIZE, &size);
  CHECK(static_cast<std::size_t>(size) == std140_size<rsm_gather_settings<float>>);
  float tangent = 0.0f;
  glGetBufferSubData(GL_UNIFORM_BUFFER, static_cast<GLintptr>(std140_offset(&rsm_gather_settings<float>::slots) + 16 + 3 * 16), sizeof tangent,
                     &tangent);
  CHECK(tangent == settings.slots.boundary_tangent[3]);
  glBindBuffer(GL_UNIFORM_BUFFER, 0);
  glDeleteBuffers(1, &buffer);
}
