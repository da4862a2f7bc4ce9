#include "wavefront/gpu_scene.h"

#include "shared/scene_buffers.h"

namespace mixtrace {

GpuScene::GpuScene(VulkanContext& ctx, const PreparedScene& p, const shared::CameraGpu& cam)
    : camera(makeBuffer(ctx, std::vector<shared::CameraGpu>{cam}, "camera")),
      bvhNodes(makeBuffer(ctx, p.bvh.nodes, "BVH nodes")),
      triangles(makeBuffer(ctx, p.bvh.triangles, "triangles")),
      triangleShading(makeBuffer(ctx, p.shading, "triangle shading data")),
      materials(makeBuffer(ctx, p.scene.materials, "materials")),
      textures(makeBuffer(ctx, p.textures, "texture table")),
      texels(makeBuffer(ctx, p.texels, "texels")),
      lights(makeBuffer(ctx, p.lights.lights, "lights")),
      emitters(makeBuffer(ctx, p.lights.emitters, "emitters")),
      environment(makeBuffer(ctx, p.environment, "environment map")),
      triangleUv2(makeBuffer(ctx, p.secondUvs, "second texture coordinates")) {}

void GpuScene::offerTo(BufferBindings& buffers) const {
#define OFFER_SCENE_BUFFER(ID, name, binding, access, Type, extent, label) buffers[shared::BINDING_##ID] = &name;
  SCENE_BUFFERS(OFFER_SCENE_BUFFER)
#undef OFFER_SCENE_BUFFER
}

}  // namespace mixtrace
