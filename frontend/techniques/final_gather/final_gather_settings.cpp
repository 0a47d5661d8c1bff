#include "frontend/techniques/final_gather/final_gather_settings.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
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

namespace {

// A text setting's value is never empty: "none" stands for not given.
std::string or_none(const std::string& text) { return text.empty() ? std::string("none") : text; }

}  // namespace

const std::vector<setting<final_gather_setup, final_gather_technique>>& final_gather_settings_table() {
  // An entry is its field's member path: the default is the struct's initialiser, and get and
  // set come from the path.
  using entry = setting<final_gather_setup, final_gather_technique>;
  using S = final_gather_setup;
  using P = final_gather_settings;
  using I = irradiance_settings<float>;
  // The kernel struct the frame uploads (the member paths of .feeds() read it).
  const auto irradiance = [](const S& s) { return s.pipeline.irradiance; };
  const auto environment_map = [](const final_gather_technique& t) { return t.variant == final_gather_variant::environment_map; };
  static const std::vector<entry> table = {
      entry::extent("size", path_of(&S::pipeline, &P::width), path_of(&S::pipeline, &P::height), schema::closed_range(1, max_image_side), "pixels",
                    "final image size, N or WxH (the paper: 700)")
          .builds("the G-buffer and output targets")
          .not_live(),
      entry::choice("format", path_of(&S::pipeline, &P::format), {{"rgba16f", texel_format::rgba16f}, {"rgba32f", texel_format::rgba32f}},
                    "float format of the output targets (the cube map and G-buffer are rgba32f)")
          .builds("the output targets"),
      entry::number("min-distance", path_of(&S::pipeline, &P::irradiance, &I::min_distance))
          .feeds("cube_face.frag", "irradiance", irradiance, &I::min_distance)
          .feeds("final_gather_direct.frag", "irradiance", irradiance, &I::min_distance),
      entry::number("cube-resolution", path_of(&S::pipeline, &P::resolution), schema::closed_range(1, 64), "texels",
                    "M, the small cube map's face resolution (the paper: 4 or 2)")
          .feeds("cube_downsample.frag: resolution; final_gather_shade.frag: resolution")
          .builds("the small cube map's target"),
      entry::number("face-size", path_of(&S::pipeline, &P::face_size), schema::closed_range(1, max_cube_face_size), "texels",
                    "the cube map's face size before averaging (the paper: 256; its six faces lie side by side in one texture)")
          .feeds("cube_downsample.frag: face_size")
          .builds("the cube map faces' target"),
      // Only envmap samples its map: the other techniques make a 1 x 1 one whatever the setting.
      entry::number("environment-resolution", path_of(&S::pipeline, &P::environment_resolution), schema::closed_range(1, 256), "texels",
                    "K, the face resolution of the baseline's irradiance environment map")
          .read_by(environment_map, "the environment map")
          .feeds("environment_convolution.frag: environment_resolution; final_gather_shade.frag: environment_resolution")
          .builds("the environment map's target",
                  [](const S& s) {
                    const bool sampled = find_final_gather_technique(s.pipeline.technique).variant == final_gather_variant::environment_map;
                    return sampled ? std::to_string(s.pipeline.environment_resolution) : std::string("1");
                  }),
      entry::text("object", path_of(&S::object), "the dynamic object: sphere or an .obj file (meshes/bunny.obj)").builds("the object's mesh").not_live(),
      entry::point("object-position", path_of(&S::object_position), schema::closed_range(-max_object_coordinate, max_object_coordinate), "scene units",
                   "the object's centre x,y,z (the room is [-1,1]x[0,2]x[-1,1])")
          .feeds("cube_face.frag: reference_point; final_gather_shade.frag: reference_point")
          .kept_by_pipeline()
          .not_live(),
      entry::number("object-size", path_of(&S::object_size), schema::open_closed_range(0, 10), "scene units", "the object's size across (the room is 2 wide)")
          .builds("the object's mesh")
          .not_live(),
      entry::custom("object-node", setting_type::text, "",
                    "none, or a named node of --scene's glTF (with its children) as the object: taken out of the environment, drawn with its materials, "
                    "where the scene has it unless --object-at moves it",
                    [](const final_gather_setup& s) { return or_none(s.object_node); },
                    [](final_gather_setup& s, const std::string& text) { s.object_node = text == "none" ? std::string() : text; })
          .builds("the object's mesh")
          .not_live(),
      entry::custom("object-at", setting_type::text, "",
                    "none, or x,y,z[,scale]: the bottom centre of the object's bounding box at x,y,z, scale (default 1) times its own size (the node's, "
                    "or the file's in its own units); instead of object-position and object-size",
                    [](const final_gather_setup& s) { return or_none(s.object_at); },
                    [](final_gather_setup& s, const std::string& text) { s.object_at = text == "none" ? std::string() : text; })
          .builds("the object's mesh")
          .not_live(),
  };
  return table;
}

std::string parse_object_at(const std::string& text, object_placement& placement) {
  std::vector<double> values;
  std::size_t at = 0;
  bool well_formed = !text.empty();
  while (well_formed && at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string part = text.substr(at, comma - at);
    std::size_t used = 0;
    try {
      values.push_back(std::stod(part, &used));
    } catch (const std::exception&) {
      well_formed = false;  // not a number, or out of double's range
    }
    well_formed = well_formed && used == part.size() && !part.empty();
    at = comma + 1;
  }
  // Built by append: GCC 12 warns falsely (-Wrestrict) on "'" + a temporary string.
  const std::string shown = std::string(1, '\'').append(excerpt(text, 60)).append(1, '\'');
  if (!well_formed || (values.size() != 3 && values.size() != 4)) return "expected x,y,z or x,y,z,scale, not " + shown;
  for (std::size_t i = 0; i < 3; ++i)
    if (!(std::abs(values[i]) <= max_object_coordinate))
      return shown + ": x, y and z must be finite and within " + format_real(max_object_coordinate) + " of the origin";
  if (values.size() == 4 && !(values[3] > 0.0 && values[3] <= 1e6)) return shown + ": the scale must be > 0 (and at most 1e6)";
  placement.bottom_centre = glm::vec3(static_cast<float>(values[0]), static_cast<float>(values[1]), static_cast<float>(values[2]));
  placement.scale = values.size() == 4 ? static_cast<float>(values[3]) : 1.0f;
  return {};
}

std::string object_key(const final_gather_setup& setup) {
  return setup.object + "\n" + setup.object_node + "\n" + setup.object_at + "\n" + format_real(setup.object_size);
}

std::string validate(const final_gather_setup& setup) {
  const final_gather_settings& settings = setup.pipeline;
  try {
    find_final_gather_technique(settings.technique);
  } catch (const error& failure) {
    return failure.what();
  }
  if (const std::string problem = check_settings(final_gather_settings_table(), setup); !problem.empty()) return problem;
  // One way to say each thing: a node or a file; --object-at or the centre and the size.
  const final_gather_setup defaults;
  const bool centre_or_size = setup.object_position != defaults.object_position || setup.object_size != defaults.object_size;
  object_placement placement;
  if (!setup.object_at.empty()) {
    if (const std::string problem = parse_object_at(setup.object_at, placement); !problem.empty()) return "--object-at " + problem;
    if (centre_or_size) return "--object-at places the object: give it or --object-position and --object-size, not both";
  }
  if (!setup.object_node.empty()) {
    if (setup.object != defaults.object) return "--object-node names the object in the scene: give it or --object, not both";
    if (centre_or_size && setup.object_at.empty())
      return "--object-position and --object-size place --object's mesh; the node --object-node names stays where the scene has it, or "
             "give --object-at x,y,z[,scale]";
  }
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
