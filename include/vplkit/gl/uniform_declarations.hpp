// The uniforms a program's GLSL source declares, with the fields of its structs, so that setting
// a uniform by name can tell a misspelled or missing name (an error) from a declared uniform the
// linker removed because the variant does not read it (a no-op, as in GL). The scan is of the
// expanded source (after #include), with comments skipped; it reads `struct Name { ... };` and
// `uniform Type name;` / `uniform Type name[N];` declarations, the only forms vplkit's shaders use.
#pragma once

#include <map>
#include <string>

namespace vplkit {

class uniform_declarations {
 public:
  /// Adds the declarations of one stage's expanded source.
  void scan(const std::string& source);
  /// Whether `path` ("light.position", "slots.boundary_tangent[2]", "shadow_matrix[0]") names a
  /// declared uniform or a field of one; array indices are not range-checked.
  bool declares(const std::string& path) const;
  /// The declared uniforms, for messages: "irradiance, light, shadow_maps".
  std::string names() const;

 private:
  std::map<std::string, std::string> uniform_types_;                      // name -> type
  std::map<std::string, std::map<std::string, std::string>> struct_fields_;  // struct -> field -> type
};

}  // namespace vplkit
