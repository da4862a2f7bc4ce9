#pragma once
// The prepared scene's arrays in device storage buffers, uploaded once.
#include "scene/prepared_scene.h"
#include "vulkan/buffer.h"

namespace mixtrace {

class VulkanContext;
class DescriptorSet;

struct GpuScene {
  GpuScene(VulkanContext& ctx, const PreparedScene& scene, const shared::CameraGpu& camera);
  void bindTo(DescriptorSet& set) const;

  Buffer camera, nodes, triangles, shading, materials, textures, texels, lights, emitters;
};

}  // namespace mixtrace
