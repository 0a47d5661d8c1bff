// vplkit::parity's GLSL: a kernel source made whole for one stage (fragment, vertex or compute)
// on one target, with its inputs, outputs, tables and uniform blocks declared.
#include <vplkit/parity/parity.hpp>

#include <sstream>

#include "frontend/parity/internal.hpp"

namespace vplkit::parity {

namespace {

std::string include_lines(const kernel_source& source) {
  std::string text;
  for (const auto& [name, value] : source.defines) text += "#define " + name + " " + value + "\n";
  for (const std::string& include : source.includes) text += "#include \"" + include + "\"\n";
  return text;
}

// The declarations of a run's tables and uniform blocks, after the includes (a block's struct
// comes from a lib file) and before the kernel's own declarations (which read them). Textures in a
// fragment or vertex run, storage buffers from binding `first_buffer` in a compute run (the vec4
// tables, then the uvec4 tables); the blocks' bindings follow the buffers on Vulkan (one set), and
// GL binds them by name.
std::string resource_declarations(const kernel_resources& resources, shader_stage stage, target where, int first_buffer) {
  std::ostringstream out;
  int binding = first_buffer;
  const std::string set = where == target::vulkan ? "set = 0, " : "";
  // vec4 tables, then uvec4 tables: the same declaration with its own types.
  const auto declare_table = [&](const std::string& name, int width, const char* type, const char* sampler) {
    if (stage == shader_stage::compute) {
      out << "layout(std430, " << set << "binding = " << binding++ << ") readonly buffer " << name << "_table { " << type << " " << name
          << "_texels[]; };\n" << type << " " << name << "(ivec2 texel) { return " << name << "_texels[texel.y * " << width << " + texel.x]; }\n";
    } else {
      out << "uniform " << sampler << " " << name << "_table;\n" << type << " " << name << "(ivec2 texel) { return texelFetch(" << name
          << "_table, texel, 0); }\n";
    }
  };
  for (const kernel_table& table : resources.tables) declare_table(table.name, table.width, "vec4", "sampler2D");
  for (const kernel_uint_table& table : resources.uint_tables) declare_table(table.name, table.width, "uvec4", "usampler2D");
  for (const kernel_block& block : resources.blocks) {
    out << "layout(std140";
    if (where == target::vulkan) out << ", " << set << "binding = " << binding++;
    out << ") uniform " << block.member << "_block {\n  " << block.type << " " << block.member << ";\n};\n";
  }
  return out.str();
}

}  // namespace

std::string detail::fragment_source(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  std::ostringstream out;
  out << glsl_preamble(where) << include_lines(source);
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "uniform sampler2D float_input" << i << ";\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "uniform usampler2D uint_input" << i << ";\n";
  int location = 0;
  for (int i = 0; i < source.float_outputs; ++i) out << "layout(location = " << location++ << ") out vec4 float_output" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "layout(location = " << location++ << ") out uvec4 uint_output" << i << ";\n";
  out << resource_declarations(resources, shader_stage::fragment, where, 0);
  out << source.declarations << "\nvoid main() {\n  ivec2 texel = ivec2(gl_FragCoord.xy);\n";
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "  vec4 fin" << i << " = texelFetch(float_input" << i << ", texel, 0);\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "  uvec4 uin" << i << " = texelFetch(uint_input" << i << ", texel, 0);\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  vec4 fout" << i << " = vec4(0.0);\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uvec4 uout" << i << " = uvec4(0u);\n";
  out << "  {\n" << source.body << "\n  }\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  float_output" << i << " = fout" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uint_output" << i << " = uout" << i << ";\n";
  out << "}\n";
  return out.str();
}

std::string detail::vertex_source(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  std::ostringstream out;
  out << glsl_preamble(where) << include_lines(source);
  int location = 0;
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "layout(location = " << location++ << ") in vec4 fin" << i << ";\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "layout(location = " << location++ << ") in uvec4 uin" << i << ";\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "out vec4 fout" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "flat out uvec4 uout" << i << ";\n";
  out << resource_declarations(resources, shader_stage::vertex, where, 0);
  out << source.declarations << "\nvoid main() {\n  ivec2 texel = ivec2(gl_VertexID % " << inputs.width << ", gl_VertexID / " << inputs.width << ");\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  fout" << i << " = vec4(0.0);\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uout" << i << " = uvec4(0u);\n";
  out << "  {\n" << source.body << "\n  }\n  gl_Position = vec4(0.0, 0.0, 0.0, 1.0);\n}\n";
  return out.str();
}

std::string detail::compute_source(const kernel_source& source, const kernel_inputs& inputs, target where, const kernel_resources& resources) {
  std::ostringstream out;
  const std::string set = where == target::vulkan ? "set = 0, " : "";
  out << glsl_preamble(where) << "layout(local_size_x = 64) in;\n" << include_lines(source);
  int binding = 0;
  for (std::size_t i = 0; i < inputs.floats.size(); ++i)
    out << "layout(std430, " << set << "binding = " << binding++ << ") readonly buffer float_input" << i << " { vec4 float_input" << i << "_values[]; };\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i)
    out << "layout(std430, " << set << "binding = " << binding++ << ") readonly buffer uint_input" << i << " { uvec4 uint_input" << i << "_values[]; };\n";
  for (int i = 0; i < source.float_outputs; ++i)
    out << "layout(std430, " << set << "binding = " << binding++ << ") writeonly buffer float_output" << i << " { vec4 float_output" << i << "_values[]; };\n";
  for (int i = 0; i < source.uint_outputs; ++i)
    out << "layout(std430, " << set << "binding = " << binding++ << ") writeonly buffer uint_output" << i << " { uvec4 uint_output" << i << "_values[]; };\n";
  out << resource_declarations(resources, shader_stage::compute, where, binding);
  out << source.declarations << "\nvoid main() {\n  uint index = gl_GlobalInvocationID.x;\n  if (index >= " << inputs.size()
      << "u) return;\n  ivec2 texel = ivec2(int(index % " << inputs.width << "u), int(index / " << inputs.width << "u));\n";
  for (std::size_t i = 0; i < inputs.floats.size(); ++i) out << "  vec4 fin" << i << " = float_input" << i << "_values[index];\n";
  for (std::size_t i = 0; i < inputs.uints.size(); ++i) out << "  uvec4 uin" << i << " = uint_input" << i << "_values[index];\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  vec4 fout" << i << " = vec4(0.0);\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uvec4 uout" << i << " = uvec4(0u);\n";
  out << "  {\n" << source.body << "\n  }\n";
  for (int i = 0; i < source.float_outputs; ++i) out << "  float_output" << i << "_values[index] = fout" << i << ";\n";
  for (int i = 0; i < source.uint_outputs; ++i) out << "  uint_output" << i << "_values[index] = uout" << i << ";\n";
  out << "}\n";
  return out.str();
}

}  // namespace vplkit::parity
