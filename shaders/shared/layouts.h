// Every struct that crosses the host/GPU boundary in a buffer, declared once (each pass's
// push-constant struct lives in its interface header, e.g. shaders/wavefront/shade_interface.h;
// the buffers themselves are the rows of shared/buffer_table.h's tables). GLSL reads these buffers with
// layout(scalar) (VK_EXT_scalar_block_layout, core in Vulkan 1.2), whose packing is exactly C's
// for these types (vec3 is 12 bytes, 4-aligned), so C++ (GLM) and GLSL agree byte for byte. The
// contract is checked twice: host/vulkan/layout_checks.cpp static_asserts every size and offset
// against host/vulkan/gpu_layout_table.inc, and tests/gpu/layout_contract_test.cpp compares them
// with the offsets the compiled shaders declare. A change to a struct here updates that table.
#ifndef MIXTRACE_SHARED_LAYOUTS_H
#define MIXTRACE_SHARED_LAYOUTS_H
#include "shared/dialect.h"
SHARED_BEGIN

// Pinhole camera; the image size decides the aspect ratio.
struct CameraGpu {
  vec3 position;
  float tanHalfFovY;   // tan(yfov / 2)
  vec3 right;          // unit vectors of the camera frame in world space
  float aspect;        // width / height
  vec3 up;
  uint width;
  vec3 forward;
  uint height;
};

// Flattened BVH node: an interior node of the binary tree holding both children's boxes, so a
// visit reads one 64-byte node (one cache line) and tests both, and a child taken from the stack
// needs no read to know what it is. A child reference (leftRef, rightRef) is an interior child's
// node index, or for a leaf kBvhLeafRef | triangle count << kBvhLeafCountShift | first triangle
// (BVH order). Node 0 is the root; a tree that is one leaf is node 0 with that leaf on the left
// and an empty leaf (no triangles) with the same box on the right (host/bvh/bvh_gpu_layout.h).
struct BvhNode {
  vec3 leftMin;
  uint leftRef;
  vec3 leftMax;
  uint rightRef;
  vec3 rightMin;
  uint pad0;   // pads the node to 64 bytes; never read
  vec3 rightMax;
  uint pad1;
};
const uint kBvhLeafRef = 0x80000000u;
const uint kBvhLeafCountShift = 28u;         // the count in bits 28-30: up to 7 (kBvhMaxLeafSize is 4)
const uint kBvhLeafFirstMask = 0x0FFFFFFFu;  // the first triangle in bits 0-27: 268 M triangles
const uint kTexelsPerBvhNode = 4u;           // 16-byte texels of a node (a TEXELS row, gpu/texel_rows.glsl)

// A child reference's encoding, written by the flattener (host/bvh/bvh_gpu_layout.cpp) and read by
// the traversal (shared/bvh_traverse.h).
SHARED_FN uint bvhLeafRef(uint first, uint count) { return kBvhLeafRef | (count << kBvhLeafCountShift) | first; }
SHARED_FN bool bvhRefIsLeaf(uint ref) { return (ref & kBvhLeafRef) != 0u; }
SHARED_FN uint bvhLeafFirst(uint ref) { return ref & kBvhLeafFirstMask; }
SHARED_FN uint bvhLeafCount(uint ref) { return (ref & ~kBvhLeafRef) >> kBvhLeafCountShift; }

// Intersection data of one triangle, in BVH order: v0 and the two edges v1-v0, v2-v0, each with
// a word beside it, so a pass reads a triangle as three 16-byte texel fetches (a TEXELS row): on
// lavapipe, with the light selection specialised, that took intersect 8-10 % and shade (which
// reads the hit and light triangles) 15-20 % below the storage-buffer loads, for a third more
// memory (benchmarks/README.md, "What a pass costs on lavapipe").
struct TriangleGeom {
  vec3 v0;
  float toUnit;     // the intersection test's exact rescaling (triangleGeom below), 2^-e
  vec3 e1;
  float fromUnit;   // and back, 2^e
  vec3 e2;
  uint pad;
};
const uint kTexelsPerTriangleGeom = 3u;

// A triangle's intersection data from v0 and its edges. The test (shared/bvh_traverse.h
// bvhIntersectTriangle) forms t scaled by the cube of the triangle's size (1e45 for a room scaled
// by 1e15: infinite in float; 1e-36 at 1e-12: near underflow), so it first multiplies the edges
// and the origin's offset by toUnit, a power of two near 1 / the largest edge component, and t
// back by fromUnit. A power of two is an exact factor: every product rounds exactly as unscaled,
// only the exponents move. Computed here once per triangle rather than at every test.
SHARED_FN TriangleGeom triangleGeom(vec3 v0, vec3 e1, vec3 e2) {
  TriangleGeom g;
  g.v0 = v0;
  g.e1 = e1;
  g.e2 = e2;
  vec3 extent = max(abs(e1), abs(e2));
  int exponent = clamp((floatBitsToInt(max(max(extent.x, extent.y), extent.z)) >> 23) & 255, 1, 253);
  g.toUnit = intBitsToFloat((254 - exponent) << 23);   // 2^-(exponent - 127)
  g.fromUnit = intBitsToFloat(exponent << 23);         // 2^(exponent - 127)
  g.pad = 0u;
  return g;
}

// Shading data of one triangle, in BVH order.
struct TriangleShading {
  vec3 n0;
  vec3 n1;
  vec3 n2;
  vec2 uv0;
  vec2 uv1;
  vec2 uv2;
  uint material;
  int emitter;         // index into the emitter buffer, -1 when the triangle does not emit
  uvec2 color0;        // COLOR_0 at each corner (shared/vertex_color.h); white where the file has none
  uvec2 color1;
  uvec2 color2;
  uint tangent0;       // the tangent at each corner (shared/tangent_frame.h); 0 where none
  uint tangent1;
  uint tangent2;
  uint pad0;           // pads the struct to seven 16-byte texels (a TEXELS row); never read
  uint pad1;
};
const uint kTexelsPerTriangleShading = 7u;

const uint kMaterialDoubleSided = 1u;
const uint kMaterialAlphaMask = 2u;    // alphaMode MASK: cut where alpha < alphaCutoff (shared/alpha.h)
const uint kMaterialAlphaBlend = 4u;   // alphaMode BLEND: stochastic transparency
const uint kMaterialVolumetric = 8u;   // KHR_materials_volume thickness > 0: glass bends light (dielectric.h)
// The texture slots that read the triangle's second texture coordinates (TriangleUvs), where a
// material's textures name two different sets or transforms (shared/triangle_attributes.h slotUv).
const uint kMaterialSecondUvBaseColor = 16u;
const uint kMaterialSecondUvMetallicRoughness = 32u;
const uint kMaterialSecondUvEmissive = 64u;
const uint kMaterialSecondUvNormal = 128u;
const uint kMaterialSecondUvTransmission = 256u;
const uint kMaterialSecondUvAny = 496u;

// A triangle's second texture coordinates at its corners (its material's second TEXCOORD set or
// transform), in the TRIANGLE_UV2 buffer, present only where a material reads them.
struct TriangleUvs {
  vec2 uv0;
  vec2 uv1;
  vec2 uv2;
};

// glTF metallic-roughness material; textures are -1 when absent.
struct MaterialGpu {
  vec3 baseColor;
  float metallic;
  vec3 emission;       // emissiveFactor * KHR_materials_emissive_strength
  float roughness;
  int baseColorTexture;
  int metallicRoughnessTexture;
  int emissiveTexture;
  uint flags;          // kMaterialDoubleSided, kMaterialAlphaMask, kMaterialAlphaBlend, kMaterialVolumetric, kMaterialSecondUv*
  float alpha;         // baseColorFactor's alpha (read only under MASK or BLEND)
  float alphaCutoff;   // MASK's threshold
  int normalTexture;   // -1: none (shared/surface.h perturbs the shading normal with it)
  float normalScale;   // normalTexture.scale: multiplies the map's x and y
  float transmission;  // KHR_materials_transmission's transmissionFactor (0: opaque)
  int transmissionTexture;   // -1: none; its red channel multiplies transmission
  float ior;           // KHR_materials_ior (1.5 without it)
  uint padMaterial;
};
const uint kTexelsPerMaterial = 5u;

// glTF sampler wrap modes.
const uint kWrapRepeat = 0u;
const uint kWrapClamp = 1u;
const uint kWrapMirror = 2u;
// TextureGpu.sampling's bit for a glTF magFilter of NEAREST: the texel a point lies in, unfiltered
// (bilinear without it). Bits 0-1 hold wrapS, bits 2-3 wrapT.
const uint kTextureNearest = 16u;

// A texture inside the texel buffer (RGBA8 packed in a uint, row-major, top row first).
struct TextureGpu {
  uint offset;         // first texel
  uint width;
  uint height;
  uint sampling;       // wrapS | (wrapT << 2) | kTextureNearest when the glTF sampler's magFilter is NEAREST
};

// A TextureGpu from the uvec4 the texture table stores it as (shared/scene_buffers.h): a pass
// loads the record in one access, where lavapipe loads a struct from a storage buffer one member
// at a time, each a loop over the lanes (a textured scene's shade pass: 12 % faster).
SHARED_FN TextureGpu textureFromWords(uvec4 w) {
  TextureGpu t;
  t.offset = w.x;
  t.width = w.y;
  t.height = w.z;
  t.sampling = w.w;
  return t;
}

const uint kLightArea = 0u;
const uint kLightPoint = 1u;
const uint kLightSpot = 2u;
const uint kLightDirectional = 3u;
// The environment (shared/environment.h): no position, all directions, not a delta light. Its
// LightGpu carries only its kind; the map and its distribution are the ENVIRONMENT buffer.
const uint kLightEnvironment = 4u;

// A light: an emissive primitive (its triangles are emitters [firstEmitter, +emitterCount)) or a
// punctual light. Only what describes the light: how a method picks it is LightSelectionGpu, in a
// buffer of the method's beside the scene's.
struct LightGpu {
  uint kind;
  uint firstEmitter;
  uint emitterCount;
  float spotScale;     // glTF spot falloff: clamp(cos * scale + offset, 0, 1)^2
  vec3 position;       // point and spot
  float spotOffset;
  vec3 direction;      // spot and directional: the direction the light travels
  vec3 intensity;      // colour * intensity (W/sr, or W/m^2 for directional)
  uint pad0;           // to whole texels (a TEXELS row: the shade pass reads a light per lane)
  uint pad1;
};
const uint kTexelsPerLight = 4u;

// How a method picks a light (host/scene/light_selection.h's LightSelection has these values; the
// vertex passes are specialised by it, SPEC_LIGHT_SELECTION):
//   uniform: every emissive triangle and every punctual light equally likely, the "uniform light
//            selection" of the paper's baseline, of SeeSharp and of pbrt-v4's UniformLightSampler
//            (each makes every emissive triangle a light): a light by its triangle count, then a
//            triangle of it uniformly
//   power:   a light by its emitted power, then a triangle by area x radiance (EmitterGpu.pmf)
//   bvh:     a light by the light BVH at the shading point, then a triangle as for power
const uint kLightSelectUniform = 0u;
const uint kLightSelectPower = 1u;
const uint kLightSelectBvh = 2u;

// How a method picks light i (host/cms/method_lights.h builds one per light of the scene): the
// light-selection distribution and, for the methods with light clusters, the cluster the light
// belongs to and its fixed probability inside it. Read through LIGHT_SELECT_PMF(i),
// LIGHT_SELECT_CDF(i), LIGHT_CLUSTER(i) and LIGHT_CLUSTER_PMF(i).
struct LightSelectionGpu {
  float pmf;           // probability of picking the light
  float cdf;           // inclusive prefix sum of pmf over the lights
  uint cluster;        // its CMS light cluster (its own index when the method has none)
  float clusterPmf;    // fixed probability of the light inside its cluster
};
const uint kTexelsPerLightSelection = 1u;

// One entry of the light BVH (host/scene/light_bvh.h builds it, shared/light_bvh.h descends it):
// node 0 is the header, node 1 + i is light i's entry (a leaf, or a directional light, which has
// no position and is chosen apart), then the directional lights' list, then the interior nodes.
//   header:      first = root (kNoHit: no light in the tree), second = start of the directional
//                list, third = its length, power = probability of picking a directional light
//   leaf:        first = the light, second = its bit-trail from the root (bit d set: the second
//                child at depth d), third = the trail's length
//   interior:    first, second = the children
//   directional: first = the light, power = its selection pmf (entry 1 + i), or its inclusive CDF
//                inside the directional list (a list entry)
// Leaves and interior nodes bound their lights: the box, the emitted power (luminance) and the
// orientation cone (Conty Estevez & Kulla 2018): the normals lie within theta_o of `axis`, and each
// emits within theta_e of its normal.
const uint kLightBvhHeader = 0u;
const uint kLightBvhInterior = 1u;
const uint kLightBvhLeaf = 2u;
const uint kLightBvhDirectional = 3u;
struct LightBvhNodeGpu {
  vec3 boundsMin;
  float power;
  vec3 boundsMax;
  float cosThetaO;
  vec3 axis;
  float cosThetaE;
  uint kind;
  uint first;
  uint second;
  uint third;
};
const uint kTexelsPerLightBvhNode = 4u;

// An emissive triangle of an area light, chosen inside its light by area * radiance.
struct EmitterGpu {
  uint triangle;       // BVH-order triangle index
  uint light;
  float pmf;           // probability inside its light by area x radiance (uniform selection: 1 / count)
  float cdf;           // inclusive prefix sum of pmf inside its light
};
const uint kTexelsPerEmitter = 1u;

// The probability of emitter `em` inside its light of `emitterCount` emitters: uniform under
// uniform selection (EMITTERS_UNIFORM), else its area x radiance pmf. One formula for the
// shaders' sampling (shared/lights.h emitterPmf) and the host's technique shares
// (cms/light_techniques.cpp).
SHARED_FN float emitterPmfInLight(EmitterGpu em, uint emitterCount, bool uniformInLight) {
  return uniformInLight ? 1.0f / float(emitterCount) : em.pmf;
}

// CMS path state: what the next depth needs to settle a vertex's BSDF sample (its control-variate
// and statistics terms depend on what the sample hits).
struct CvPathState {
  vec3 throughput;   // the vertex's path throughput
  uint cell;         // the vertex's cell (kNoCell: none)
  vec3 bsdfCos;      // bsdf * cos of the BSDF sample
  float pad;
};

// Result of an extension-ray intersection. triangle == kNoHit for a miss.
const uint kNoHit = 0xffffffffu;
struct HitRecord {
  float t;
  uint triangle;
  float u;             // barycentrics of v1 and v2
  float v;
};

// A pending shadow ray and the radiance it adds to its path when unoccluded.
// With controlled mixture sampling the light sample's control-variate and statistics terms also
// wait for visibility (docs/estimator.md §1: a light point hidden from the vertex is a point the
// BSDF cannot sample, p_B = 0 there): the shadow pass pays them with the p_B that visibility
// decides.
struct ShadowRay {
  vec3 origin;
  float tMax;
  vec3 direction;
  uint path;
  vec3 contribution;   // throughput * integrand / p_eff, added when unoccluded
  uint cell;           // CMS cell of the vertex (kNoCell: no statistics, no control variate)
  vec3 integrand;      // Le * bsdf * cos, without throughput
  uint cluster;        // CMS: the sample's cluster k
  vec3 throughput;     // CMS: the vertex's throughput (for the control-variate term)
  float pk;            // CMS: p_k(z) of the light sample
  float pB;            // CMS: p_B(z) if the point is visible
  float ck;            // CMS: c_k of the vertex's cell
  uint flags;          // kShadowRayCms: pay the CMS terms
  uint source;         // per-triangle CV: the light point's technique source (shared/cms_pair_state.h)
};
const uint kShadowRayCms = 1u;
// The per-triangle control variate (shaders/wavefront/shade_interface.h says why): records the
// shadow pass settles without tracing. A light sample at a hidden point (integrand 0, pB 0), and a
// BSDF sample whose hit lies on a light technique: cell, source, pk = p_j, pB = p_B, ck = p_eff,
// integrand = f, throughput, contribution.x = the statistics weight.
const uint kShadowRayHidden = 2u;
const uint kShadowRayBsdfPair = 4u;

// Queue counters and indirect dispatch arguments, in one buffer.
struct DispatchArgs {
  uint x;
  uint y;
  uint z;
};
struct QueueState {
  uint rayCount[2];    // ping-pong extension-ray queues
  uint shadowCount;
  uint nonFinite;      // samples dropped from the image because they were NaN or Inf
  DispatchArgs rayArgs;
  DispatchArgs shadowArgs;
  uint extensionRays[2];  // rays traced so far, 64-bit as (low, high): counted by prepare.comp
  uint shadowRays[2];
  uint verticesWithoutCell;  // CMS: vertices that found the cell table full (no control variate)
  // Records of this depth's shadow queue that trace no ray (kShadowRayHidden, kShadowRayBsdfPair:
  // the per-triangle control variate's terms), so that shadowRays counts rays only.
  uint untracedShadows;
  // The rays intersect queued for the shade pass (the ray queue's third kShadeQueue: those that
  // hit something, where the renderer has it queue them: IntersectConstants.queueForShade), the
  // shade pass's indirect dispatch arguments for them, and their count so far, 64-bit (low, high):
  // counted by prepare.comp.
  uint shadeCount;
  DispatchArgs shadeArgs;
  uint shadedRays[2];
};

// A light of a cluster, in the cluster-grouped list: cdf is inclusive inside its cluster.
struct ClusterLightGpu {
  uint light;
  float cdf;
};

const uint kWorkgroupSize = 64u;
// The third of the ray queue (RAY_QUEUE, shared/path_state.h) that holds the shade queue; 0 and 1
// are the extension rays' ping-pong halves.
const uint kShadeQueue = 2u;

SHARED_END
#endif
