#include "render/gpu_scene.h"

#include "shared/bindings.h"
#include "vulkan/pipeline.h"

namespace mixtrace {

GpuScene::GpuScene(VulkanContext& ctx, const PreparedScene& p, const shared::CameraGpu& cam)
    : camera(makeBuffer(ctx, std::vector<shared::CameraGpu>{cam}, "camera")),
      nodes(makeBuffer(ctx, p.bvh.nodes, "BVH nodes")),
      triangles(makeBuffer(ctx, p.bvh.triangles, "triangles")),
      shading(makeBuffer(ctx, p.shading, "triangle shading data")),
      materials(makeBuffer(ctx, p.scene.materials, "materials")),
      textures(makeBuffer(ctx, p.textures, "texture table")),
      texels(makeBuffer(ctx, p.texels, "texels")),
      lights(makeBuffer(ctx, p.lights.lights, "lights")),
      emitters(makeBuffer(ctx, p.lights.emitters, "emitters")) {}

void GpuScene::bindTo(DescriptorSet& set) const {
  set.bind(BINDING_CAMERA, camera);
  set.bind(BINDING_BVH_NODES, nodes);
  set.bind(BINDING_TRIANGLES, triangles);
  set.bind(BINDING_TRIANGLE_SHADING, shading);
  set.bind(BINDING_MATERIALS, materials);
  set.bind(BINDING_TEXTURES, textures);
  set.bind(BINDING_TEXELS, texels);
  set.bind(BINDING_LIGHTS, lights);
  set.bind(BINDING_EMITTERS, emitters);
}

}  // namespace mixtrace
