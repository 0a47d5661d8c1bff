// vplkit/gl/settings_uniforms.hpp: every kernel settings struct with a GLSL twin has exactly
// the twin's fields, both ways (names, types, arrays), checked against the shipped
// shaders/lib/*.glsl; a program whose uniform struct misses a described field, declares one that
// nothing sets, or types one differently fails when it is built, naming the struct and the field;
// set_uniforms sets every field (read back from GL).
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/gl/debug_output.hpp"
#include "frontend/gl/gl.hpp"
#include <vplkit/gl/settings_uniforms.hpp>
#include <vplkit/parity/parity.hpp>
#include "tests/gl_test_helpers.hpp"

namespace fs = std::filesystem;
using namespace vplkit;

namespace {

// The declarations of every shipped lib file.
uniform_declarations shipped_lib_declarations() {
  uniform_declarations declarations;
  for (const fs::directory_entry& file : fs::directory_iterator(default_shader_dir() / "lib"))
    if (file.path().extension() == ".glsl") declarations.scan(read_file(file.path(), std::uintmax_t{1} << 20, "shader file"));
  return declarations;
}

using vplkit::testing::message_of;

std::string irradiance_program(const std::string& struct_body, const std::string& read = "min_distance") {
  return "#version 330 core\nstruct irradiance_settings {\n" + struct_body + "};\nuniform irradiance_settings irradiance;\nout vec4 colour;\n"
         "void main() { colour = vec4(irradiance." + read + "); }\n";
}

program link_fragment(const std::string& text) {
  const shader_library& library = parity::test_shaders();
  return link_program("test program", {{shader_stage::vertex, library.expand_text("#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n", "v.vert")},
                                       {shader_stage::fragment, library.expand_text(text, "f.frag")}});
}

}  // namespace

TEST_CASE("every settings struct's C++ fields are its GLSL struct's fields, both ways: names, types, arrays") {
  const uniform_declarations shipped = shipped_lib_declarations();
  // glsl_twin_settings is the list; its static_asserts tie it to the descriptions (a nested twin
  // left out, a struct without glsl_twin, two of one name do not compile).
  REQUIRE(glsl_twins().size() == glsl_twin_settings::size);
  for (const glsl_twin& twin : glsl_twins()) {
    CAPTURE(twin.name);
    const auto* declared = shipped.struct_fields(twin.name);
    REQUIRE_MESSAGE(declared != nullptr, "shaders/lib declares no struct " << twin.name);
    // C++ -> GLSL
    for (const glsl_twin::field& field : twin.fields) {
      CAPTURE(field.name);
      const auto found = declared->find(field.name);
      REQUIRE(found != declared->end());
      CHECK(found->second.type == field.type);
      CHECK(found->second.array == field.array);
    }
    // GLSL -> C++
    for (const auto& declared_field : *declared) {
      const std::string& name = declared_field.first;  // named: clang 14's CAPTURE cannot take a structured binding
      CAPTURE(name);
      bool described = false;
      for (const glsl_twin::field& field : twin.fields) described = described || field.name == name;
      CHECK(described);
    }
  }
}

TEST_CASE("a uniform struct unlike its C++ twin fails to build, naming the struct and the field") {
  parity::test_shaders();
  CHECK_NOTHROW(link_fragment(irradiance_program("  float min_distance;\n")));
  const std::string extra = message_of([] { link_fragment(irradiance_program("  float min_distance;\n  float scale;\n")); });
  CHECK(extra.find("GLSL struct irradiance_settings declares field 'scale' that the C++ irradiance_settings does not describe") != std::string::npos);
  CHECK(extra.find("would read 0") != std::string::npos);
  const std::string missing = message_of([] { link_fragment(irradiance_program("  float minimum_distance;\n", "minimum_distance")); });
  CHECK(missing.find("GLSL struct irradiance_settings has no field 'min_distance' that the C++ irradiance_settings sets (float)") != std::string::npos);
  const std::string typed = message_of([] { link_fragment(irradiance_program("  int min_distance;\n")); });
  CHECK(typed.find("declares 'min_distance' as int, the C++ irradiance_settings as float") != std::string::npos);
  // Nested: a twin inside another struct is checked too.
  const std::string nested = message_of([] {
    link_fragment("#version 330 core\nstruct irradiance_settings { float min_distance; int extra; };\nstruct holder { irradiance_settings inner; };\n"
                  "uniform holder h;\nout vec4 colour;\nvoid main() { colour = vec4(h.inner.min_distance); }\n");
  });
  CHECK(nested.find("declares field 'extra'") != std::string::npos);
  // An array where the C++ field is one value, and the other way round.
  const std::string slots = message_of([] {
    link_fragment("#version 330 core\nstruct elevation_slots { int count; float boundary_tangent; };\nuniform elevation_slots slots;\nout vec4 colour;\n"
                  "void main() { colour = vec4(slots.boundary_tangent); }\n");
  });
  CHECK(slots.find("declares 'boundary_tangent' as float, the C++ elevation_slots as float[]") != std::string::npos);
  // A twin held in a uniform block, with or without an instance name, is checked as well.
  const std::string in_block = message_of([] {
    link_fragment("#version 330 core\nstruct irradiance_settings { float min_distance; float scale; };\n"
                  "layout(std140) uniform lights { irradiance_settings irradiance; };\nout vec4 colour;\nvoid main() { colour = vec4(irradiance.scale); }\n");
  });
  CHECK(in_block.find("GLSL struct irradiance_settings declares field 'scale'") != std::string::npos);
  const std::string in_instance = message_of([] {
    link_fragment("#version 330 core\nstruct irradiance_settings { int min_distance; };\n"
                  "layout(std140) uniform lights { irradiance_settings irradiance; } block;\nout vec4 colour;\n"
                  "void main() { colour = vec4(block.irradiance.min_distance); }\n");
  });
  CHECK(in_instance.find("declares 'min_distance' as int, the C++ irradiance_settings as float") != std::string::npos);
  // A struct vplkit does not describe is the program's own business.
  CHECK_NOTHROW(link_fragment("#version 330 core\nstruct mine { float a; };\nuniform mine m;\nout vec4 colour;\nvoid main() { colour = vec4(m.a); }\n"));
}

TEST_CASE("set_uniforms sets every field of a nested settings struct, read back from GL") {
  parity::test_shaders();
  rsm_gather_settings<float> settings = default_rsm_gather_settings<float>(glm::ivec2(256, 128));
  settings.irradiance.min_distance = 0.125f;
  settings.radial.seed = 77u;
  settings.disk.samples = 33;
  // Every field reaches the output, so that none is optimised away.
  const program linked = link_fragment(
      "#version 330 core\n#define VPLKIT_RSM_PATTERN 0\n#define VPLKIT_VISIBILITY 0\n#include \"lib/rsm_gather.glsl\"\n"
      "rsm_texel rsm_fetch(ivec2 t) { return rsm_texel(vec3(0.0), vec3(0.0), vec3(0.0)); }\n"
      "uniform rsm_gather_settings settings;\nout vec4 colour;\n"
      "void main() {\n  float s = settings.irradiance.min_distance + float(settings.radial.paths + settings.radial.samples_per_path) +\n"
      "    settings.radial.min_radius + settings.radial.ring_ratio + settings.radial.path_turns + settings.radial.path_angle +\n"
      "    settings.radial.rotation_jitter + settings.radial.angle_jitter + settings.radial.scale_jitter + float(settings.radial.seed) +\n"
      "    float(settings.disk.samples) + settings.disk.max_radius + float(settings.disk.seed) + float(settings.slots.count) +\n"
      "    float(settings.rsm_size.x + settings.rsm_size.y);\n"
      "  for (int k = 0; k < VPLKIT_MAX_SLOTS - 1; ++k) s += settings.slots.boundary_tangent[k];\n  colour = vec4(s);\n}\n");
  set_uniforms(linked, "settings", settings);
  const auto read_float = [&](const std::string& name) {
    GLfloat value = -1.0f;
    glGetUniformfv(linked.id(), linked.location(name), &value);
    return value;
  };
  const auto read_int = [&](const std::string& name) {
    GLint value[2] = {-1, -1};
    glGetUniformiv(linked.id(), linked.location(name), value);
    return glm::ivec2(value[0], value[1]);
  };
  CHECK(read_float("settings.irradiance.min_distance") == 0.125f);
  CHECK(read_int("settings.radial.paths").x == settings.radial.paths);
  CHECK(read_float("settings.radial.ring_ratio") == settings.radial.ring_ratio);
  CHECK(read_float("settings.radial.scale_jitter") == settings.radial.scale_jitter);
  GLuint seed = 0;
  glGetUniformuiv(linked.id(), linked.location("settings.radial.seed"), &seed);
  CHECK(seed == 77u);
  CHECK(read_int("settings.disk.samples").x == 33);
  CHECK(read_float("settings.disk.max_radius") == settings.disk.max_radius);
  CHECK(read_int("settings.slots.count").x == settings.slots.count);
  for (int k = 0; k < micro_linear_buffer_max_slots - 1; ++k)
    CHECK(read_float("settings.slots.boundary_tangent[" + std::to_string(k) + "]") == settings.slots.boundary_tangent[k]);
  CHECK(read_int("settings.rsm_size") == glm::ivec2(256, 128));
  check_gl("reading back uniforms");
}
