// vplkit render: one frame of any technique, headless, to images. --technique picks the family
// from the registry (frontend/techniques/registry.hpp); every setting is an option scoped to the
// techniques that read it (technique_options), so an option the technique ignores is an error.
// --reference measures the frame against ground truth (frontend/reference/quality.hpp) and
// --stats writes the settings in effect, the pass times and the quality as JSON. --poses renders
// a sequence in one pipeline (numbered frames, all or nothing) for the families that render sequences.
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <vplkit/version.hpp>

#include "frontend/cli/commands.hpp"
#include "frontend/cli/output.hpp"
#include "frontend/cli/technique_options.hpp"
#include "frontend/core/parallel.hpp"
#include "frontend/core/progress.hpp"
#include "frontend/reference/quality.hpp"
#include "frontend/scene/pose.hpp"

namespace vplkit::cli {

namespace {

struct render_state {
  technique_options options;
  std::string out;
  bool raw_indirect = false;
  std::string stats;
  std::string reference = "none";
  reference_options quality;
  option_scope reference_scope;  ///< --receiver-stride, --samples, --reference-seed
  std::string poses;             ///< --poses: a pose file, one frame per line
  double max_seconds = 0.0;      ///< --max-seconds: a --poses sequence stops after the frame that passes it; 0: no limit
};

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) >= 0x20) out += c;
  }
  return out + "\"";
}

// Who renders --poses sequences, from the families' descriptions (the command line names none).
std::string sequence_readers() {
  std::string readers;
  for (const technique_family& family : technique_families())
    if (!family.sequence_readers.empty()) readers += (readers.empty() ? "" : " and ") + family.sequence_readers;
  return readers;
}

std::string json_number(double value) { return std::isfinite(value) ? format_real(value) : "null"; }

std::string pass_json(const std::vector<pass_time>& passes) {
  std::string json = "[";
  double total = 0.0;
  for (const pass_time& pass : passes) {
    json += std::string(json.size() > 1 ? ", " : "") + "{\"pass\": " + json_string(pass.pass) + ", \"ms\": " + json_number(pass.milliseconds) + "}";
    total += pass.milliseconds;
  }
  return json + "], \"frame_ms\": " + json_number(total);
}

// "-0001" for frame 1 of a sequence of `count` frames (at least 4 digits, more for longer ones).
std::string frame_suffix(std::size_t frame, std::size_t count) {
  std::string number = std::to_string(frame);
  const std::size_t digits = std::max<std::size_t>(4, std::to_string(count).size());
  return "-" + std::string(digits - std::min(digits, number.size()), '0') + number;
}

// The frames of --poses, rendered in one pipeline (pipeline::draw_next: for the RSM techniques the
// pattern turns and the temporal accumulation blends with the history); nothing is written unless every frame renders.
// A long sequence reports its progress on stderr (a plain line every 5 s, or
// $VPLKIT_PROGRESS_SECONDS, with the time left, when stderr is not a terminal). --max-seconds
// (counted from the command's start) stops it after the frame during which the time ran out: the
// frames rendered until then, 1 to k, are written (all or nothing, as a whole sequence is), stderr
// says how many, and the exit code is exit_stopped_by_deadline, so a script can tell a shortened
// sequence from a whole one.
int render_sequence(const session& io, const render_state& s, const technique_settings& settings, output_set& files) {
  const double started = steady_seconds();
  const std::vector<pose_frame> frames = read_pose_file(s.poses, false);
  const headless_session gl(s.options.common);
  std::unique_ptr<scene> source;
  const std::unique_ptr<pipeline> drawn = make_posed_pipeline(gl.shaders, s.options.common, settings, source);
  // Every frame's files are kept in memory until the end (all or nothing): bound them.
  drawn->draw();
  drawn->collect_pass_times();
  const image first = drawn->output().read_image();
  const double bytes_per_frame = static_cast<double>(first.width) * first.height * (s.raw_indirect ? 31.0 : 27.0);
  if (bytes_per_frame * static_cast<double>(frames.size()) > 4.0 * 1024 * 1024 * 1024)
    throw error(s.poses + ": " + std::to_string(frames.size()) + " frames of " + std::to_string(first.width) + "x" + std::to_string(first.height) +
                " would hold more than 4 GiB until they are written; split the pose file");
  camera view = drawn->current_camera();
  // A pose file's --light moves the first light, as --light does.
  std::vector<scene_light> lights = drawn->current_lights();
  double total_ms = 0.0;
  progress_settings reporting = progress_on_stderr();
  const std::string deadline_name = "--max-seconds " + format_number(static_cast<float>(s.max_seconds));
  if (s.max_seconds > 0.0) {
    reporting.deadline = started + s.max_seconds;
    reporting.deadline_name = deadline_name;
  }
  progress_monitor progress("render --poses", frames.size(), "frames", reporting);
  std::size_t rendered_frames = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    // The deadline is checked between frames: the frame it fell in is finished and kept.
    if (i > 0 && (progress.stopped() || steady_seconds() >= reporting.deadline)) break;
    const pose_frame& frame = frames[i];
    const std::string where = s.poses + ":" + std::to_string(frame.line);
    if (frame.camera) {
      apply_pose(*frame.camera, view, where + ": --camera");
      drawn->set_camera(view);
    }
    if (frame.light) {
      if (lights.empty()) throw error(where + ": --light: the scene has no light to place");
      apply_pose(*frame.light, lights.front(), where + ": --light");
      drawn->set_light(0, lights.front());
    }
    drawn->draw_next();
    for (const pass_time& pass : drawn->collect_pass_times()) total_ms += pass.milliseconds;
    const std::string suffix = frame_suffix(i + 1, frames.size());
    files.add_png(files.sibling(suffix, ".png"), drawn->output().read_image());
    files.add_pfm(files.sibling(suffix + "-indirect", ".pfm"), drawn->indirect_output().read_image());
    files.add_pfm(files.sibling(suffix + "-direct", ".pfm"), drawn->direct_output().read_image());
    if (s.raw_indirect)
      if (const std::optional<image> raw = drawn->raw_indirect()) files.add_pfm(files.sibling(suffix + "-raw-indirect", ".pfm"), *raw);
    rendered_frames = i + 1;
    progress.advance();
  }
  const bool whole = rendered_frames == frames.size();
  if (whole) {
    progress.finish();
  } else if (reporting.terminal) {
    std::cerr << "\n";  // past the progress bar's line
  }
  io.out << drawn->describe() << "\n" << rendered_frames << " frames from " << s.poses << ", " << std::fixed << std::setprecision(1)
         << total_ms / static_cast<double>(rendered_frames) << " ms per frame (passes)\n";
  files.write(io.out);
  if (whole) return 0;
  std::cerr << "vplkit render: stopped by " << deadline_name << " after " << duration_text(steady_seconds() - started) << ": wrote frames 1 to "
            << rendered_frames << " of " << frames.size() << "; the other " << frames.size() - rendered_frames << " were not rendered (exit code "
            << exit_stopped_by_deadline << ")\n";
  return exit_stopped_by_deadline;
}

int run_render(const session& io, const render_state& s) {
  const technique_options& o = s.options;
  o.scope.require_read_by(o.technique, "technique");
  s.reference_scope.require_read_by(s.reference, "--reference");
  const std::unique_ptr<technique_settings> settings = make_technique_settings(o.given, o.technique);
  const technique_family& family = family_of(o.technique);
  const reference_kind kind = reference_from_name(s.reference);
  if (const std::string refusal = reference_refusal(kind, o.technique); !refusal.empty()) throw usage_error("--reference " + s.reference + ": " + refusal);
  output_set files(s.out, "output/" + std::filesystem::path(drawn_scene_name(o.common, *settings)).stem().string() + "-" + o.technique + ".png", ".png", "--out");
  if (!s.stats.empty() && std::filesystem::path(s.stats).extension() != ".json") throw usage_error("--stats must name a .json file, got " + shown(s.stats));
  if (!s.poses.empty() && (kind != reference_kind::none || !s.stats.empty())) throw usage_error("--poses renders a sequence: no --reference or --stats");
  if (s.poses.empty() && o.given.find("temporal-blend")) throw usage_error("--temporal-blend is read with --poses (a sequence), not for one frame");
  if (s.poses.empty() && s.max_seconds > 0.0) throw usage_error("--max-seconds bounds a --poses sequence, not one frame");
  if (io.dry_run) return 0;
  if (!s.poses.empty()) return render_sequence(io, s, *settings, files);

  const headless_session gl(o.common);
  std::unique_ptr<scene> source;
  std::unique_ptr<pipeline> drawn = make_posed_pipeline(gl.shaders, o.common, *settings, source);
  // The first frame pays for the shader compilers' lazy work (llvmpipe's JIT, a driver's first use
  // of a program); the tables report warmed-up frames: every pass, then what a camera move redraws.
  drawn->draw();
  drawn->collect_pass_times();
  drawn->draw();
  const std::vector<pass_time> every_pass = drawn->collect_pass_times();
  const image radiance = drawn->output().read_image();
  const image indirect = drawn->indirect_output().read_image();
  const image direct = drawn->direct_output().read_image();

  // Everything is rendered before anything is written, so a failure leaves no partial set.
  files.add_png(files.main(), radiance, exposure_scale(o.common, radiance, io.out));
  const bool has_indirect = drawn->has_indirect();
  const float exposure = has_indirect ? percentile_exposure(indirect) : 1.0f;
  if (has_indirect) files.add_png(files.sibling("-indirect", ".png"), indirect, exposure);
  // The indirect shadow factor as grey, linear (1 = white = not shadowed).
  if (const texture_2d* shadow = drawn->indirect_shadow_output()) files.add_png(files.sibling("-indirect-shadow", ".png"), red_as_grey(shadow->read_image()));
  // The indirect light, linear (0 for direct light only).
  files.add_pfm(files.sibling("-indirect", ".pfm"), indirect);
  // The direct light, linear: the shadowed direct irradiance (reference --method monte-carlo's -direct.pfm).
  files.add_pfm(files.sibling("-direct", ".pfm"), direct);
  if (s.raw_indirect) files.add_pfm(files.sibling("-raw-indirect", ".pfm"), *drawn->raw_indirect());

  // What a camera move costs: the camera "moved" onto itself, then only what that invalidated.
  drawn->set_camera(drawn->current_camera());
  drawn->draw_changed();
  const std::vector<pass_time> camera_moved = drawn->collect_pass_times();

  // Per light where the passes name their light (several lights): what each light costs.
  const light_times every_light = group_by_light(every_pass);
  io.out << drawn->describe() << "\nevery pass (the frame the papers time):\n" << format_pass_table(every_pass) << format_light_table(every_light)
         << "a frame after the camera moved (what the viewer redraws):\n" << format_pass_table(camera_moved);

  std::string quality_json;
  if (kind != reference_kind::none) {
    reference_options options = s.quality;
    options.kind = kind;
    options.threads = hardware_threads();
    scene_references references(gl.shaders, options, source.get());
    drawn->draw();
    drawn->collect_pass_times();
    const frame_quality quality = references.measure(*drawn, *settings);
    io.out << "quality against " << reference_name(kind) << " (" << quality.receivers << " receivers or pixels):\n| metric | value |\n|---|---:|\n";
    quality_json = ",\n  \"quality\": {\"reference\": " + json_string(reference_name(kind)) + ", \"receivers\": " + std::to_string(quality.receivers);
    // A relative number against a black reference does not exist: "undefined" and why in the
    // table, null in the JSON with the reason under "undefined", never a number to compare.
    std::string undefined_json;
    for (const quality_metric& metric : quality.metrics) {
      if (metric.defined) {
        io.out << "| " << metric.name << " | " << std::setprecision(6) << metric.value << " |\n";
        quality_json += ", " + json_string(metric.name) + ": " + json_number(metric.value);
      } else {
        io.out << "| " << metric.name << " | undefined: " << metric.why_undefined << " |\n";
        quality_json += ", " + json_string(metric.name) + ": null";
        undefined_json += (undefined_json.empty() ? "" : ", ") + json_string(metric.name) + ": " + json_string(metric.why_undefined);
      }
    }
    io.out << references.coverage() << "\n";
    if (!undefined_json.empty()) quality_json += ", \"undefined\": {" + undefined_json + "}";
    quality_json += ", \"covers\": " + json_string(references.coverage()) + "}";
  }
  if (!s.stats.empty()) {
    std::ostringstream json;
    json << "{\n  \"vplkit\": " << json_string(version_string) << ",\n  \"scene\": " << json_string(drawn->scene_name()) << ",\n  \"settings\": "
         << settings_json(*settings, 2) << ",\n  \"timing\": {\"method\": " << json_string(describe(timing_method_for_current_context()))
         << ",\n    \"every_pass\": {\"passes\": " << pass_json(every_pass) << ", \"per_light\": " << light_times_json(every_light) << "},\n    \"camera_moved\": {\"passes\": " << pass_json(camera_moved)
         << "}}" << quality_json << "\n}\n";
    files.add_text(s.stats, json.str());
  }
  if (const std::string baseline = has_indirect ? family.visibility_baseline(o.technique) : std::string(); !baseline.empty()) {
    // The same frame without visibility: what the approximation removes, amplified 8x relative
    // to the indirect image's exposure (Fig. 5.1c). Drawn last, once the frame's own pipeline is
    // released: the two side by side held the mesh on the GPU twice (a 2^21-triangle faceted mesh
    // is 300 MB a copy).
    drawn.reset();
    std::unique_ptr<technique_settings> without = settings->clone();
    without->set_technique(baseline);
    // The scene already loaded and posed is the baseline's too (the same family reads it).
    std::unique_ptr<scene> baseline_source;
    const std::unique_ptr<pipeline> reference = source ? family.make_pipeline(gl.shaders, source.get(), *without)
                                                       : make_posed_pipeline(gl.shaders, o.common, *without, baseline_source);
    reference->draw();
    files.add_png(files.sibling("-visibility-difference", ".png"), luminance_difference(reference->indirect_output().read_image(), indirect, 8.0f * exposure));
  }
  files.write(io.out);
  return 0;
}

}  // namespace

command add_render_command(CLI::App& app) {
  auto state = std::make_shared<render_state>();
  CLI::App* render = app.add_subcommand("render", "render a scene headless to PNG images (and the linear indirect light as PFM)");
  add_technique_options(*render, state->options);
  render->add_option("--out", state->out, "final image path (.png; folders are created) [output/<scene or object>-<technique>.png]; the other "
                                          "images go next to it");
  state->options.scope.add(render->add_flag("--raw-indirect", state->raw_indirect,
                                            "also write <out>-raw-indirect.pfm: the unfiltered gather at the indirect buffer's receivers (compare it "
                                            "with vplkit reference --method rsm-brute-force)"),
                           setting_readers("indirect-divisor"),
                           [](const std::string& technique) { return family_of(technique).make_settings(technique)->reads("indirect-divisor"); });
  state->options.scope.add(render->add_option("--poses", state->poses,
                                             "render a sequence in one pipeline: a file with one frame per line, each line --camera x,y,z,tx,ty,tz "
                                             "and/or --light x,y,z,tx,ty,tz ('#' comments; a pose a line leaves out stays); writes <out>-0001.png, "
                                             "<out>-0001-indirect.pfm, ... for every frame, or nothing; --temporal-blend sets the accumulation"),
                           sequence_readers(), [](const std::string& technique) { return !family_of(technique).sequence_readers.empty(); });
  render->add_option("--max-seconds", state->max_seconds,
                     "with --poses: stop after the frame during which this many seconds (counted from the start) have passed, write the "
                     "frames rendered until then, and exit with code 3; 0: no limit")
      ->check(number_in(0.0, 1e9, false, "seconds"))->capture_default_str();
  render->add_option("--stats", state->stats, "write the settings in effect, the pass times with their method and the quality numbers as JSON (.json)");
  render->add_option("--reference", state->reference,
                     "measure the frame against ground truth: rsm-brute-force (the RSM techniques' raw gather against the brute-force gather of "
                     "the same frame), monte-carlo (the final image against the one-bounce path-traced image) or none")
      ->check(CLI::IsMember({"none", "rsm-brute-force", "monte-carlo"}))->capture_default_str();
  add_reference_options(*render, state->quality, state->reference_scope);
  return {render, [state](const session& io) { return run_render(io, *state); }, restorer(state)};
}

}  // namespace vplkit::cli
