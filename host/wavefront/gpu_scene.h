#pragma once
// The prepared scene's arrays in device storage buffers, uploaded once: the rows of
// shaders/shared/scene_buffers.h, each member named as the shaders name the buffer.
#include "scene/prepared_scene.h"
#include "vulkan/buffer.h"
#include "vulkan/pipeline.h"

namespace mixtrace {

class VulkanContext;

struct GpuScene {
  GpuScene(VulkanContext& ctx, const PreparedScene& scene, const shared::CameraGpu& camera);
  void offerTo(BufferBindings& buffers) const;   // every row, at its binding number

  Buffer camera, bvhNodes, triangles, triangleShading, materials, textures, texels, lights, emitters, environment, triangleUv2;
};

}  // namespace mixtrace
