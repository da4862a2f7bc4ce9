#include "scene/prepared_scene.h"

#include <atomic>
#include <cmath>

#include "scene/environment_distribution.h"
#include "shared/tangent_frame.h"
#include "shared/vertex_color.h"
#include "util/error.h"
#include "util/log.h"

namespace mixtrace {
namespace {
std::atomic<uint64_t> gPreparedScenes{0};
}  // namespace

uint64_t preparedSceneCount() { return gPreparedScenes.load(); }

PreparedScene prepareScene(Scene scene) {
  if (scene.triangles.empty()) throw Error(scene.name + " contains no triangles");
  ++gPreparedScenes;
  PreparedScene p;
  p.bvh = buildBvh(cornersOf(scene.triangles));
  p.lights = buildLightSet(scene, p.bvh.triangleOrder);
  p.features = deriveFeatures(scene, p.lights);
  p.environment = buildEnvironmentBuffer(scene.environment, p.lights.environmentLight);
  if (p.lights.lights.empty()) warn(scene.name + " has no lights: the image will be black");

  p.shading.resize(p.bvh.triangleOrder.size());
  for (size_t b = 0; b < p.shading.size(); ++b) {
    const Triangle& t = scene.triangles[p.bvh.triangleOrder[b]];
    shared::TriangleShading& s = p.shading[b];
    s.n0 = t.n[0]; s.n1 = t.n[1]; s.n2 = t.n[2];
    s.uv0 = t.uv[0]; s.uv1 = t.uv[1]; s.uv2 = t.uv[2];
    s.material = t.material;
    s.emitter = p.lights.triangleEmitter[b];
    s.color0 = shared::packVertexColor(t.color[0]);
    s.color1 = shared::packVertexColor(t.color[1]);
    s.color2 = shared::packVertexColor(t.color[2]);
    s.tangent0 = shared::packTangent(t.tangent[0]);
    s.tangent1 = shared::packTangent(t.tangent[1]);
    s.tangent2 = shared::packTangent(t.tangent[2]);
  }
  // Second texture coordinates only where a material reads them: no memory for the rest.
  p.secondUvs.assign(p.features.secondUvs ? p.shading.size() : 1, shared::TriangleUvs{});
  if (p.features.secondUvs) {
    for (size_t b = 0; b < p.shading.size(); ++b) {
      const Triangle& t = scene.triangles[p.bvh.triangleOrder[b]];
      p.secondUvs[b] = shared::TriangleUvs{t.uv2[0], t.uv2[1], t.uv2[2]};
    }
  }
  for (const Texture& t : scene.textures) {
    shared::TextureGpu g{};
    g.offset = uint32_t(p.texels.size());
    g.width = t.width;
    g.height = t.height;
    g.sampling = t.wrapS | (t.wrapT << 2u) | (t.nearest ? shared::kTextureNearest : 0u);
    p.texels.insert(p.texels.end(), t.texels.begin(), t.texels.end());
    p.textures.push_back(g);
  }
  p.scene = std::move(scene);
  return p;
}

Camera defaultFraming(const Scene& scene) {
  // Frame the bounding sphere from +Z, looking down -Z, with the default field of view.
  Camera cam;
  float radius = std::max(0.5f * glm::length(scene.bounds.extent()), 1e-6f);
  float distance = radius / std::sin(0.5f * cam.yfov) * 1.05f;
  cam.forward = glm::vec3(0.0f, 0.0f, -1.0f);
  cam.up = glm::vec3(0.0f, 1.0f, 0.0f);
  cam.position = scene.bounds.center() - distance * cam.forward;
  return cam;
}

shared::CameraGpu makeCamera(const Scene& scene, uint32_t width, uint32_t height) {
  const Camera cam = scene.camera.fromFile ? scene.camera : defaultFraming(scene);
  shared::CameraGpu c{};
  c.position = cam.position;
  c.forward = glm::normalize(cam.forward);
  c.right = glm::normalize(glm::cross(c.forward, cam.up));
  c.up = glm::cross(c.right, c.forward);
  c.tanHalfFovY = std::tan(0.5f * cam.yfov);
  c.aspect = float(width) / float(height);
  c.width = width;
  c.height = height;
  return c;
}

}  // namespace mixtrace
