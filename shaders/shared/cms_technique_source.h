// Which technique source (shared/cms_pair_state.h TECHNIQUES) a sample's light point belongs to:
// apart from shared/cms_pair_terms.h because the Vulkan shade pass names the source without binding
// the pair rows (shaders/wavefront/shade_interface.h). Needs TRIANGLE_SHADING(i) and ENV_DATA(i) only.
#ifndef MIXTRACE_SHARED_CMS_TECHNIQUE_SOURCE_H
#define MIXTRACE_SHARED_CMS_TECHNIQUE_SOURCE_H
#include "shared/dialect.h"
#include "shared/lights.h"
SHARED_BEGIN_WITH_BUFFERS

// The technique source of a light sample's point: its emitter, or emitterCount + light for a
// light without triangles (punctual, the environment: shared/cms_pair_state.h TECHNIQUES).
SHARED_FN uint techniqueSourceOfLightSample(LightSample ls, uint emitterCount) {
  if (ls.triangle == kNoHit) return emitterCount + ls.light;
  return uint(TRIANGLE_SHADING(ls.triangle).emitter);
}

// The technique source of a BSDF sample's hit on emitting triangle `tri`, or of its escape to the
// environment (tri = kNoHit) (only where clusterOfBsdfHit found a cluster: the point emits
// towards the vertex).
SHARED_FN uint techniqueSourceOfHit(uint tri, uint emitterCount) {
  if (tri == kNoHit) return emitterCount + environmentLight();
  return uint(TRIANGLE_SHADING(tri).emitter);
}

SHARED_END_WITH_BUFFERS
#endif
