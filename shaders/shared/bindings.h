// Binding numbers of the one descriptor set every pass uses (set 0), shared by the host, which
// writes the set, and the shaders, which declare the buffers (shaders/gpu/buffers.glsl).
// Plain #defines because GLSL layout qualifiers need them as preprocessor constants.
#ifndef MIXTRACE_SHARED_BINDINGS_H
#define MIXTRACE_SHARED_BINDINGS_H

// Scene (read-only, uploaded once)
#define BINDING_CAMERA 0
#define BINDING_BVH_NODES 1
#define BINDING_TRIANGLES 2
#define BINDING_TRIANGLE_SHADING 3
#define BINDING_MATERIALS 4
#define BINDING_TEXTURES 5
#define BINDING_TEXELS 6
#define BINDING_LIGHTS 7
#define BINDING_EMITTERS 8
// Path state (structure of arrays, one entry per path of the wavefront)
#define BINDING_RAY_ORIGIN 9
#define BINDING_RAY_DIRECTION 10
#define BINDING_THROUGHPUT 11
#define BINDING_RADIANCE 12
#define BINDING_RNG 13
#define BINDING_MIS_PDF 14
#define BINDING_HITS 15
// Queues
#define BINDING_RAY_QUEUE 16      // 2 * pathCount entries: ping-pong halves
#define BINDING_SHADOW_QUEUE 17
#define BINDING_QUEUE_STATE 18
// Film
#define BINDING_FILM 19           // per pixel: running mean and sum of squared deviations (vec3 each)
// Controlled mixture sampling (shaders/shared/cms_layouts.h)
#define BINDING_CELL_STATS 20     // float[cells * cellStatsStride(L)]
#define BINDING_CELL_SAMPLES 21   // uint[cells]: samples per cell
#define BINDING_CELL_SOLUTION 22  // float[cells * cellSolutionStride(L)]
#define BINDING_CLUSTER_DEFAULTS 23  // float[L]: default selection pmf over clusters
#define BINDING_CELL_KEYS 24      // uint64[tableSize]: hashed cell keys, 0 = empty (cms_cells.h)
#define BINDING_CLUSTERS 25       // ClusterGpu[L]
#define BINDING_CLUSTER_LIGHTS 26 // ClusterLightGpu[lights]: lights grouped by cluster, with CDFs
#define BINDING_CV_STATE 27       // CvPathState per path: the previous vertex's cell, throughput, bsdf * cos
#define BINDING_PIXEL_ESTIMATE 28  // vec3[pixels]: the pixel values CMS weights relate to (pixel_estimate.h)
#define BINDING_FIRST_CELL 29     // uint[pixels]: the cell of each pixel's first hit (CMS; viewer debug views)
// The viewer (host/viewer): the display pass's output, packed 8-bit colour per window pixel
#define BINDING_DISPLAY 30
// The method's light selection (LightSelectionGpu per light, host/cms/method_lights.h): beside the
// scene's lights because the scene is prepared once for every method
#define BINDING_LIGHT_SELECTION 31
// Lavapipe allows 32 storage buffers per stage: keep BINDING_COUNT <= 32.
#define BINDING_COUNT 32

// Specialization constants: the scene's feature set (host/scene/features.h fills them).
#define SPEC_HAS_TEXTURES 0
#define SPEC_HAS_AREA_LIGHTS 1
#define SPEC_HAS_PUNCTUAL_LIGHTS 2
#define SPEC_HAS_METALS 3
#define SPEC_SINGLE_LIGHT 4
#define SPEC_CMS_SELECTION 5         // lights chosen through per-cell cluster selection (learned, cv, cms)
#define SPEC_CMS_CONTROL_VARIATE 6   // the control variate (cv, cms)
#define SPEC_CMS_RELATIVE_WEIGHT 7   // relative-throughput statistics weights (docs/estimator.md §5)
#define SPEC_COUNT 8

#endif
