// vplkit view: any technique in a GLFW window with a Dear ImGui panel. The camera orbits (left
// drag), looks around (right drag), dollies (wheel) and flies (WASD, Q/E down/up); Tab makes the
// mouse and keys move the selected light instead, or the object (final gathering); N selects the
// next of the scene's lights (the panel's "light and exposure" section too, which shows the
// selection; a scene without lights shows its image and no light controls). The panel switches the
// technique and the layer shown, edits the technique's settings live, shows the per-pass times of
// the last frame that drew anything (the pass_timer's method), the frame time, what each stage
// has been drawn so far, and the pose as --camera/--lights/--light arguments. Floating over the image it
// covers at most a quarter of it (half its width and half its height, scrolling beyond); docked,
// it takes a column beside the image, which the window is widened by. H hides the panel, P saves
// a screenshot PNG and the indirect PFM, L cycles the layers, Esc closes. A move redraws only
// what it invalidates (technique_view.hpp).
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <vplkit/gl/program.hpp>

#include "frontend/window/window_context.hpp"
#include "frontend/viewer/technique_view.hpp"

namespace vplkit {

/// The docked panel's column, in pixels beside the image.
constexpr int docked_panel_width = 340;

struct viewer_options {
  std::string technique;
  viewer_scenes scenes;
  bool panel = true;
  /// The width of the docked panel's column beside the image (the window is the image's width
  /// plus this); 0: the panel floats over the image.
  int docked_panel_width = 0;
  /// Where the P key (and run_viewer after a scripted run's last frame) saves the screenshot; the
  /// indirect PFM goes next to it as <stem>-indirect.pfm.
  std::filesystem::path screenshot = "output/view.png";
  /// Where "wrote <path>" goes when the P key saves (none when null).
  std::ostream* log = nullptr;
  /// The final image's exposure (vplkit render's --exposure): 2^exposure_ev, or with
  /// auto_exposure the percentile_exposure of the image.
  float exposure_ev = 0.0f;
  bool auto_exposure = false;
};

/// What moves with the mouse and the keys.
enum class move_target { camera, light, object };

/// The window's pixels: RGBA8, rows top-down (the PNG raster order).
struct window_pixels {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba8;
};

class viewer {
 public:
  /// Sets up Dear ImGui on the window and builds the first technique's view. Throws vplkit::error
  /// when the technique's pipeline cannot be built, or while another viewer exists (Dear ImGui
  /// has one current context).
  viewer(window_context& window, const shader_library& shaders, viewer_options options);
  ~viewer();
  viewer(const viewer&) = delete;
  viewer& operator=(const viewer&) = delete;

  /// One frame: input, moves, the passes they invalidated, the layer, the panel. Does not swap.
  void frame();

  technique_view& view() { return *view_; }
  const std::string& technique() const { return technique_; }
  /// Switches technique (settings kept per family, poses kept). A refusal leaves the current one
  /// and sets message().
  void select_technique(const std::string& technique);
  /// The shown technique's settings replaced, as the panel's controls do: in place when they
  /// change only uniforms (the next frame redraws, no program is compiled), else the view is
  /// built again. Invalid settings (or a view that refuses them) change nothing and set message().
  void set_settings(const technique_settings& settings);
  void select_layer(view_layer layer);
  view_layer layer() const { return layer_; }
  void show_panel(bool shown) { panel_ = shown; }
  /// Docks the panel beside the image (the window widens by docked_panel_width) or floats it
  /// over the image again (the window narrows back).
  void dock_panel(bool docked);
  bool panel_shown() const { return panel_; }
  /// Moves as the controls make them; a move the view refuses changes nothing and sets message().
  void move_camera(const pose& where);
  /// Moves the selected light (a refusal, or a scene without lights, sets message()).
  void move_light(const pose& where);
  void move_object(glm::vec3 centre);
  /// Chooses the light that move_light, the light intensity and the mouse move; kept across
  /// technique switches where the next technique's scene has it. An index the scene does not have
  /// changes nothing and sets message().
  void select_light(std::size_t index);
  /// The selected light's index (0 in a scene without lights).
  std::size_t selected_light() const { return selected_light_; }
  /// The selected light's intensity (W/sr, or W/m^2 for a sun), its colour kept: a light
  /// move (what it invalidates is redrawn). A refusal changes nothing and sets message().
  void set_light_intensity(float intensity);
  /// The brightest channel of the selected light (0 in a scene without lights).
  float light_intensity() const;
  /// The final image's exposure: 2^ev, or automatic.
  void set_exposure(float ev, bool automatic);
  /// The last error from a move, a setting or a switch ("" when the last action succeeded).
  const std::string& message() const { return message_; }
  /// The panel's rectangle in window pixels from the top left (x, y, width, height) in the last frame.
  glm::vec4 panel_rectangle() const { return panel_rectangle_; }
  /// The image's rectangle in window pixels from the top left: the window, less a docked panel.
  glm::vec4 image_rectangle() const;
  /// Whether the last panel showed the technique list wide enough for the longest name.
  bool technique_names_fit() const { return technique_names_fit_; }
  /// "--technique T --camera ... --light ..." (and --object-position): the pose as `vplkit render`
  /// takes it; with several lights "--lights s,a,b --light ...", the selected light first
  /// (light_arguments of pose_controls.hpp), without lights "--lights none".
  std::string pose_arguments() const;
  /// Whether the last frame drew nothing and no key or button is held (run_viewer then waits for
  /// input instead of spinning).
  bool idle() const { return idle_; }
  /// The back buffer after frame(), before the swap.
  window_pixels read_window() const;
  /// The window as a PNG and the indirect light as <stem>-indirect.pfm, all or nothing; returns
  /// the paths written.
  std::vector<std::filesystem::path> save_screenshot(const std::filesystem::path& png);

 private:
  void handle_input();
  void build_panel();
  void present();
  /// The family's settings in scenes_ taken by the view (after a settings edit): in place, or a
  /// new view.
  void take_stored_settings();
  bool try_action(const std::function<void()>& action);

  window_context& window_;
  const shader_library& shaders_;
  viewer_scenes scenes_;
  std::string technique_;
  std::unique_ptr<technique_view> view_;
  /// The poses of the last frame that drew, restored when a move fails while drawing.
  struct poses {
    pose camera;
    std::optional<pose> light;  ///< the selected light's; none without lights
    glm::vec3 object;
  } last_good_;
  poses current_poses() const;
  std::size_t selected_light_ = 0;
  program present_program_;
  gl_vertex_array empty_vertex_array_;
  view_layer layer_ = view_layer::image;
  move_target target_ = move_target::camera;
  bool panel_ = true;
  int docked_panel_width_ = 0;
  std::filesystem::path screenshot_path_;
  std::ostream* log_;
  std::string message_;
  std::vector<pass_time> last_pass_times_;
  float exposure_ = 1.0f;
  bool exposure_stale_ = true;
  float image_exposure_ev_ = 0.0f;  ///< the final image layer's exposure (--exposure)
  bool image_auto_exposure_ = false;
  double frame_ms_ = 0.0;
  std::chrono::steady_clock::time_point last_frame_;
  glm::vec4 panel_rectangle_{0.0f};
  bool technique_names_fit_ = false;
  bool imgui_ready_ = false;
  bool idle_ = false;
  std::vector<int> pressed_keys_;  ///< GLFW keys pressed since the last frame, in order
};

/// Runs `frames` frames (0: until the window is closed or Esc), saves the screenshot after the
/// last scripted frame when `screenshot_at_end`, and prints the pose to `out` at the end.
int run_viewer(window_context& window, const shader_library& shaders, viewer_options options, int frames, bool screenshot_at_end, std::ostream& out);

}  // namespace vplkit
