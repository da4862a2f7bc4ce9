#version 460
#extension GL_GOOGLE_include_directive : require
// The interface's pair-table rows (shared/cms_pair_state.h) name 64-bit keys.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
// Stage 3: at every queued path's hit: emission (MIS-weighted against light sampling), one light
// sample (queued as a shadow ray with its contribution) and one BSDF sample (the next extension
// ray). Balance heuristic over the two techniques: p_eff = p_light + p_bsdf.
//
// With controlled mixture sampling (CMS_SELECTION: methods learned, cv, cms) the light comes from
// a cluster chosen by the vertex's cell, p_eff = c_k p_k + p_B, and every sample adds its terms
// of A and b to the cell (docs/estimator.md §4); with CMS_CONTROL_VARIATE (cv, cms) the vertex also
// pays the control variate: + sum(alpha) - g(z)/p_eff(z) for both samples (docs/estimator.md §3).
// The BSDF sample's terms depend on what it hits, so they are paid at the start of the next depth's
// shade.
#include "wavefront/shade_interface.h"
#define PASS_BUFFERS SHADE_BUFFERS
#define PASS_CONSTANTS VertexConstants
#define PASS_READS_SOLUTION_VIEWS
#include "gpu/cms_buffers.glsl"
#include "gpu/buffers.glsl"
// pt-bvh picks lights by the method's light BVH (shared/light_bvh.h, through shared/lights.h).
#define LIGHT_BVH(i) LIGHT_BVH_FROM_TEXELS(i)
#define LIGHT_SELECT_BVH (LIGHT_SELECTION == kLightSelectBvh)
#define EMITTERS_UNIFORM (LIGHT_SELECTION == kLightSelectUniform)
#include "gpu/cms_statistics.glsl"
#include "gpu/queue_append.glsl"
#include "shared/bsdf.h"
#include "shared/cms_sampling.h"
#include "shared/cms_technique_source.h"
#include "shared/cms_vertex_terms.h"
#include "shared/ray_offset.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/scatter_side.h"
#include "shared/surface.h"

layout(local_size_x = kWorkgroupSize) in;

// What the steps below know of the vertex at this ray's hit.
struct Vertex {
  uint path;
  SurfaceHit sh;
  BsdfParams bsdf;
  OrthonormalBasis frame;
  vec3 wo;       // towards the previous vertex, in the shading frame
  vec3 origin;   // the offset origin of the rays leaving the vertex
  vec3 originBelow;   // the same on the far side, for transmitted rays (= origin when opaque)
  vec3 beta;     // the path throughput up to the vertex
  uint cell;     // CMS: the vertex's cell (kNoCell: none, or no CMS)
  bool cv;       // CMS: the cell pays a control variate
};

// Appends a record to the shadow queue, member by member, the CMS members only for the methods
// that read them: lavapipe stores each member in a loop over the lanes whether or not the shadow
// pass reads it (the 14 stores were a fifth of pt-power's shade pass; the shadow pass reads
// `flags` only under CMS_SELECTION too).
void queueShadowRecord(ShadowRay s) {
  uint slot;
  QUEUE_APPEND(queues.shadowCount, slot);
  shadowQueue[slot].origin = s.origin;
  shadowQueue[slot].tMax = s.tMax;
  shadowQueue[slot].direction = s.direction;
  shadowQueue[slot].path = s.path;
  shadowQueue[slot].contribution = s.contribution;
  if (CMS_SELECTION) {
    shadowQueue[slot].cell = s.cell;
    shadowQueue[slot].integrand = s.integrand;
    shadowQueue[slot].cluster = s.cluster;
    shadowQueue[slot].throughput = s.throughput;
    shadowQueue[slot].pk = s.pk;
    shadowQueue[slot].pB = s.pB;
    shadowQueue[slot].ck = s.ck;
    shadowQueue[slot].flags = s.flags;
    shadowQueue[slot].source = s.source;
  }
}

// CMS: the previous vertex's BSDF sample, now that its hit is known (docs/estimator.md §3, §4): it
// pays its control-variate term and adds its statistics. Returns the balance-heuristic weight of
// the emission it reached against the cell's light selection.
float settlePreviousBsdfSample(uint path, HitRecord hit, SurfaceHit sh, vec3 le, float prevPdfB) {
  uint L = pc.clusterCount;
  uint prevCell = cvState[path].cell;
  float pj;
  uint j = clusterOfBsdfHit(hit.triangle, le, rayOrigin[path], sh.position, rayDirection[path], pj);
  float cj = bsdfHitClusterWeight(prevCell, L, j, hit.triangle, rayOrigin[path], misNormal[path]);
  float peff = bsdfSampleMixtureDensity(j, cj, pj, prevPdfB);
  bool cv = CMS_CONTROL_VARIATE && cellSolutionValid(prevCell, L);
  float w = sampleWeight(cvState[path].throughput, path, prevCell);
  if (CMS_PAIR_TECHNIQUES && j != kNoCell && prevCell != kNoCell && (cv || w > 0.0)) {
    // Per technique: the hit triangle's technique (host/cpu/cpu_cms_path.cpp
    // settlePendingBsdfSample); its pair lives in the shadow pass's rows, so its control-variate
    // term and statistics are settled there.
    ShadowRay s;
    s.origin = vec3(0.0);
    s.tMax = 0.0;
    s.direction = vec3(0.0);
    s.path = path;
    s.contribution = vec3(w, 0.0, 0.0);
    s.cell = prevCell;
    s.integrand = le * cvState[path].bsdfCos;
    s.cluster = j;
    s.throughput = cvState[path].throughput;
    s.pk = pj;
    s.pB = prevPdfB;
    s.ck = peff;
    s.flags = kShadowRayBsdfPair;
    s.source = techniqueSourceOfHit(hit.triangle, pc.emitterCount);
    queueShadowRecord(s);
    atomicAdd(queues.untracedShadows, 1u);   // a record, not a ray (the stats count rays)
  } else if (CMS_PAIR_TECHNIQUES) {
    // No light technique: g = alpha_B p_B alone.
    if (cv) radiance[path] -= controlVariateTerm(cvState[path].throughput, prevCell, L, kNoCell, 0.0, prevPdfB, peff);
  } else if (cv) {
    radiance[path] -= controlVariateTerm(cvState[path].throughput, prevCell, L, j, pj, prevPdfB, peff);
  }
  if (prevCell != kNoCell && passGathersStatistics())
    addSampleStatistics(prevCell, L, j, pj, prevPdfB, peff, le * cvState[path].bsdfCos, w);
  return balanceWeight(prevPdfB, peff);
}

// Emission reached by this ray (an emitter's, or the environment's where it escaped), weighted
// against light sampling (a camera ray's is not: p_B = 0).
void addEmission(uint path, HitRecord hit, SurfaceHit sh, vec3 le, vec3 beta, float prevPdfB, float cmsWeight) {
  float w = 1.0;
  if (prevPdfB > 0.0) {
    if (CMS_SELECTION) {
      w = cmsWeight;
    } else {
      float lightPdf = hit.triangle == kNoHit
                           ? environmentLightPdfAt(rayOrigin[path], misNormal[path], rayDirection[path])
                           : emitterLightPdfAt(uint(sh.emitter), hit.triangle, rayOrigin[path], misNormal[path],
                                                   sh.position);
      w = prevPdfB / (prevPdfB + lightPdf);
    }
  }
  radiance[path] += beta * le * w;
}

// CMS: the vertex's cell (found or claimed), counted while it gathers, shown by the viewer's cell
// views at depth 1; a cell with a solution pays the control variate's integral at once (§3).
void enterCell(INOUT(Vertex) v) {
  uint L = pc.clusterCount;
  v.cell = findOrInsertCell(pushedCellGrid(), v.sh.position, v.sh.geometricNormal, v.sh.material);
  countCellVertex(v.cell);
  if (pc.depth == 1u) firstCell[pc.pixelOffset + v.path] = v.cell;
  v.cv = CMS_CONTROL_VARIATE && cellSolutionValid(v.cell, L);
  if (v.cv) radiance[v.path] += controlVariateIntegral(v.beta, v.cell, L);
}

// One light sample (next event estimation), queued as a shadow ray with its contribution. Plain
// MIS picks a light from the scene's selection; CMS a cluster from the cell's, and a hidden point
// (§1, lightPointReachable) settles its terms at once, with no shadow ray; a reachable one with
// the shadow ray, because whether the BSDF could have sampled it (p_B) depends on visibility.
void queueLightSample(Vertex v, INOUT(uint) rng) {
  float uLight = rngNextFloat(rng);
  float uEmitter = rngNextFloat(rng);
  vec2 uPoint = vec2(rngNextFloat(rng), rngNextFloat(rng));
  if (pc.lightCount == 0u) return;
  uint L = pc.clusterCount;
  LightSample ls;
  bool carries;
  uint k = kNoCell;
  float pk = 0.0;
  float ck = 0.0;
  if (CMS_SELECTION) {
    carries = sampleClusterLight(v.cell, L, v.sh.position, v.origin, v.sh.geometricNormal, uLight, uEmitter, uPoint,
                                 rng, k, pk, ck, ls);
    if (k == kNoCell) return;   // the defaults' BVH reached no light: no sample, nothing to pay
  } else {
    // Chosen at the rays' origin and the geometric normal: what addEmission's MIS weight of this
    // vertex's BSDF sample has (rayOrigin, misNormal).
    carries = sampleLightAt(v.sh.position, v.origin, v.sh.geometricNormal, pc.lightCount, uLight, uEmitter, uPoint, ls);
  }
  bool cmsTerms = CMS_SELECTION && v.cell != kNoCell;
  if (!(ls.pdf > 0.0 || cmsTerms)) return;
  vec3 wi = toLocal(v.frame, ls.direction);
  bool reachable = lightPointReachable(ck, v.sh.geometricNormal, wi.z, bsdfTransmits(v.bsdf), carries, pk, ls);
  float pB;
  vec3 f = lightSampleIntegrand(v.bsdf, v.wo, wi, ls, reachable, pB);
  float peff = lightSampleMixtureDensity(ls.pdf, pB);
  vec3 contribution = v.beta * f / peff;
  uint source = CMS_PAIR_TECHNIQUES && cmsTerms ? techniqueSourceOfLightSample(ls, pc.emitterCount) : 0u;
  if (cmsTerms && !reachable && !CMS_PAIR_TECHNIQUES) {
    settleLightSample(v.cell, k, pk, ck, 0.0, f, v.beta, v.path, source);
  } else if (!isBlack(contribution) || cmsTerms) {
    // (A hidden point with the per-triangle control variate: queued untraced, kShadowRayHidden.)
    ShadowRay s;
    s.origin = originTowards(ls.direction, v.sh.geometricNormal, v.origin, v.originBelow);
    shadowRay(s.origin, ls, s.direction, s.tMax);
    s.path = v.path;
    s.contribution = contribution;
    s.cell = v.cell;
    s.integrand = f;
    s.cluster = k;
    s.throughput = v.beta;
    s.pk = pk;
    s.pB = pB;
    s.ck = ck;
    s.flags = (cmsTerms ? kShadowRayCms : 0u) | (reachable ? 0u : kShadowRayHidden);
    s.source = source;
    queueShadowRecord(s);
    if (!reachable) atomicAdd(queues.untracedShadows, 1u);
  }
}

// One BSDF sample: the next extension ray. Under CMS its terms depend on what it hits, so the
// path state keeps what the next depth's settlePreviousBsdfSample needs; a failed sample settles
// at once.
void sampleBsdf(Vertex v, INOUT(uint) rng) {
  vec2 uDir = vec2(rngNextFloat(rng), rngNextFloat(rng));
  float uLobe = rngNextFloat(rng);
  vec3 wiLocal;
  float pdf;
  rngState[v.path] = rng;
  bool sampled = bsdfSample(v.bsdf, v.wo, uDir, uLobe, wiLocal, pdf) && pdf > 0.0;
  vec3 wiWorld = toWorld(v.frame, wiLocal);
  if (!sampled || !leavesOnShadingSide(wiWorld, v.sh.geometricNormal, wiLocal.z)) {
    // A failed sample, or one on the wrong side of the geometric surface, is still a sample with f = 0 that hits no light
    // (docs/estimator.md §1): g / p_eff = alpha_B, and it adds p_B^2 / p_eff^2 = 1 to A_BB.
    uint L = pc.clusterCount;
    if (v.cv)
      radiance[v.path] -= controlVariateTerm(v.beta, v.cell, L, kNoCell, 0.0, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf);
    if (CMS_SELECTION && v.cell != kNoCell && passGathersStatistics())
      addSampleStatistics(v.cell, L, kNoCell, 0.0, kFailedBsdfSamplePdf, kFailedBsdfSamplePdf, vec3(0.0),
                          sampleWeight(v.beta, v.path, v.cell));
    return;
  }
  vec3 bsdfCos = bsdfEval(v.bsdf, v.wo, wiLocal) * abs(wiLocal.z);
  vec3 weight = bsdfCos / pdf;
  // Without CMS a path that can carry nothing more ends; with it, the ray is still traced so the
  // next depth can settle this sample's control-variate and statistics terms.
  if (!CMS_SELECTION && isBlack(weight)) return;
  throughput[v.path] = v.beta * weight;
  misPdf[v.path] = pdf;
  rayOrigin[v.path] = originTowards(wiWorld, v.sh.geometricNormal, v.origin, v.originBelow);
  rayDirection[v.path] = wiWorld;
  if (LIGHT_SELECT_BVH) misNormal[v.path] = v.sh.geometricNormal;
  if (CMS_SELECTION) {
    CvPathState state;
    state.throughput = v.beta;
    state.cell = v.cell;
    state.bsdfCos = bsdfCos;
    state.pad = 0.0;
    cvState[v.path] = state;
  }
  uint queueOut = 1u - pc.queueIn;
  uint slot;
  QUEUE_APPEND(queues.rayCount[queueOut], slot);
  rayQueue[queueOut * pc.pathCount + slot] = v.path;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= (pc.shadeQueued != 0u ? queues.shadeCount : queues.rayCount[pc.queueIn])) return;
  uint path = rayQueue[(pc.shadeQueued != 0u ? kShadeQueue : pc.queueIn) * pc.pathCount + i];
  HitRecord hit = hits[path];
  vec3 dir = rayDirection[path];
  vec3 beta = throughput[path];
  float prevPdfB = misPdf[path];   // p_B of the BSDF sample that made this ray; 0 for camera rays
  SurfaceHit sh;
  SurfaceMaterial sm;
  if (hit.triangle != kNoHit) {
    sh = makeSurfaceHit(hit.triangle, hit.u, hit.v, dir);
    sm = surfaceMaterial(sh);
  }
  bool hitEmitter = hit.triangle != kNoHit && HAS_AREA_LIGHTS && sh.emitter >= 0;
  bool escaped = hit.triangle == kNoHit && HAS_ENVIRONMENT && hasEnvironmentLight();
  vec3 le = hitEmitter ? surfaceEmission(sh, sm) : escaped ? environmentRadiance(dir) : vec3(0.0);

  float cmsEmissionWeight = 1.0;
  if (CMS_SELECTION && prevPdfB > 0.0) cmsEmissionWeight = settlePreviousBsdfSample(path, hit, sh, le, prevPdfB);
  // The viewer's cell views show the cell of each pixel's first hit (none where the ray escapes).
  if (CMS_SELECTION && pc.depth == 1u && hit.triangle == kNoHit) firstCell[pc.pixelOffset + path] = kNoCell;
  if (hit.triangle == kNoHit) {   // the path ends, with the environment's light if there is one
    if (escaped) addEmission(path, hit, sh, le, beta, prevPdfB, cmsEmissionWeight);
    return;
  }
  if (isBlack(beta)) return;            // continued only to settle the terms above

  if (hitEmitter) addEmission(path, hit, sh, le, beta, prevPdfB, cmsEmissionWeight);
  if (pc.depth >= pc.maxDepth) return;

  Vertex v;
  v.path = path;
  v.sh = sh;
  v.bsdf = surfaceBsdf(sh, sm);
  v.frame = makeOrthonormalBasis(sh.shadingNormal);
  v.wo = toLocal(v.frame, -dir);
  scatterOrigins(sh.position, sh.positionError, sh.geometricNormal, bsdfTransmits(v.bsdf), v.origin,
                 v.originBelow);
  v.beta = beta;
  v.cell = kNoCell;
  v.cv = false;
  if (CMS_SELECTION) enterCell(v);

  uint rng = rngState[path];
  queueLightSample(v, rng);
  sampleBsdf(v, rng);
}
