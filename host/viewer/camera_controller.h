#pragma once
// The viewer's camera: starts as the scene's camera and moves as a user expects from a 3D viewer,
// with glTF's +Y as up.
// Orbit turns the camera around a pivot in front of it (the point it looks at, at the distance of
// the scene's centre), pan slides camera and pivot sideways, zoom moves the camera towards the
// pivot, and fly (WASD, Q/E) moves both along the camera's axes. Pure maths: no window needed.
#include <glm/glm.hpp>

#include "shared/layouts.h"

namespace mixtrace {

class CameraController {
 public:
  // `initial` as makeCamera() builds it; `sceneSize` sets the speeds (the bounds' diagonal).
  CameraController(const shared::CameraGpu& initial, const glm::vec3& sceneCentre, float sceneSize);

  void orbit(float dxPixels, float dyPixels);     // mouse drag with the left button
  // Right or middle button. `imageHeightPixels`: the height the image covers in the window, in
  // the units of dx, dy (the film is letterboxed: shared/display.h), so that the point under the
  // cursor, at the pivot's depth, moves by exactly the mouse's delta.
  void pan(float dxPixels, float dyPixels, float imageHeightPixels);
  void zoom(float steps);                         // scroll wheel: positive moves closer
  void fly(const glm::vec3& localDirection, float seconds);  // x right, y up, z forward
  void reset();

  shared::CameraGpu camera() const;   // for the renderer (width and height as `initial`)
  glm::vec3 pivot() const { return position_ + distance_ * forward(); }
  glm::vec3 position() const { return position_; }
  glm::vec3 forward() const;
  // Bumped on every change, so renderers know when to start accumulating again.
  unsigned version() const { return version_; }

 private:
  shared::CameraGpu initial_;
  glm::vec3 worldUp_;
  float initialDistance_, sceneSize_;
  glm::vec3 position_;
  float yaw_ = 0.0f, pitch_ = 0.0f;   // radians; forward from yaw/pitch around worldUp_
  float distance_;                    // camera to pivot
  glm::vec3 yawZero_;                 // the horizontal direction of yaw 0
  unsigned version_ = 0;
};

}  // namespace mixtrace
