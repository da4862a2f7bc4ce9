#pragma once
// The viewer's window (GLFW, no client API: Vulkan presents into it). Turns the window system's
// input into InputEvents (viewer/input.h) and reports which fly keys are held.
#include <deque>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <vulkan/vulkan.h>

#include "viewer/input.h"

struct GLFWwindow;

namespace mixtrace {

class Window {
 public:
  // Throws Error with a one-line reason when no window can be opened (no display).
  Window(int width, int height, const std::string& title);
  ~Window();
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  std::vector<std::string> vulkanInstanceExtensions() const;
  VkSurfaceKHR createSurface(VkInstance instance) const;

  // Processes the window system's events; what the viewer should react to is appended to `out`.
  void poll(std::deque<InputEvent>& out);
  bool closeRequested() const;
  void framebufferSize(int& width, int& height) const;
  void resize(int width, int height);   // scripted resizes
  void setTitle(const std::string& title);
  // Held W/A/S/D/Q/E as a direction in camera space (x right, y up, z forward).
  glm::vec3 flyDirection() const;

 private:
  static void onKey(GLFWwindow* w, int key, int scancode, int action, int mods);
  static void onButton(GLFWwindow* w, int button, int action, int mods);
  static void onCursor(GLFWwindow* w, double x, double y);
  static void onScroll(GLFWwindow* w, double dx, double dy);
  GLFWwindow* window_ = nullptr;
  std::deque<InputEvent> pending_;
  int dragButton_ = -1;
  double lastX_ = 0.0, lastY_ = 0.0;
};

}  // namespace mixtrace
