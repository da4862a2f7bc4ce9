// What a pipeline is built with besides its code: the binding numbers of every buffer (from the
// buffer tables: shared/scene_buffers.h, shared/path_state.h, shared/cms_state.h, each row
// declaring BINDING_<ID>; each pass binds only the rows its interface header lists, e.g.
// shaders/wavefront/shade_interface.h) and the specialization constants, shared by the host and
// the shaders. Plain #defines for the constant ids because GLSL layout qualifiers read them.
#ifndef MIXTRACE_SHARED_BINDINGS_H
#define MIXTRACE_SHARED_BINDINGS_H
#include "shared/cms_state.h"
#include "shared/method_buffers.h"
#include "shared/path_state.h"
#include "shared/scene_buffers.h"

// Specialization constants: the scene's feature set (host/scene/features.h fills them).
#define SPEC_HAS_TEXTURES 0
#define SPEC_HAS_AREA_LIGHTS 1
#define SPEC_HAS_PUNCTUAL_LIGHTS 2
#define SPEC_HAS_METALS 3
#define SPEC_SINGLE_LIGHT 4
#define SPEC_CMS_SELECTION 5         // lights chosen through per-cell cluster selection (learned, cv, cms)
#define SPEC_CMS_CONTROL_VARIATE 6   // the control variate (cv, cms)
#define SPEC_CMS_RELATIVE_WEIGHT 7   // relative-throughput statistics weights (docs/estimator.md §5)
#define SPEC_CMS_PAIR_TECHNIQUES 8   // the per-triangle control variate (shared/cms_pair_terms.h; cv, cms)
#define SPEC_HAS_ENVIRONMENT 9       // an environment light (shared/environment.h)
#define SPEC_HAS_VERTEX_COLORS 10     // COLOR_0 on some triangle (shared/vertex_color.h)
#define SPEC_HAS_ALPHA 11             // alphaMode MASK or BLEND on some material (shared/alpha.h)
#define SPEC_HAS_NORMAL_MAPS 12       // a material with a normalTexture (shared/surface.h)
#define SPEC_HAS_TRANSMISSION 13      // a material with KHR_materials_transmission (shared/dielectric.h)
#define SPEC_HAS_SECOND_UVS 14        // a material whose textures read two texture-coordinate mappings
// The method's light selection (kLightSelect*, shared/layouts.h). A constant, not a push constant:
// on lavapipe a branch costs its code whether or not a lane takes it (gallivm runs both sides of
// an `if` under a lane mask), so a selection the method never uses must not be in its pipelines.
#define SPEC_LIGHT_SELECTION 15
#define SPEC_COUNT 16

#endif
