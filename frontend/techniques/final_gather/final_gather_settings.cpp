#include "frontend/techniques/final_gather/final_gather_settings.hpp"

#include <tuple>

#include "frontend/core/error.hpp"
#include "frontend/core/named_table.hpp"
#include "frontend/image/image.hpp"

namespace vplkit {

const std::vector<final_gather_technique>& final_gather_techniques() {
  static const std::vector<final_gather_technique> techniques = {
      {"finalgather-polygon", final_gather_variant::polygon, "polygon-to-point form factors (the paper's method, clipped)"},
      {"finalgather-point", final_gather_variant::point, "point-to-point form factors, a virtual light per texel"},
      {"envmap", final_gather_variant::environment_map, "one lookup of a convolved environment map (right at o only)"},
  };
  return techniques;
}

const final_gather_technique& find_final_gather_technique(const std::string& name) { return find_by_name(final_gather_techniques(), name, "final gathering technique"); }

const std::vector<setting<final_gather_setup, final_gather_technique>>& final_gather_settings_table() {
  using entry = setting<final_gather_setup, final_gather_technique>;
  // The kernel struct the frame uploads (the member paths of .feeds() read it).
  const auto irradiance = [](const final_gather_setup& s) { return s.pipeline.irradiance; };
  static const std::vector<entry> table = {
      entry::custom("size", setting_type::size, "pixels", "final image size, N or WxH (the paper: 700)",
                    [](const final_gather_setup& s) {
                      const final_gather_settings& p = s.pipeline;
                      return p.width == p.height ? std::to_string(p.width) : std::to_string(p.width) + "x" + std::to_string(p.height);
                    },
                    [](final_gather_setup& s, const std::string& text) { std::tie(s.pipeline.width, s.pipeline.height) = *parse_extent(text); })
          .within(schema::closed_range(1, max_image_side))
          .not_live(),
      entry::choice("format", [](auto& s) -> auto& { return s.pipeline.format; }, {{"rgba16f", texel_format::rgba16f}, {"rgba32f", texel_format::rgba32f}},
                    "float format of the output targets (the cube map and G-buffer are rgba32f)"),
      entry::number("min-distance", [](auto& s) -> auto& { return s.pipeline.irradiance.min_distance; },
                    describe_field(&irradiance_settings<float>::min_distance))
          .feeds("cube_face.frag", "irradiance", irradiance, &irradiance_settings<float>::min_distance)
          .feeds("final_gather_shade.frag", "irradiance", irradiance, &irradiance_settings<float>::min_distance),
      entry::number("cube-resolution", [](auto& s) -> auto& { return s.pipeline.resolution; }, schema::closed_range(1, 64), "texels",
                    "M, the small cube map's face resolution (the paper: 4 or 2)")
          .feeds("cube_downsample.frag: resolution; final_gather_shade.frag: resolution"),
      entry::number("face-size", [](auto& s) -> auto& { return s.pipeline.face_size; }, schema::closed_range(1, max_cube_face_size), "texels",
                    "the cube map's face size before averaging (the paper: 256; its six faces lie side by side in one texture)")
          .feeds("cube_downsample.frag: face_size"),
      entry::number("environment-resolution", [](auto& s) -> auto& { return s.pipeline.environment_resolution; }, schema::closed_range(1, 256), "texels",
                    "K, the face resolution of the baseline's irradiance environment map")
          .read_by([](const final_gather_technique& t) { return t.variant == final_gather_variant::environment_map; }, "the environment map")
          .feeds("environment_convolution.frag: environment_resolution; final_gather_shade.frag: environment_resolution"),
      entry::custom("object", setting_type::text, "", "the dynamic object: sphere or an .obj file (meshes/bunny.obj)",
                    [](const final_gather_setup& s) { return s.object; }, [](final_gather_setup& s, const std::string& text) { s.object = text; })
          .not_live(),
      entry::custom("object-position", setting_type::point, "scene units", "the object's centre x,y,z (the room is [-1,1]x[0,2]x[-1,1])",
                    [](const final_gather_setup& s) {
                      return format_real(s.object_position.x) + "," + format_real(s.object_position.y) + "," + format_real(s.object_position.z);
                    },
                    [](final_gather_setup& s, const std::string& text) {
                      const std::vector<double> point = *parse_point(text);
                      s.object_position = glm::vec3(static_cast<float>(point[0]), static_cast<float>(point[1]), static_cast<float>(point[2]));
                    })
          .within(schema::closed_range(-max_object_coordinate, max_object_coordinate))
          .feeds("cube_face.frag: reference_point; final_gather_shade.frag: reference_point")
          .not_live(),
      entry::number("object-size", [](auto& s) -> auto& { return s.object_size; }, schema::open_closed_range(0, 10), "scene units",
                    "the object's size across (the room is 2 wide)")
          .not_live(),
  };
  return table;
}

std::string validate(const final_gather_setup& setup) {
  const final_gather_settings& settings = setup.pipeline;
  try {
    find_final_gather_technique(settings.technique);
  } catch (const error& failure) {
    return failure.what();
  }
  if (const std::string problem = check_settings(final_gather_settings_table(), setup); !problem.empty()) return problem;
  if (settings.face_size % settings.resolution != 0)
    return "M = " + std::to_string(settings.resolution) + " does not divide the face size " + std::to_string(settings.face_size) +
           ": every small texel must average a whole block of face texels";
  if (const setting_problem problem = validate(settings.irradiance)) return problem.message();
  return {};
}

std::string validate(const final_gather_settings& settings) {
  final_gather_setup setup;
  setup.pipeline = settings;
  return validate(setup);
}

}  // namespace vplkit
