// The uniforms a program's GLSL source declares, with the fields of its structs, so that setting
// a uniform by name can tell a misspelled or missing name (an error) from a declared uniform the
// linker removed because the variant does not read it (a no-op, as in GL). The scan is of the
// expanded source (after #include), with comments skipped; it reads `struct Name { ... };` and
// `uniform Type name;` / `uniform Type name[N];` declarations, the only forms vplkit's shaders use,
// and uniform blocks, `[layout(...)] uniform Block { Type member; ... } [instance];`, whose
// members a buffer holds (program::set_uniform_block, vplkit/std140.hpp).
#pragma once

#include <map>
#include <set>
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
  /// Every member of a uniform block and its type; a block with an instance name is listed as its
  /// instance, of the block's type, which struct_fields() then lists the members of.
  const std::map<std::string, std::string>& block_members() const { return block_member_types_; }
  /// Whether the source declares a uniform block of this name.
  bool declares_block(const std::string& name) const { return blocks_.count(name) != 0; }
  /// The declared uniform blocks, for messages.
  std::string block_names() const;
  /// The fields of the struct called `name`, or null when the source declares no such struct.
  const std::map<std::string, field>* struct_fields(const std::string& name) const;

 private:
  std::map<std::string, std::string> uniform_types_;                   // name -> type
  std::map<std::string, std::map<std::string, field>> struct_fields_;  // struct -> field -> type
  std::map<std::string, std::string> block_member_types_;              // block member -> type
  std::set<std::string> blocks_;
};

}  // namespace vplkit
