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
  /// A struct's field: its GLSL type ("float", "vec3", another struct's name) and whether it is an array.
  struct field {
    std::string type;
    bool array = false;
  };
  /// Adds the declarations of one stage's expanded source.
  void scan(const std::string& source);
  /// Whether `path` ("light.position", "slots.boundary_tangent[2]", "shadow_matrix[0]") names a
  /// declared uniform or a field of one; array indices are not range-checked.
  bool declares(const std::string& path) const;
  /// The declared uniforms, for messages: "irradiance, light, shadow_maps".
  std::string names() const;
  /// Every declared uniform and its type.
  const std::map<std::string, std::string>& uniforms() const { return uniform_types_; }
  /// The fields of the struct called `name`, or null when the source declares no such struct.
  const std::map<std::string, field>* struct_fields(const std::string& name) const;

 private:
  std::map<std::string, std::string> uniform_types_;                   // name -> type
  std::map<std::string, std::map<std::string, field>> struct_fields_;  // struct -> field -> type
};

}  // namespace vplkit
