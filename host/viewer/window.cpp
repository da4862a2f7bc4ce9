#include "viewer/window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <utility>

#include "util/error.h"

namespace mixtrace {
namespace {

Window* self(GLFWwindow* w) { return static_cast<Window*>(glfwGetWindowUserPointer(w)); }

// GLFW keys the viewer knows, by the names scripts use (viewer/input.h).
std::string keyName(int key, int mods) {
  const std::string shift = (mods & GLFW_MOD_SHIFT) ? "shift+" : "";
  if (key >= GLFW_KEY_1 && key <= GLFW_KEY_5) return shift + char('1' + (key - GLFW_KEY_1));
  if (key >= GLFW_KEY_F1 && key <= GLFW_KEY_F6) return "f" + std::to_string(1 + key - GLFW_KEY_F1);
  switch (key) {
    case GLFW_KEY_V: return "v";
    case GLFW_KEY_G: return "g";
    case GLFW_KEY_P: return "p";
    case GLFW_KEY_R: return "r";
    case GLFW_KEY_ESCAPE: return "escape";
    default: return "";   // W/A/S/D/Q/E are read as held keys (flyDirection)
  }
}

}  // namespace

Window::Window(int width, int height, const std::string& title) {
  if (!glfwInit())
    throw Error("cannot open a window: no display (set DISPLAY, or run under xvfb-run for a virtual one)");
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw Error("cannot open a window: GLFW finds no Vulkan loader with window-system support");
  }
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw Error("cannot open a window of " + std::to_string(width) + "x" + std::to_string(height));
  }
  glfwSetWindowUserPointer(window_, this);
  glfwSetKeyCallback(window_, onKey);
  glfwSetMouseButtonCallback(window_, onButton);
  glfwSetCursorPosCallback(window_, onCursor);
  glfwSetScrollCallback(window_, onScroll);
}

Window::~Window() {
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

std::vector<std::string> Window::vulkanInstanceExtensions() const {
  uint32_t n = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&n);
  return std::vector<std::string>(names, names + n);
}

VkSurfaceKHR Window::createSurface(VkInstance instance) const {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  if (glfwCreateWindowSurface(instance, window_, nullptr, &surface) != VK_SUCCESS)
    throw Error("cannot create a Vulkan surface for the window");
  return surface;
}

void Window::poll(std::deque<InputEvent>& out) {
  glfwPollEvents();
  while (!pending_.empty()) {
    out.push_back(pending_.front());
    pending_.pop_front();
  }
}

bool Window::closeRequested() const { return glfwWindowShouldClose(window_); }

void Window::framebufferSize(int& width, int& height) const { glfwGetFramebufferSize(window_, &width, &height); }

void Window::resize(int width, int height) { glfwSetWindowSize(window_, width, height); }

void Window::setTitle(const std::string& title) { glfwSetWindowTitle(window_, title.c_str()); }

glm::vec3 Window::flyDirection() const {
  const std::pair<int, const char*> keys[] = {{GLFW_KEY_W, "w"}, {GLFW_KEY_A, "a"}, {GLFW_KEY_S, "s"},
                                              {GLFW_KEY_D, "d"}, {GLFW_KEY_Q, "q"}, {GLFW_KEY_E, "e"}};
  glm::vec3 direction(0.0f);
  for (const auto& [key, name] : keys)
    if (glfwGetKey(window_, key) == GLFW_PRESS) direction += flyDirectionOf(name);
  return direction;
}

void Window::onKey(GLFWwindow* w, int key, int, int action, int mods) {
  if (action != GLFW_PRESS) return;
  const std::string name = keyName(key, mods);
  if (name.empty()) return;
  InputEvent e;
  e.kind = InputEvent::Kind::Key;
  e.name = name;
  self(w)->pending_.push_back(e);
}

void Window::onButton(GLFWwindow* w, int button, int action, int) {
  Window* me = self(w);
  if (action == GLFW_PRESS && me->dragButton_ < 0) {
    me->dragButton_ = button;
    glfwGetCursorPos(w, &me->lastX_, &me->lastY_);
  } else if (action == GLFW_RELEASE && button == me->dragButton_) {
    me->dragButton_ = -1;
  }
}

void Window::onCursor(GLFWwindow* w, double x, double y) {
  Window* me = self(w);
  if (me->dragButton_ < 0) return;
  InputEvent e;
  e.kind = InputEvent::Kind::Drag;
  e.name = me->dragButton_ == GLFW_MOUSE_BUTTON_LEFT ? "left" : "right";
  e.x = float(x - me->lastX_);
  e.y = float(y - me->lastY_);
  me->lastX_ = x;
  me->lastY_ = y;
  me->pending_.push_back(e);
}

void Window::onScroll(GLFWwindow* w, double, double dy) {
  InputEvent e;
  e.kind = InputEvent::Kind::Scroll;
  e.y = float(dy);
  self(w)->pending_.push_back(e);
}

}  // namespace mixtrace
