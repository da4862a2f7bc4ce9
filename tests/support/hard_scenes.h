#pragma once
// Small glTF scenes built at test time that stress the numerics of light sampling and of the
// CMS statistics and solve (docs/estimator.md §6): light powers over eight orders of magnitude, a
// light that only a few cells can reach, degenerate and tiny emitters, near-mirrors next to small
// lights, and one room at very small and very large scale. Every scene is a closed room (no
// escaping paths) seen from inside; the builders return the glTF text.
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "support/analytic/gltf_writer.h"
#include "support/analytic/meshes.h"

namespace mixtrace::testing::hard {

using analytic::CameraSpec;
using analytic::GltfWriter;
using analytic::MaterialSpec;
using analytic::rectangle;
using analytic::Tri;

// Axis-aligned box [lo, hi] as six rectangles whose front faces point `inward` or outward.
inline void addBox(GltfWriter& w, glm::dvec3 lo, glm::dvec3 hi, int material, bool inward) {
  const glm::dvec3 d = hi - lo, ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
  const double s = inward ? 1.0 : -1.0;
  w.addMesh(rectangle(lo, ex, ez, {0, s, 0}), material);                     // floor
  w.addMesh(rectangle(lo + ey, ex, ez, {0, -s, 0}), material);               // ceiling
  w.addMesh(rectangle(lo, ey, ez, {s, 0, 0}), material);                     // x = lo.x
  w.addMesh(rectangle(lo + ex, ey, ez, {-s, 0, 0}), material);               // x = hi.x
  w.addMesh(rectangle(lo, ex, ey, {0, 0, s}), material);                     // z = lo.z
  w.addMesh(rectangle(lo + ez, ex, ey, {0, 0, -s}), material);               // z = hi.z
}

// The room [-1, 1] x [0, 2] x [-1, 1] times `scale`: grey floor, ceiling and back/front walls,
// a red left and a green right wall (so a wrong light pdf shows up per channel), all diffuse.
inline void addRoom(GltfWriter& w, double scale) {
  const int grey = w.addMaterial({glm::vec3(0.7f)});
  const int red = w.addMaterial({glm::vec3(0.7f, 0.15f, 0.1f)});
  const int green = w.addMaterial({glm::vec3(0.15f, 0.6f, 0.1f)});
  const double s = scale;
  w.addMesh(rectangle({-s, 0, -s}, {2 * s, 0, 0}, {0, 0, 2 * s}, {0, 1, 0}), grey);       // floor
  w.addMesh(rectangle({-s, 2 * s, -s}, {2 * s, 0, 0}, {0, 0, 2 * s}, {0, -1, 0}), grey);  // ceiling
  w.addMesh(rectangle({-s, 0, -s}, {2 * s, 0, 0}, {0, 2 * s, 0}, {0, 0, 1}), grey);       // back wall
  w.addMesh(rectangle({-s, 0, s}, {2 * s, 0, 0}, {0, 2 * s, 0}, {0, 0, -1}), grey);       // front wall
  w.addMesh(rectangle({-s, 0, -s}, {0, 2 * s, 0}, {0, 0, 2 * s}, {1, 0, 0}), red);        // left wall
  w.addMesh(rectangle({s, 0, -s}, {0, 2 * s, 0}, {0, 0, 2 * s}, {-1, 0, 0}), green);      // right wall
}

// From near the front wall at eye height, looking slightly down at the back wall: the ceiling
// (and any light on it) stays out of view, so no emitter edge dominates the pixel variances.
inline CameraSpec roomCamera(double scale) {
  CameraSpec c;
  c.position = glm::dvec3(0.0, 1.0, 0.9) * scale;
  c.target = glm::dvec3(0.0, 0.8, -1.0) * scale;
  c.yfov = 1.0;
  return c;
}

// A downward-facing emissive square of side `side` centred at `centre`.
inline void addCeilingLight(GltfWriter& w, glm::dvec3 centre, double side, float radiance) {
  const int m = w.addMaterial({glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(radiance)});
  w.addMesh(rectangle(centre - glm::dvec3(side / 2, 0, side / 2), {side, 0, 0}, {0, 0, side}, {0, -1, 0}), m);
}

// Scene 5 (and the reference for the power check): the room with one ceiling light and a box on
// the floor casting a shadow, all positions times `scale`; the emission does not scale, so the
// image is the same at every scale. `lightFactor` scales the light's radiance.
inline std::string scaledRoomScene(double scale, float lightFactor = 1.0f) {
  GltfWriter w;
  addRoom(w, scale);
  addBox(w, glm::dvec3(-0.6, 0.0, -0.7) * scale, glm::dvec3(-0.1, 0.6, -0.2) * scale,
         w.addMaterial({glm::vec3(0.6f, 0.6f, 0.8f)}), false);
  addCeilingLight(w, glm::dvec3(0.2, 1.999, -0.2) * scale, 0.5 * scale, 5.0f * lightFactor);
  w.setCamera(roomCamera(scale));
  return w.json();
}

// Scene 1: five ceiling lights whose radiance spans 1e-4 .. 1e4 (written through
// KHR_materials_emissive_strength above 1): cluster contributions, the CV coefficients and the
// learned selection probabilities all span eight orders of magnitude.
inline std::string powerSpanScene() {
  GltfWriter w;
  addRoom(w, 1.0);
  const float radiance[5] = {1e-4f, 1e-2f, 1.0f, 1e2f, 1e4f};
  for (int i = 0; i < 5; ++i) addCeilingLight(w, {-0.8 + 0.4 * i, 1.999, -0.3}, 0.1, radiance[i]);
  w.setCamera(roomCamera(1.0));
  return w.json();
}

// Scene 2: a bright light inside a closed box on the floor whose only opening is a 4 cm square
// hole facing the right wall: it lights a spot there and little else, so most cells never see
// that cluster (an all-zero row of the CMS system) while a dim ceiling light reaches everything.
inline std::string nicheScene() {
  GltfWriter w;
  addRoom(w, 1.0);
  addCeilingLight(w, {0.0, 1.999, 0.0}, 0.4, 1.0f);
  const int wall = w.addMaterial({glm::vec3(0.5f), 0.0f, 1.0f, glm::vec3(0.0f), true});
  // Box [-0.9, -0.6] x [0.3, 0.6] x [-0.6, -0.3]; its +x face has the hole around (y, z) = (0.45, -0.45).
  const double x0 = -0.9, x1 = -0.6, y0 = 0.3, y1 = 0.6, z0 = -0.6, z1 = -0.3, h = 0.02, yc = 0.45, zc = -0.45;
  w.addMesh(rectangle({x0, y0, z0}, {x1 - x0, 0, 0}, {0, 0, z1 - z0}, {0, 1, 0}), wall);
  w.addMesh(rectangle({x0, y1, z0}, {x1 - x0, 0, 0}, {0, 0, z1 - z0}, {0, -1, 0}), wall);
  w.addMesh(rectangle({x0, y0, z0}, {x1 - x0, 0, 0}, {0, y1 - y0, 0}, {0, 0, 1}), wall);
  w.addMesh(rectangle({x0, y0, z1}, {x1 - x0, 0, 0}, {0, y1 - y0, 0}, {0, 0, -1}), wall);
  w.addMesh(rectangle({x0, y0, z0}, {0, y1 - y0, 0}, {0, 0, z1 - z0}, {1, 0, 0}), wall);
  // The holed face at x = x1 as four strips around the hole.
  w.addMesh(rectangle({x1, y0, z0}, {0, yc - h - y0, 0}, {0, 0, z1 - z0}, {-1, 0, 0}), wall);
  w.addMesh(rectangle({x1, yc + h, z0}, {0, y1 - yc - h, 0}, {0, 0, z1 - z0}, {-1, 0, 0}), wall);
  w.addMesh(rectangle({x1, yc - h, z0}, {0, 2 * h, 0}, {0, 0, zc - h - z0}, {-1, 0, 0}), wall);
  w.addMesh(rectangle({x1, yc - h, zc + h}, {0, 2 * h, 0}, {0, 0, z1 - zc - h}, {-1, 0, 0}), wall);
  // The light on the inner face opposite the hole, facing it.
  const int light = w.addMaterial({glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(2000.0f)});
  w.addMesh(rectangle({x0 + 0.001, yc - 0.05, zc - 0.05}, {0, 0.1, 0}, {0, 0, 0.1}, {1, 0, 0}), light);
  w.setCamera(roomCamera(1.0));
  return w.json();
}

// Scene 3: a normal ceiling light next to emitters the loader must drop (every triangle of one
// mesh has zero area; another mesh mixes a good triangle with a point-like one) and a 1e-5 x 1e-5
// emitter (area 1e-10 of the room's 2 x 2 walls) bright enough (1e10) to light the floor like a
// point light: its light-sampling pdf is ~1e10 and BSDF sampling essentially never hits it. It is
// kept out of view, where a pixel sample would hit it about once in 1e8, with value 1e10.
inline std::string degenerateEmittersScene() {
  GltfWriter w;
  addRoom(w, 1.0);
  addCeilingLight(w, {-0.3, 1.999, -0.3}, 0.5, 5.0f);
  const int bright = w.addMaterial({glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(100.0f)});
  const glm::vec3 a(0.3f, 1.5f, 0.0f), b(0.5f, 1.5f, 0.0f), c(0.7f, 1.5f, 0.0f);
  w.addMesh({Tri{{a, b, c}}, Tri{{a, a, b}}}, bright);  // collinear, repeated vertex: zero area
  const glm::vec3 p(0.0f, 1.2f, 0.4f);
  std::vector<Tri> mixed = rectangle({-0.2, 1.2, 0.2}, {0.1, 0, 0}, {0, 0, 0.1}, {0, -1, 0});
  mixed.push_back(Tri{{p, p, p}});
  w.addMesh(mixed, w.addMaterial({glm::vec3(0.0f), 0.0f, 1.0f, glm::vec3(3.0f)}));
  const double side = 1e-5;
  addCeilingLight(w, {0.5, 1.9, -0.5}, side, 1e10f);  // above the camera's view
  w.setCamera(roomCamera(1.0));
  return w.json();
}

// Scene 4: a metallic floor of roughness 0.02 (GGX alpha 4e-4: BSDF values up to ~1e6) with two
// small bright lights hanging 0.3 above it; the camera looks down onto the floor, so their
// highlights are in view, and the rest of the room is lit mostly through the mirror.
inline std::string nearMirrorScene() {
  GltfWriter w;
  addRoom(w, 1.0);
  const int mirror = w.addMaterial({glm::vec3(0.9f), 1.0f, 0.02f});
  w.addMesh(rectangle({-1.0, 0.001, -1.0}, {2.0, 0, 0}, {0, 0, 2.0}, {0, 1, 0}), mirror);
  addCeilingLight(w, {-0.3, 0.3, -0.4}, 0.05, 500.0f);
  addCeilingLight(w, {0.4, 0.3, -0.6}, 0.05, 300.0f);
  CameraSpec camera = roomCamera(1.0);
  camera.target = {0.0, 0.0, -1.0};
  w.setCamera(camera);
  return w.json();
}

}  // namespace mixtrace::testing::hard
