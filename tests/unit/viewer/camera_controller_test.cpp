// The viewer's camera (host/viewer/camera_controller.h): it starts as the scene's camera, orbit
// keeps the distance to the pivot, pan moves camera and pivot together, zoom approaches the pivot,
// fly moves along the camera's axes, reset returns, and every change bumps the version.
#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include "viewer/camera_controller.h"

namespace mixtrace {
namespace {

shared::CameraGpu sceneCamera() {
  shared::CameraGpu c{};
  c.position = glm::vec3(0.0f, 1.0f, 5.0f);
  c.forward = glm::normalize(glm::vec3(0.0f, -0.2f, -1.0f));
  c.right = glm::normalize(glm::cross(c.forward, glm::vec3(0, 1, 0)));
  c.up = glm::cross(c.right, c.forward);
  c.tanHalfFovY = 0.4f;
  c.aspect = 4.0f / 3.0f;
  c.width = 320;
  c.height = 240;
  return c;
}

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-4f) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(CameraController, StartsAsTheSceneCamera) {
  const shared::CameraGpu initial = sceneCamera();
  CameraController cam(initial, glm::vec3(0.0f), 4.0f);
  const shared::CameraGpu c = cam.camera();
  expectNear(c.position, initial.position);
  expectNear(c.forward, initial.forward);
  expectNear(c.right, initial.right);
  expectNear(c.up, initial.up);
  EXPECT_EQ(c.width, 320u);
  EXPECT_FLOAT_EQ(c.tanHalfFovY, initial.tanHalfFovY);
}

TEST(CameraController, OrbitKeepsThePivotAndItsDistance) {
  CameraController cam(sceneCamera(), glm::vec3(0.0f), 4.0f);
  const glm::vec3 pivot = cam.pivot();
  const float distance = glm::length(pivot - cam.position());
  const unsigned version = cam.version();
  cam.orbit(120.0f, -40.0f);
  expectNear(cam.pivot(), pivot, 1e-3f);
  EXPECT_NEAR(glm::length(cam.pivot() - cam.position()), distance, 1e-3f);
  EXPECT_GT(glm::length(cam.position() - sceneCamera().position), 0.1f) << "the camera moved";
  EXPECT_NE(cam.version(), version);
  const shared::CameraGpu c = cam.camera();   // still an orthonormal frame, horizon level
  EXPECT_NEAR(glm::dot(c.forward, c.right), 0.0f, 1e-5f);
  EXPECT_NEAR(glm::dot(c.up, c.right), 0.0f, 1e-5f);
  EXPECT_NEAR(c.right.y, 0.0f, 1e-5f) << "orbiting rolled the horizon";
  for (int i = 0; i < 100; ++i) cam.orbit(0.0f, -1000.0f);   // pitch clamps short of the pole
  EXPECT_TRUE(std::isfinite(cam.camera().right.x));
  EXPECT_LT(std::abs(cam.forward().y), 1.0f);
}

TEST(CameraController, PanMovesCameraAndPivotTogether) {
  CameraController cam(sceneCamera(), glm::vec3(0.0f), 4.0f);
  const glm::vec3 offset = cam.pivot() - cam.position();
  const glm::vec3 right = cam.camera().right;
  cam.pan(-50.0f, 0.0f, 240.0f);   // dragging left moves the view right
  expectNear(cam.pivot() - cam.position(), offset);
  EXPECT_GT(glm::dot(cam.position() - sceneCamera().position, right), 0.0f);
}

// Where `point` appears, in pixels of an image `imageHeight` tall (x right, y down from the centre).
glm::vec2 projected(const shared::CameraGpu& c, const glm::vec3& point, float imageHeight) {
  const glm::vec3 d = point - c.position;
  const float depth = glm::dot(d, c.forward);
  const float ndcX = glm::dot(d, c.right) / depth / (c.tanHalfFovY * c.aspect);
  const float ndcY = glm::dot(d, c.up) / depth / c.tanHalfFovY;
  return {0.5f * ndcX * imageHeight * c.aspect, -0.5f * ndcY * imageHeight};
}

// A 320x240 film shown in a 1280x960 window (the viewer scales small films up): a 30 x -20 pixel
// drag must move the picture 30 x -20 window pixels, not 4x that (the film's pixels).
TEST(CameraController, PanMovesThePointUnderTheCursorWithTheMouse) {
  CameraController cam(sceneCamera(), glm::vec3(0.0f), 4.0f);
  const float imageHeight = 960.0f;
  const glm::vec3 grabbed = cam.pivot();
  const glm::vec2 before = projected(cam.camera(), grabbed, imageHeight);
  cam.pan(30.0f, -20.0f, imageHeight);
  const glm::vec2 moved = projected(cam.camera(), grabbed, imageHeight) - before;
  EXPECT_NEAR(moved.x, 30.0f, 0.05f);
  EXPECT_NEAR(moved.y, -20.0f, 0.05f);
}

TEST(CameraController, ZoomApproachesThePivotAndFlyFollowsTheAxes) {
  CameraController cam(sceneCamera(), glm::vec3(0.0f), 4.0f);
  const glm::vec3 pivot = cam.pivot();
  const float before = glm::length(pivot - cam.position());
  cam.zoom(2.0f);
  EXPECT_LT(glm::length(pivot - cam.position()), before);
  expectNear(cam.pivot(), pivot, 1e-3f);
  const glm::vec3 p = cam.position(), f = cam.forward();
  cam.fly(glm::vec3(0, 0, 1), 1.0f);
  EXPECT_NEAR(glm::dot(cam.position() - p, f), 1.0f, 1e-4f) << "a quarter of the scene size per second";
  cam.reset();
  expectNear(cam.position(), sceneCamera().position);
}

}  // namespace
}  // namespace mixtrace
