// The technique families: every technique that the command line, the viewer and the sweep offer,
// with its family's settings (one description per setting, frontend/core/setting.hpp) and the
// pipeline that draws it (frontend/techniques/pipeline.hpp). The one place that knows all three
// families; a fourth is one more entry here.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "frontend/core/setting.hpp"
#include <vplkit/gl/program.hpp>
#include "frontend/scene/scene.hpp"
#include "frontend/techniques/pipeline.hpp"

namespace vplkit {

struct technique_entry {
  std::string name;         ///< the CLI name, e.g. "rsm-alg6"
  std::string description;  ///< one line
};

struct technique_family {
  std::string name;   ///< "rsm", "lightwave", "final-gather"
  std::string title;  ///< "reflective shadow maps with visibility ([RSMV])"
  std::vector<technique_entry> techniques;
  /// The scene drawn when none is given; "" for a family that draws its own (final gathering:
  /// the room around its object, which its settings choose).
  std::string default_scene;
  /// A family that draws its own room unless --scene gives one (final gathering: the user's scene
  /// around the object); make_pipeline gets null without --scene.
  bool scene_optional = false;
  /// The technique's settings at their defaults.
  std::function<std::unique_ptr<technique_settings>(const std::string& technique)> make_settings;
  /// Its pipeline over `source` (null for a family without a scene). Throws vplkit::error when
  /// the pipeline refuses the settings or the scene.
  std::function<std::unique_ptr<pipeline>(const shader_library&, const scene* source, const technique_settings&)> make_pipeline;
  /// The technique whose indirect light, the same frame without visibility, shows what a
  /// technique's visibility removes (Fig. 5.1c of [RSMV]); "" when the technique has none.
  std::function<std::string(const std::string& technique)> visibility_baseline;
  /// Who renders a --poses sequence in one pipeline (pipeline::draw_next), as the option's scope
  /// says it: "the RSM techniques (direct, rsm-*)"; "" for a family whose pipelines do not.
  std::string sequence_readers;
  /// How the family ranks a configuration against its base configuration (`vplkit sweep
  /// --reference base`), from the frames per second it gains over the base and the % similarity to
  /// the base's image it keeps; empty when the family has no such rank. The sweep writes it as the
  /// column `rank`, titled base_rank_title.
  std::function<double(double fps_gain, double similarity_percent)> base_rank;
  std::string base_rank_title;  ///< e.g. "[LW] Eq. 5.3 (Table 5.10)"

  bool reads_scene() const { return !default_scene.empty(); }
  /// Whether --scene may be given: a family that reads a scene, or draws its own unless given one.
  bool takes_scene() const { return reads_scene() || scene_optional; }
  /// Whether it draws a scene (make_pipeline gets one) when --scene is given or not.
  bool draws_scene(bool scene_given) const { return reads_scene() || (scene_optional && scene_given); }
  bool has(const std::string& technique) const;
  std::vector<std::string> technique_names() const;
};

const std::vector<technique_family>& technique_families();
/// The family of `technique`. Throws vplkit::error "unknown technique '...' (known: ...)".
const technique_family& family_of(const std::string& technique);
/// Every technique of every family, in the families' order.
std::vector<std::string> technique_names();
/// Whether `technique` names a technique of any family.
bool is_technique(const std::string& technique);

/// The struct behind `settings`, for code that knows the family; throws vplkit::error for another.
template <typename Settings, typename Technique>
const Settings& settings_struct(const technique_settings& settings) {
  const auto* typed = dynamic_cast<const described_settings<Settings, Technique>*>(&settings);
  if (!typed) throw error("settings of technique " + settings.technique() + " are not of the expected family");
  return typed->value();
}

}  // namespace vplkit
