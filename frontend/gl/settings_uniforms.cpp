#include <vplkit/gl/settings_uniforms.hpp>

#include <set>

#include "frontend/core/error.hpp"

namespace vplkit {

namespace {

template <typename... Settings>
std::vector<glsl_twin> twins_of(settings_list<Settings...>) {
  return {glsl_twin_of<Settings>()...};
}

}  // namespace

const std::vector<glsl_twin>& glsl_twins() {
  static const std::vector<glsl_twin> twins = twins_of(glsl_twin_settings{});
  return twins;
}

namespace {

const glsl_twin* twin_named(const std::string& name) {
  for (const glsl_twin& twin : glsl_twins())
    if (twin.name == name) return &twin;
  return nullptr;
}

void check_struct(const uniform_declarations& declarations, const std::string& struct_name, const std::string& program_name,
                  std::set<std::string>& checked) {
  if (!checked.insert(struct_name).second) return;
  const auto* fields = declarations.struct_fields(struct_name);
  if (!fields) return;  // a basic type
  const glsl_twin* twin = twin_named(struct_name);
  const std::string where = "program " + program_name + ": GLSL struct " + struct_name;
  if (twin) {
    for (const glsl_twin::field& field : twin->fields) {
      const auto declared = fields->find(field.name);
      if (declared == fields->end())
        throw error(where + " has no field '" + field.name + "' that the C++ " + struct_name + " sets (" + field.type + (field.array ? "[]" : "") + ")");
      if (declared->second.type != field.type || declared->second.array != field.array)
        throw error(where + " declares '" + field.name + "' as " + declared->second.type + (declared->second.array ? "[]" : "") + ", the C++ " +
                    struct_name + " as " + field.type + (field.array ? "[]" : ""));
    }
    for (const auto& [name, declared] : *fields) {
      bool described = false;
      for (const glsl_twin::field& field : twin->fields) described = described || field.name == name;
      if (!described)
        throw error(where + " declares field '" + name + "' that the C++ " + struct_name + " does not describe: set_uniforms would never set it, and it would read 0");
    }
  }
  for (const auto& [name, declared] : *fields) check_struct(declarations, declared.type, program_name, checked);
}

}  // namespace

void check_glsl_twins(const uniform_declarations& declarations, const std::string& program_name) {
  std::set<std::string> checked;
  for (const auto& [name, type] : declarations.uniforms()) check_struct(declarations, type, program_name, checked);
  for (const auto& [name, type] : declarations.block_members()) check_struct(declarations, type, program_name, checked);
}

}  // namespace vplkit
