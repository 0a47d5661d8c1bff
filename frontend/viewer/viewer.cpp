#include "frontend/viewer/viewer.hpp"

#define GLFW_INCLUDE_NONE  // GL comes from glad (frontend/gl/gl.hpp)
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_opengl3.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "frontend/core/error.hpp"
#include "frontend/core/files.hpp"
#include "frontend/gl/debug_output.hpp"
#include "frontend/image/image_files.hpp"
#include "frontend/viewer/pose_controls.hpp"

namespace vplkit {

namespace {

constexpr float radians_per_pixel = 0.005f;

// Dear ImGui keeps one current context and its GLFW backend installs callbacks on the window:
// one viewer at a time.
bool viewer_exists = false;

const char* describe(move_target target) {
  switch (target) {
    case move_target::camera: return "camera";
    case move_target::light: return "light";
    case move_target::object: return "object";
  }
  return "";
}

}  // namespace

viewer::viewer(window_context& window, const shader_library& shaders, viewer_options options)
    : window_(window),
      shaders_(shaders),
      scenes_(std::move(options.scenes)),
      technique_(options.technique),
      view_(make_technique_view(shaders, scenes_, technique_)),
      last_good_{current_poses()},
      present_program_(load_program(shaders, "fullscreen.vert", "present.frag")),
      empty_vertex_array_(generate_vertex_array()),
      panel_(options.panel),
      docked_panel_width_(options.docked_panel_width),
      screenshot_path_(std::move(options.screenshot)),
      log_(options.log),
      image_exposure_ev_(options.exposure_ev),
      image_auto_exposure_(options.auto_exposure),
      last_frame_(std::chrono::steady_clock::now()) {
  if (viewer_exists) throw error("a viewer is already open: Dear ImGui allows one at a time");
  // Key presses are queued by a callback rather than read from ImGui's key state: a press and its
  // release handled in the same glfwPollEvents (a slow frame, or an idle wait) would leave no
  // frame in which the key reads as down. Installed before ImGui's backend, which chains to it.
  glfwSetWindowUserPointer(window_.window(), this);
  glfwSetKeyCallback(window_.window(), [](GLFWwindow* handle, int key, int, int action, int) {
    if (action == GLFW_PRESS) static_cast<viewer*>(glfwGetWindowUserPointer(handle))->pressed_keys_.push_back(key);
  });
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the viewer writes no imgui.ini
  ImGui::StyleColorsDark();
  if (!ImGui_ImplGlfw_InitForOpenGL(window_.window(), true) || !ImGui_ImplOpenGL3_Init("#version 330 core")) {
    ImGui::DestroyContext();
    glfwSetKeyCallback(window_.window(), nullptr);
    throw error("Dear ImGui could not set up its GLFW and OpenGL 3 backends");
  }
  imgui_ready_ = true;
  viewer_exists = true;
}

viewer::~viewer() {
  if (!imgui_ready_) return;
  ImGui_ImplOpenGL3_Shutdown();
  ImGui_ImplGlfw_Shutdown();
  ImGui::DestroyContext();
  glfwSetKeyCallback(window_.window(), nullptr);
  glfwSetWindowUserPointer(window_.window(), nullptr);
  viewer_exists = false;
}

bool viewer::try_action(const std::function<void()>& action) {
  try {
    action();
    message_.clear();
    return true;
  } catch (const error& failure) {
    message_ = failure.what();
    return false;
  }
}

void viewer::select_technique(const std::string& technique) {
  try_action([&] {
    view_->store_pose(scenes_);
    std::unique_ptr<technique_view> next = make_technique_view(shaders_, scenes_, technique);
    view_ = std::move(next);
    technique_ = technique;
    // The selected light kept where the next scene has it.
    if (selected_light_ < view_->light_count()) view_->select_light(selected_light_);
    else selected_light_ = 0;
    last_good_ = current_poses();
    const std::vector<view_layer> layers = view_->layers();
    if (std::find(layers.begin(), layers.end(), layer_) == layers.end()) layer_ = view_layer::image;
    if (target_ == move_target::object && !view_->has_object()) target_ = move_target::camera;
    if (target_ == move_target::light && view_->light_count() == 0) target_ = move_target::camera;
    exposure_stale_ = true;
  });
}

viewer::poses viewer::current_poses() const {
  return {view_->camera_pose(), view_->light_count() > 0 ? std::optional<pose>(view_->light_pose()) : std::nullopt, view_->object_position()};
}

void viewer::select_light(std::size_t index) {
  if (try_action([&] { view_->select_light(index); })) {
    selected_light_ = index;
    last_good_.light = view_->light_pose();
  }
}

void viewer::take_stored_settings() {
  bool in_place = false;
  if (!try_action([&] { in_place = view_->take_settings(scenes_); })) return;
  if (in_place) exposure_stale_ = true;
  else select_technique(technique_);
}

void viewer::set_settings(const technique_settings& settings) {
  if (settings.technique() != technique_) {
    message_ = "the settings are " + settings.technique() + "'s; the viewer shows " + technique_;
    return;
  }
  if (const std::string why = settings.validate(); !why.empty()) {
    message_ = why;
    return;
  }
  viewer_family& family = scenes_.of(technique_);
  std::unique_ptr<technique_settings> previous = std::move(family.settings);
  family.settings = settings.clone();
  take_stored_settings();
  // A view that refused them (select_technique kept the current one): the family keeps the
  // settings the view draws.
  if (!message_.empty()) family.settings = std::move(previous);
}

void viewer::select_layer(view_layer layer) {
  const std::vector<view_layer> layers = view_->layers();
  if (std::find(layers.begin(), layers.end(), layer) == layers.end()) {
    message_ = std::string("technique ") + technique_ + " has no layer \"" + describe(layer) + "\"";
    return;
  }
  layer_ = layer;
  exposure_stale_ = true;
}

void viewer::move_camera(const pose& where) { try_action([&] { view_->set_camera_pose(where); }); }

float viewer::light_intensity() const { return view_->light_count() > 0 ? view_->light_intensity() : 0.0f; }

void viewer::set_light_intensity(float intensity) {
  try_action([&] {
    view_->set_light_intensity(intensity);
    exposure_stale_ = true;
  });
}

void viewer::set_exposure(float ev, bool automatic) {
  image_exposure_ev_ = ev;
  image_auto_exposure_ = automatic;
  exposure_stale_ = true;
}
void viewer::move_light(const pose& where) { try_action([&] { view_->set_light_pose(where); }); }
void viewer::move_object(glm::vec3 centre) { try_action([&] { view_->set_object_position(centre); }); }

std::string viewer::pose_arguments() const {
  const std::size_t count = view_->light_count();
  std::string arguments = "--technique " + technique_ + " --camera " + format_pose(view_->camera_pose()) + " " +
                          light_arguments(scenes_.of(technique_).file_lights, count, selected_light_, count > 0 ? view_->light_pose() : pose{});
  if (view_->has_object()) arguments += " --object-position " + format_point(view_->object_position());
  return arguments;
}

void viewer::handle_input() {
  const ImGuiIO& io = ImGui::GetIO();
  std::vector<int> pressed;
  pressed.swap(pressed_keys_);
  if (!io.WantCaptureKeyboard) {
    for (int key : pressed) {
      if (key == GLFW_KEY_H) panel_ = !panel_;
      if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window_.window(), GLFW_TRUE);
      if (key == GLFW_KEY_TAB) {
        // Camera, light (when the scene has one), object (when the technique has one), camera.
        const bool lit = view_->light_count() > 0;
        target_ = target_ == move_target::camera && lit                                    ? move_target::light
                  : (target_ == move_target::camera || target_ == move_target::light) && view_->has_object() ? move_target::object
                                                                                                             : move_target::camera;
      }
      if (key == GLFW_KEY_N && view_->light_count() > 0) select_light((selected_light_ + 1) % view_->light_count());
      if (key == GLFW_KEY_L) {
        const std::vector<view_layer> layers = view_->layers();
        const auto current = std::find(layers.begin(), layers.end(), layer_);
        select_layer(current == layers.end() || current + 1 == layers.end() ? layers.front() : *(current + 1));
      }
      if (key == GLFW_KEY_P) {
        try_action([&] {
          for (const std::filesystem::path& path : save_screenshot(screenshot_path_))
            if (log_) *log_ << "wrote " << std::filesystem::absolute(path).string() << std::endl;
        });
      }
    }
  }

  // The mouse and keys move the chosen target: orbit/look/dolly/fly for a pose, WASD/QE for the object.
  const bool is_pose = target_ != move_target::object;
  if (target_ == move_target::light && view_->light_count() == 0) target_ = move_target::camera;
  const pose current = target_ == move_target::light ? view_->light_pose() : view_->camera_pose();
  pose moved = current;
  if (!io.WantCaptureMouse) {
    if (io.MouseDown[0] && is_pose) moved = orbit(moved, -io.MouseDelta.x * radians_per_pixel, io.MouseDelta.y * radians_per_pixel);
    if (io.MouseDown[1] && is_pose) moved = look(moved, -io.MouseDelta.x * radians_per_pixel, -io.MouseDelta.y * radians_per_pixel);
    if (io.MouseWheel != 0.0f && is_pose) moved = dolly(moved, std::pow(0.9f, io.MouseWheel));
  }
  glm::vec3 step(0.0f);
  if (!io.WantCaptureKeyboard) {
    const auto key = [](int code) { return ImGui::IsKeyDown(code) ? 1.0f : 0.0f; };
    step = glm::vec3(key(GLFW_KEY_D) - key(GLFW_KEY_A), key(GLFW_KEY_E) - key(GLFW_KEY_Q), key(GLFW_KEY_W) - key(GLFW_KEY_S));
  }
  if (step != glm::vec3(0.0f)) {
    // Half the distance to the target per second, so that a move feels the same in any scene.
    const float speed = 0.5f * std::max(glm::length(current.target - current.position), 0.05f) * std::min(io.DeltaTime, 0.1f);
    if (is_pose) {
      moved = fly(moved, step * speed);
    } else {
      // The object moves along the camera's horizontal axes and world up.
      const pose_axes axes = axes_of(view_->camera_pose());
      const glm::vec3 flat_forward = glm::normalize(glm::vec3(axes.forward.x, 0.0f, axes.forward.z) + glm::vec3(0.0f, 0.0f, 1e-6f));
      const glm::vec3 flat_right = glm::normalize(glm::cross(flat_forward, glm::vec3(0.0f, 1.0f, 0.0f)));
      move_object(view_->object_position() + speed * (step.x * flat_right + step.y * glm::vec3(0.0f, 1.0f, 0.0f) + step.z * flat_forward));
    }
  }
  if (is_pose && (moved.position != current.position || moved.target != current.target)) {
    if (target_ == move_target::light) move_light(moved);
    else move_camera(moved);
  }
}

glm::vec4 viewer::image_rectangle() const {
  const auto [width, height] = window_.framebuffer_size();
  return glm::vec4(0.0f, 0.0f, static_cast<float>(std::max(1, width - docked_panel_width_)), static_cast<float>(height));
}

void viewer::dock_panel(bool docked) {
  const int image_width = static_cast<int>(image_rectangle().z), image_height = static_cast<int>(image_rectangle().w);
  docked_panel_width_ = docked ? docked_panel_width : 0;
  glfwSetWindowSize(window_.window(), image_width + docked_panel_width_, image_height);
}

void viewer::build_panel() {
  const glm::vec4 image = image_rectangle();
  ImGuiWindowFlags flags = 0;
  if (docked_panel_width_ > 0) {
    // A column beside the image: the whole height, the docked width, not moved or resized.
    ImGui::SetNextWindowPos(ImVec2(image.z, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(docked_panel_width_), image.w));
    flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse;
  } else {
    // Over the image: at most half its width and half its height, a quarter of it; what does not
    // fit scrolls.
    const ImVec2 largest(std::max(32.0f, 0.5f * image.z - 8.0f), std::max(32.0f, 0.5f * image.w - 8.0f));
    ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(std::min(largest.x, 380.0f), largest.y), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSizeConstraints(ImVec2(32.0f, 32.0f), largest);
    ImGui::SetNextWindowBgAlpha(0.85f);
  }
  ImGui::Begin("vplkit", nullptr, flags);
  ImGui::PushItemWidth(-140.0f);
  ImGui::PushTextWrapPos(0.0f);
  // The technique list as wide as the panel, the longest name whole.
  ImGui::TextUnformatted("technique");
  const std::vector<std::string> names = technique_names();
  float longest = 0.0f;
  for (const std::string& name : names) longest = std::max(longest, ImGui::CalcTextSize(name.c_str()).x);
  ImGui::SetNextItemWidth(-1.0f);
  if (ImGui::BeginCombo("##technique", technique_.c_str())) {
    for (const std::string& name : names)
      if (ImGui::Selectable(name.c_str(), name == technique_) && name != technique_) select_technique(name);
    ImGui::EndCombo();
  }
  const ImGuiStyle& style = ImGui::GetStyle();
  technique_names_fit_ = ImGui::GetItemRectSize().x >= longest + ImGui::GetFrameHeight() + 2.0f * style.FramePadding.x;
  for (const technique_family& family : technique_families())
    for (const technique_entry& entry : family.techniques)
      if (entry.name == technique_) ImGui::TextDisabled("%s", entry.description.c_str());
  for (view_layer layer : view_->layers())
    if (ImGui::RadioButton(describe(layer), layer_ == layer)) select_layer(layer);
  // Which light, where the mouse moves one: the selected light's index.
  const std::string moved_name = target_ == move_target::light ? "light " + std::to_string(selected_light_) : describe(target_);
  ImGui::Text("mouse, WASD and Q/E move the %s (Tab: next)", moved_name.c_str());

  if (ImGui::CollapsingHeader("settings", ImGuiTreeNodeFlags_DefaultOpen)) {
    std::string problem;
    if (view_->edit_settings(scenes_, problem)) take_stored_settings();
    if (!problem.empty()) message_ = problem;
  }

  const std::size_t light_count = view_->light_count();
  if (ImGui::CollapsingHeader("light and exposure", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (light_count == 0) {
      // Nothing to move: the image is shown, the light controls are not.
      ImGui::TextDisabled("no light in this scene (--lights none, or a file without lights)");
    } else {
      // Which light the intensity, the pose and the mouse move (N: the next one).
      const auto light_label = [&](std::size_t k) { return "light " + std::to_string(k) + " (" + light_kind_name(view_->light_kind_of(k)) + ")"; };
      ImGui::Text("%s of %zu (N: next)", light_label(selected_light_).c_str(), light_count);
      if (light_count > 1 && ImGui::BeginCombo("moved light", light_label(selected_light_).c_str())) {
        for (std::size_t k = 0; k < light_count; ++k)
          if (ImGui::Selectable(light_label(k).c_str(), k == selected_light_) && k != selected_light_) select_light(k);
        ImGui::EndCombo();
      }
      // The selected light of the technique shown; a light move for the pipeline (what it invalidates redrawn).
      float intensity = light_intensity();
      if (ImGui::DragFloat("light intensity", &intensity, 0.01f * std::max(intensity, 1e-3f), 0.0f, 1e6f, "%.4g W/sr or W/m^2", ImGuiSliderFlags_Logarithmic))
        set_light_intensity(intensity);
    }
    float ev = image_exposure_ev_;
    bool automatic = image_auto_exposure_;
    const bool moved = ImGui::SliderFloat("exposure (EV)", &ev, -10.0f, 10.0f, "%.2f");
    const bool toggled = ImGui::Checkbox("auto exposure", &automatic);
    if (moved || toggled) set_exposure(ev, automatic);
  }

  if (ImGui::CollapsingHeader("pose")) {
    const auto edit_pose = [&](const char* label, pose where, bool light) {
      ImGui::PushID(label);
      bool changed = ImGui::DragFloat3("position", &where.position.x, 0.01f);
      changed |= ImGui::DragFloat3("target", &where.target.x, 0.01f);
      ImGui::PopID();
      if (changed) (light ? move_light(where) : move_camera(where));
    };
    ImGui::TextUnformatted("camera");
    edit_pose("camera", view_->camera_pose(), false);
    if (light_count > 0) {
      ImGui::Text("light %zu", selected_light_);
      edit_pose("light", view_->light_pose(), true);
    }
    if (view_->has_object()) {
      glm::vec3 centre = view_->object_position();
      if (ImGui::DragFloat3("object", &centre.x, 0.01f)) move_object(centre);
    }
    if (ImGui::Button("copy as vplkit render arguments")) ImGui::SetClipboardText(pose_arguments().c_str());
  }

  if (ImGui::CollapsingHeader("timing", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::Text("frame interval %.2f ms", frame_ms_);
    ImGui::TextUnformatted(describe(timing_method_for_current_context()).c_str());
    double total = 0.0;
    for (const pass_time& pass : last_pass_times_) {
      ImGui::Text("%-26s %9.2f ms", pass.pass.c_str(), pass.milliseconds);
      total += pass.milliseconds;
    }
    ImGui::Text("%-26s %9.2f ms", "passes drawn last", total);
    ImGui::TextWrapped("drawn so far: %s", view_->draw_counts().c_str());
  }
  if (!message_.empty()) ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.3f, 1.0f), "%s", message_.c_str());
  ImGui::TextDisabled("H panel, L layer, N next light, P screenshot, Esc close");
  if (ImGui::CollapsingHeader("panel")) {
    bool docked = docked_panel_width_ > 0;
    if (ImGui::Checkbox("dock beside the image", &docked)) dock_panel(docked);
  }
  const ImVec2 position = ImGui::GetWindowPos(), size = ImGui::GetWindowSize();
  panel_rectangle_ = glm::vec4(position.x, position.y, size.x, size.y);
  ImGui::PopTextWrapPos();
  ImGui::PopItemWidth();
  ImGui::End();
}

void viewer::present() {
  const layer_display display = view_->display(layer_);
  // The indirect layers are auto-exposed from the indirect light; the final image takes
  // --exposure (2^EV, or auto from its own luminance, as vplkit render's PNG).
  const bool final_image = layer_ == view_layer::image;
  if (exposure_stale_ && (display.auto_exposure || (final_image && image_auto_exposure_))) {
    exposure_ = percentile_exposure(final_image ? display.image->read_image() : view_->read_indirect());
    exposure_stale_ = false;
  }
  const float shown_exposure = final_image ? (image_auto_exposure_ ? exposure_ : std::exp2(image_exposure_ev_)) : display.auto_exposure ? exposure_ : 1.0f;
  const auto [window_width, window_height] = window_.framebuffer_size();
  const glm::vec4 image = image_rectangle();
  const int width = static_cast<int>(image.z), height = static_cast<int>(image.w);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  if (docked_panel_width_ > 0) {
    glViewport(0, 0, window_width, window_height);
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glDisable(GL_SCISSOR_TEST);
  display.image->bind(0);
  (display.other ? display.other : display.image)->bind(1);
  present_program_.use();
  present_program_.set("image", 0);
  present_program_.set("other", 1);
  present_program_.set("mode", display.mode);
  present_program_.set("exposure", shown_exposure * display.scale);
  present_program_.set("viewport_size", glm::ivec2(width, height));
  glBindVertexArray(empty_vertex_array_.get());
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  check_gl("presenting " + technique_);
}

void viewer::frame() {
  const auto now = std::chrono::steady_clock::now();
  frame_ms_ = std::chrono::duration<double, std::milli>(now - last_frame_).count();
  last_frame_ = now;

  ImGui_ImplOpenGL3_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  // A hidden panel takes no input: everything goes to the moves.
  if (!panel_) ImGui::GetIO().WantCaptureMouse = ImGui::GetIO().WantCaptureKeyboard = false;
  handle_input();
  if (panel_) build_panel();
  ImGui::Render();

  bool drawn = false;
  if (try_action([&] { drawn = view_->draw(); })) {
    last_good_ = current_poses();
  } else {
    // A move the pipeline refused while drawing (the object into a wall): back to the last pose
    // that drew.
    const std::string reason = message_;
    try_action([&] {
      view_->set_camera_pose(last_good_.camera);
      if (last_good_.light) view_->set_light_pose(*last_good_.light);
      if (view_->has_object()) view_->set_object_position(last_good_.object);
      drawn = view_->draw();
    });
    message_ = reason;
  }
  if (drawn) {
    last_pass_times_ = view_->collect_pass_times();
    exposure_stale_ = true;
  }
  const ImGuiIO& io = ImGui::GetIO();
  const bool held = std::any_of(std::begin(io.MouseDown), std::end(io.MouseDown), [](bool down) { return down; }) ||
                    std::any_of(std::begin(io.KeysDown), std::end(io.KeysDown), [](bool down) { return down; });
  idle_ = !drawn && !held;
  present();
  if (panel_) ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

window_pixels viewer::read_window() const {
  window_pixels pixels;
  std::tie(pixels.width, pixels.height) = window_.framebuffer_size();
  const std::size_t row = static_cast<std::size_t>(pixels.width) * 4;
  std::vector<std::uint8_t> bottom_up(row * static_cast<std::size_t>(pixels.height));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, pixels.width, pixels.height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  check_gl("reading the window");
  pixels.rgba8.resize(bottom_up.size());
  for (int y = 0; y < pixels.height; ++y)
    std::copy_n(bottom_up.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(y)), row,
                pixels.rgba8.begin() + static_cast<std::ptrdiff_t>(row * static_cast<std::size_t>(pixels.height - 1 - y)));
  return pixels;
}

std::vector<std::filesystem::path> viewer::save_screenshot(const std::filesystem::path& png) {
  if (png.extension() != ".png") throw error("screenshot " + png.string() + ": the file name must end in .png");
  const window_pixels pixels = read_window();
  const image indirect = view_->read_indirect();
  std::filesystem::path pfm = png;
  pfm.replace_filename(png.stem().string() + "-indirect.pfm");
  write_all_or_nothing({{png, [&] { return encode_png(pixels.width, pixels.height, pixels.rgba8); }}, {pfm, [&] { return encode_pfm(indirect); }}});
  return {png, pfm};
}

int run_viewer(window_context& window, const shader_library& shaders, viewer_options options, int frames, bool screenshot_at_end, std::ostream& out) {
  const std::filesystem::path screenshot = options.screenshot;
  options.log = &out;
  viewer app(window, shaders, std::move(options));
  int shown = 0;
  for (; (frames == 0 || shown < frames) && !window.should_close(); ++shown) {
    app.frame();
    if (screenshot_at_end && shown + 1 == frames)
      for (const std::filesystem::path& path : app.save_screenshot(screenshot)) out << "wrote " << std::filesystem::absolute(path).string() << "\n";
    window.swap_and_poll();
    // Nothing moved and nothing is held: wait for input (at most 1/30 s) instead of spinning.
    if (app.idle()) glfwWaitEventsTimeout(1.0 / 30.0);
  }
  if (!app.message().empty()) out << "last message: " << app.message() << "\n";
  out << "closed the window after " << shown << " frames of " << app.technique() << " (drawn: " << app.view().draw_counts() << ")\n"
      << "pose: " << app.pose_arguments() << "\n";
  if (app.panel_shown()) {
    const glm::vec4 panel = app.panel_rectangle(), image = app.image_rectangle();
    // The part of the image under the panel (none when docked beside it).
    const float covered_width = std::max(0.0f, std::min(panel.x + panel.z, image.z) - std::max(panel.x, image.x));
    const float covered_height = std::max(0.0f, std::min(panel.y + panel.w, image.w) - std::max(panel.y, image.y));
    std::ostringstream share;
    share << std::fixed << std::setprecision(1) << 100.0 * covered_width * covered_height / (image.z * image.w);
    out << "panel: " << panel.z << "x" << panel.w << " at " << panel.x << "," << panel.y << ", covering " << share.str() << " % of the " << image.z << "x"
        << image.w << " image; technique names " << (app.technique_names_fit() ? "fit" : "cut") << "\n";
  }
  return 0;
}

}  // namespace vplkit
