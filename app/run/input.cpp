// Input (input.h): GLFW callbacks forward to the entry points; the entry
// points update the state, the per-frame edges and the log.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>

#include <cfloat>
#include <utility>

#include "app/run/input.h"

namespace dtlab::run {

namespace {

Input* of(GLFWwindow* w) { return static_cast<Input*>(glfwGetWindowUserPointer(w)); }

void key_cb(GLFWwindow* w, int key, int, int action, int mods) { of(w)->on_key(key, action, mods); }
void char_cb(GLFWwindow* w, unsigned c) { of(w)->on_char(c); }
void button_cb(GLFWwindow* w, int button, int action, int mods) { of(w)->on_mouse_button(button, action, mods); }
void cursor_cb(GLFWwindow* w, double x, double y) { of(w)->on_cursor(x, y); }
void scroll_cb(GLFWwindow* w, double dx, double dy) { of(w)->on_scroll(dx, dy); }
void focus_cb(GLFWwindow* w, int focused) { of(w)->on_focus(focused != 0); }
void enter_cb(GLFWwindow* w, int entered) { of(w)->on_enter(entered != 0); }

struct KeyName {
  int key;
  const char* name;
};
constexpr KeyName kNamed[] = {
    {GLFW_KEY_SPACE, "Space"},        {GLFW_KEY_ENTER, "Enter"},         {GLFW_KEY_KP_ENTER, "KeypadEnter"},
    {GLFW_KEY_ESCAPE, "Escape"},      {GLFW_KEY_TAB, "Tab"},             {GLFW_KEY_BACKSPACE, "Backspace"},
    {GLFW_KEY_DELETE, "Delete"},      {GLFW_KEY_UP, "Up"},               {GLFW_KEY_DOWN, "Down"},
    {GLFW_KEY_LEFT, "Left"},          {GLFW_KEY_RIGHT, "Right"},         {GLFW_KEY_HOME, "Home"},
    {GLFW_KEY_END, "End"},            {GLFW_KEY_PAGE_UP, "PageUp"},      {GLFW_KEY_PAGE_DOWN, "PageDown"},
    {GLFW_KEY_LEFT_SHIFT, "LeftShift"}, {GLFW_KEY_RIGHT_SHIFT, "RightShift"},
    {GLFW_KEY_LEFT_CONTROL, "LeftControl"}, {GLFW_KEY_RIGHT_CONTROL, "RightControl"},
    {GLFW_KEY_LEFT_ALT, "LeftAlt"},   {GLFW_KEY_RIGHT_ALT, "RightAlt"},
};

}  // namespace

Input::Input(GLFWwindow* window) : window_(window) {
  if (!window) return;  // no window: events come only through the entry points (the script tests)
  glfwSetWindowUserPointer(window, this);
  glfwSetKeyCallback(window, key_cb);
  glfwSetCharCallback(window, char_cb);
  glfwSetMouseButtonCallback(window, button_cb);
  glfwSetCursorPosCallback(window, cursor_cb);
  glfwSetScrollCallback(window, scroll_cb);
  glfwSetWindowFocusCallback(window, focus_cb);
  glfwSetCursorEnterCallback(window, enter_cb);
  focused_ = glfwGetWindowAttrib(window, GLFW_FOCUSED) != 0;
  hovered_ = glfwGetWindowAttrib(window, GLFW_HOVERED) != 0;
}

Input::~Input() {
  if (!window_) return;
  glfwSetKeyCallback(window_, nullptr);
  glfwSetCharCallback(window_, nullptr);
  glfwSetMouseButtonCallback(window_, nullptr);
  glfwSetCursorPosCallback(window_, nullptr);
  glfwSetScrollCallback(window_, nullptr);
  glfwSetWindowFocusCallback(window_, nullptr);
  glfwSetCursorEnterCallback(window_, nullptr);
  glfwSetWindowUserPointer(window_, nullptr);
}

std::string Input::key_name(int key) {
  for (const KeyName& k : kNamed)
    if (k.key == key) return k.name;
  if (key >= GLFW_KEY_A && key <= GLFW_KEY_Z) return std::string(1, static_cast<char>('A' + key - GLFW_KEY_A));
  if (key >= GLFW_KEY_0 && key <= GLFW_KEY_9) return std::string(1, static_cast<char>('0' + key - GLFW_KEY_0));
  if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F12) return "F" + std::to_string(key - GLFW_KEY_F1 + 1);
  return "key" + std::to_string(key);
}

int Input::key_code(const std::string& name) {
  for (const KeyName& k : kNamed)
    if (name == k.name) return k.key;
  if (name.size() == 1 && name[0] >= 'A' && name[0] <= 'Z') return GLFW_KEY_A + (name[0] - 'A');
  if (name.size() == 1 && name[0] >= 'a' && name[0] <= 'z') return GLFW_KEY_A + (name[0] - 'a');
  if (name.size() == 1 && name[0] >= '0' && name[0] <= '9') return GLFW_KEY_0 + (name[0] - '0');
  if (name.size() >= 2 && name[0] == 'F') {
    int n = 0;
    for (char c : name.substr(1)) {
      if (c < '0' || c > '9') return -1;
      n = n * 10 + (c - '0');
    }
    if (n >= 1 && n <= 12) return GLFW_KEY_F1 + n - 1;
  }
  return -1;
}

void EventLog::start(Clock::time_point origin) {
  origin_ = origin;
  events_.clear();
  active_ = true;
}

void EventLog::add(store::InputEvent::Kind kind, std::string detail, double x, double y) {
  if (!active_) return;
  const double t = std::chrono::duration<double>(Clock::now() - origin_).count();
  events_.push_back(store::InputEvent{t < 0 ? 0.0 : t, kind, std::move(detail), x, y});
}

std::vector<store::InputEvent> EventLog::take() {
  active_ = false;
  return std::exchange(events_, {});
}

void Input::on_key(int key, int action, int) {
  if (key < 0 || key >= static_cast<int>(keys_.size())) return;
  const auto k = static_cast<std::size_t>(key);
  if (action == GLFW_PRESS) {
    keys_[k] = true;
    pressed_[k] = true;
    log_.add(store::InputEvent::Kind::key_down, key_name(key), cursor_.x, cursor_.y);
  } else if (action == GLFW_RELEASE) {
    keys_[k] = false;
    log_.add(store::InputEvent::Kind::key_up, key_name(key), cursor_.x, cursor_.y);
  }
}

void Input::on_char(unsigned codepoint) { chars_.push_back(codepoint); }
void Input::on_focus(bool focused) { focused_ = focused; }
void Input::on_enter(bool inside) { hovered_ = inside; }

void Input::on_mouse_button(int button, int action, int) {
  if (button < 0 || button >= static_cast<int>(buttons_.size())) return;
  if (lent_ && action == GLFW_PRESS) lend_pointer(false);  // a click here takes the pointer back
  const auto b = static_cast<std::size_t>(button);
  static const char* names[] = {"left", "right", "middle", "4", "5", "6", "7", "8"};
  if (action == GLFW_PRESS) {
    buttons_[b] = true;
    button_pressed_[b] = true;
    log_.add(store::InputEvent::Kind::button_down, names[b], cursor_.x, cursor_.y);
  } else if (action == GLFW_RELEASE) {
    buttons_[b] = false;
    button_released_[b] = true;
    log_.add(store::InputEvent::Kind::button_up, names[b], cursor_.x, cursor_.y);
  }
}

void Input::on_cursor(double x, double y) {
  if (have_cursor_ && !lent_ && !rebase_) delta_ += glm::dvec2(x, y) - cursor_;
  rebase_ = false;
  cursor_ = {x, y};
  have_cursor_ = true;
  log_.add(store::InputEvent::Kind::cursor, "", x, y);
}

void Input::on_scroll(double dx, double dy) {
  scroll_ += glm::dvec2(dx, dy);
  log_.add(store::InputEvent::Kind::scroll, "", dx, dy);
}

void Input::new_frame() {
  pressed_.fill(false);
  button_pressed_.fill(false);
  button_released_.fill(false);
  chars_.clear();
  delta_ = glm::dvec2(0.0);
  scroll_ = glm::dvec2(0.0);
}

void Input::feed_imgui(float delta_s) const {
  ImGuiIO& io = ImGui::GetIO();
  io.DeltaTime = delta_s > 0 ? delta_s : 1.0f / 60.0f;
  io.MousePos = captured_ || !have_cursor_ ? ImVec2(-FLT_MAX, -FLT_MAX)
                                           : ImVec2(static_cast<float>(cursor_.x), static_cast<float>(cursor_.y));
  // A press and release within one frame still reads as "down this frame" (as ImGui's backends do).
  for (int i = 0; i < 5; ++i) io.MouseDown[i] = !captured_ && (buttons_[static_cast<std::size_t>(i)] ||
                                                               button_pressed_[static_cast<std::size_t>(i)]);
  io.MouseWheel += static_cast<float>(scroll_.y);
  io.MouseWheelH += static_cast<float>(scroll_.x);
  for (std::size_t k = 0; k < keys_.size(); ++k) io.KeysDown[k] = keys_[k] || pressed_[k];
  io.KeyCtrl = ctrl();
  io.KeyShift = shift();
  io.KeyAlt = key_down(GLFW_KEY_LEFT_ALT) || key_down(GLFW_KEY_RIGHT_ALT);
  io.KeySuper = false;
  for (unsigned c : chars_) io.AddInputCharacter(c);
}

bool Input::key_down(int key) const {
  return key >= 0 && key < static_cast<int>(keys_.size()) && keys_[static_cast<std::size_t>(key)];
}
bool Input::key_pressed(int key) const {
  return key >= 0 && key < static_cast<int>(pressed_.size()) && pressed_[static_cast<std::size_t>(key)];
}
bool Input::button_down(int b) const {
  return b >= 0 && b < static_cast<int>(buttons_.size()) && buttons_[static_cast<std::size_t>(b)];
}
bool Input::button_pressed(int b) const {
  return b >= 0 && b < static_cast<int>(button_pressed_.size()) && button_pressed_[static_cast<std::size_t>(b)];
}
bool Input::button_released(int b) const {
  return b >= 0 && b < static_cast<int>(button_released_.size()) && button_released_[static_cast<std::size_t>(b)];
}
void Input::swallow_press(int key) {
  if (key >= 0 && key < static_cast<int>(pressed_.size())) pressed_[static_cast<std::size_t>(key)] = false;
}

bool Input::ctrl() const { return key_down(GLFW_KEY_LEFT_CONTROL) || key_down(GLFW_KEY_RIGHT_CONTROL); }
bool Input::shift() const { return key_down(GLFW_KEY_LEFT_SHIFT) || key_down(GLFW_KEY_RIGHT_SHIFT); }

void Input::capture_cursor(bool on) {
  if (on == captured_) return;
  captured_ = on;
  if (!window_ || lent_) return;  // a lent pointer is captured when it comes back
  glfwSetInputMode(window_, GLFW_CURSOR, on ? GLFW_CURSOR_DISABLED : GLFW_CURSOR_NORMAL);
  if (on && glfwRawMouseMotionSupported()) glfwSetInputMode(window_, GLFW_RAW_MOUSE_MOTION, GLFW_TRUE);
}

void Input::lend_pointer(bool on) {
  if (on == lent_) return;
  lent_ = on;
  // Captured and free cursors count from different origins: the next position starts the motion
  // afresh (no jump when the pointer comes back). The position itself stays valid: the click that
  // takes the pointer back is a click where it is.
  rebase_ = true;
  if (!window_ || !captured_) return;
  glfwSetInputMode(window_, GLFW_CURSOR, on ? GLFW_CURSOR_NORMAL : GLFW_CURSOR_DISABLED);
}

void Input::start_log(Clock::time_point origin) { log_.start(origin); }
std::vector<store::InputEvent> Input::take_log() { return log_.take(); }
void Input::log_answer(const std::string& detail) { log_.add(store::InputEvent::Kind::answer, detail, cursor_.x, cursor_.y); }

}  // namespace dtlab::run
