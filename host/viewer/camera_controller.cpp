#include "viewer/camera_controller.h"

#include <algorithm>
#include <cmath>

namespace mixtrace {
namespace {

constexpr float kOrbitRadiansPerPixel = 0.005f;
constexpr float kMaxPitch = 1.55f;   // just short of straight up or down, where yaw degenerates

}  // namespace

CameraController::CameraController(const shared::CameraGpu& initial, const glm::vec3& sceneCentre, float sceneSize)
    : initial_(initial), sceneSize_(std::max(sceneSize, 1e-6f)) {
  // glTF's up is +Y: orbiting turns around it and never rolls the horizon (a camera looking
  // straight up or down keeps its own up instead).
  worldUp_ = std::abs(glm::normalize(initial.forward).y) < 0.99f ? glm::vec3(0.0f, 1.0f, 0.0f) : glm::normalize(initial.up);
  initialDistance_ = std::max(glm::dot(sceneCentre - initial.position, glm::normalize(initial.forward)), 1e-3f * sceneSize_);
  reset();
}

void CameraController::reset() {
  position_ = initial_.position;
  distance_ = initialDistance_;
  const glm::vec3 f = glm::normalize(initial_.forward);
  pitch_ = std::asin(std::clamp(glm::dot(f, worldUp_), -1.0f, 1.0f));
  glm::vec3 horizontal = f - glm::dot(f, worldUp_) * worldUp_;
  yawZero_ = glm::length(horizontal) > 1e-6f ? glm::normalize(horizontal) : glm::normalize(initial_.right);
  yaw_ = 0.0f;
  ++version_;
}

glm::vec3 CameraController::forward() const {
  const glm::vec3 side = glm::normalize(glm::cross(yawZero_, worldUp_));   // yaw 0's right
  const glm::vec3 horizontal = std::cos(yaw_) * yawZero_ + std::sin(yaw_) * side;
  return glm::normalize(std::cos(pitch_) * horizontal + std::sin(pitch_) * worldUp_);
}

void CameraController::orbit(float dx, float dy) {
  const glm::vec3 p = pivot();
  yaw_ += dx * kOrbitRadiansPerPixel;
  pitch_ = std::clamp(pitch_ - dy * kOrbitRadiansPerPixel, -kMaxPitch, kMaxPitch);
  position_ = p - distance_ * forward();
  ++version_;
}

void CameraController::pan(float dx, float dy, float imageHeightPixels) {
  const shared::CameraGpu c = camera();
  // The image spans 2 distance tan(fov/2) vertically at the pivot's depth: one window pixel is
  // that over the image's height in window pixels (not the film's: the window shows it scaled).
  const float perPixel = 2.0f * distance_ * c.tanHalfFovY / std::max(imageHeightPixels, 1.0f);
  position_ += (-dx * c.right + dy * c.up) * perPixel;
  ++version_;
}

void CameraController::zoom(float steps) {
  const glm::vec3 p = pivot();
  distance_ = std::max(distance_ * std::pow(0.85f, steps), 1e-4f * sceneSize_);
  position_ = p - distance_ * forward();
  ++version_;
}

void CameraController::fly(const glm::vec3& local, float seconds) {
  const shared::CameraGpu c = camera();
  const float speed = 0.25f * sceneSize_;   // a quarter of the scene per second
  position_ += (local.x * c.right + local.y * c.up + local.z * c.forward) * speed * seconds;
  ++version_;
}

shared::CameraGpu CameraController::camera() const {
  shared::CameraGpu c = initial_;
  c.position = position_;
  c.forward = forward();
  c.right = glm::normalize(glm::cross(c.forward, worldUp_));
  c.up = glm::cross(c.right, c.forward);
  return c;
}

}  // namespace mixtrace
