#version 460
#extension GL_GOOGLE_include_directive : require
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
#include "gpu/cms_buffers.glsl"
#include "gpu/buffers.glsl"
#include "gpu/cms_statistics.glsl"
#include "shared/bsdf.h"
#include "shared/cms_sampling.h"
#include "shared/ray_offset.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/surface.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= queues.rayCount[pc.queueIn]) return;
  uint path = rayQueue[pc.queueIn * pc.pathCount + i];
  HitRecord hit = hits[path];
  vec3 dir = rayDirection[path];
  vec3 beta = throughput[path];
  uint L = pc.clusterCount;
  float prevPdfB = misPdf[path];   // p_B of the BSDF sample that made this ray; 0 for camera rays
  bool hitEmitter = hit.triangle != kNoHit && HAS_AREA_LIGHTS && triangleShading[hit.triangle].emitter >= 0;
  vec3 le = hitEmitter ? emittedRadiance(hit.triangle, hit.u, hit.v, -dir) : vec3(0.0);
  SurfaceHit sh;
  if (hit.triangle != kNoHit) sh = makeSurfaceHit(hit.triangle, hit.u, hit.v, dir);

  // CMS: the previous vertex's BSDF sample, now that its hit is known.
  float emissionWeight = 1.0;
  if (CMS_SELECTION && prevPdfB > 0.0) {
    uint prevCell = cvState[path].cell;
    uint j = kNoCell;
    float pj = 0.0;
    // A light point that emits nothing towards the vertex (a one-sided emitter's back) counts as
    // no light point at all, for BSDF and light samples alike (see the light sample below).
    if (!isBlack(le)) {
      j = LIGHT_CLUSTER(lightOfTriangle(hit.triangle));
      pj = clusterPointPdf(hit.triangle, rayOrigin[path], sh.position);
    }
    float peff = (j != kNoCell ? clusterSelectPmf(prevCell, L, j) * pj : 0.0) + prevPdfB;
    emissionWeight = prevPdfB / peff;
    if (CMS_CONTROL_VARIATE && cellSolutionValid(prevCell, L)) {
      vec3 g = cellAlphaB(prevCell, L) * prevPdfB;
      if (j != kNoCell) g += cellAlpha(prevCell, L, j) * pj;
      radiance[path] -= cvState[path].throughput * g / peff;
    }
    if (prevCell != kNoCell && passGathersStatistics()) {
      float w = sampleWeight(cvState[path].throughput, path, prevCell);
      if (w > 0.0) addSampleToA(prevCell, j, pj, prevPdfB, peff, w);
      if (w > 0.0 && j != kNoCell) addSampleToB(prevCell, j, le * cvState[path].bsdfCos, pj, prevPdfB, peff, w);
    }
  }
  // The viewer's cell views show the cell of each pixel's first hit (none where the ray escapes).
  if (CMS_SELECTION && pc.depth == 1u && hit.triangle == kNoHit) firstCell[pc.pixelOffset + path] = kNoCell;
  if (hit.triangle == kNoHit) return;   // no environment light: the path ends
  if (isBlack(beta)) return;            // continued only to settle the terms above

  // Emission reached by this ray.
  if (hitEmitter) {
    float w = 1.0;
    if (prevPdfB > 0.0) {
      if (CMS_SELECTION) {
        w = emissionWeight;
      } else {
        float lightPdf = areaLightPdf(hit.triangle, rayOrigin[path], sh.position);
        w = prevPdfB / (prevPdfB + lightPdf);
      }
    }
    radiance[path] += beta * le * w;
  }
  if (pc.depth >= pc.maxDepth) return;

  uint rng = rngState[path];
  BsdfParams bsdf = surfaceBsdf(sh);
  OrthonormalBasis frame = makeOrthonormalBasis(sh.shadingNormal);
  vec3 wo = toLocal(frame, -dir);
  vec3 origin = offsetRayOrigin(sh.position, hitPointError(hit.triangle, hit.u, hit.v), sh.geometricNormal);

  uint cell = kNoCell;
  bool cv = false;
  if (CMS_SELECTION) {
    CellGrid grid;
    grid.origin = pc.gridOrigin;
    grid.invCellSize = pc.gridInvCellSize;
    grid.tableSize = pc.cellTableSize;
    cell = findOrInsertCell(grid, sh.position, sh.geometricNormal, sh.material);
    if (cell != kNoCell) {
      if (gatheringStatistics(cell)) atomicAdd(cellSamples[cell], 1u);
    }
    else atomicAdd(queues.verticesWithoutCell, 1u);
    if (pc.depth == 1u) firstCell[pc.pixelOffset + path] = cell;
    cv = CMS_CONTROL_VARIATE && cellSolutionValid(cell, L);
    if (cv) radiance[path] += beta * cellAlphaSum(cell, L);
  }

  // One light sample (next event estimation).
  float uLight = rngNextFloat(rng);
  float uEmitter = rngNextFloat(rng);
  vec2 uPoint = vec2(rngNextFloat(rng), rngNextFloat(rng));
  if (pc.lightCount > 0u) {
    LightSample ls;
    bool carries;
    uint k = kNoCell;
    float pk = 0.0;
    if (CMS_SELECTION) {
      k = selectCluster(cell, L, uLight);
      uint light = selectLightInCluster(k, rngNextFloat(rng));
      carries = sampleLightPoint(sh.position, light, uEmitter, uPoint, ls);
      pk = LIGHT_CLUSTER_PMF(light) * ls.pdf;
      ls.pdf = clusterSelectPmf(cell, L, k) * pk;
    } else {
      carries = sampleLight(sh.position, pc.lightCount, uLight, uEmitter, uPoint, ls);
    }
    bool cmsTerms = CMS_SELECTION && cell != kNoCell;
    if (ls.pdf > 0.0 || cmsTerms) {
      vec3 wi = toLocal(frame, ls.direction);
      bool above = dot(ls.direction, sh.geometricNormal) > 0.0;
      if (!(ls.pdf > 0.0)) {
        // A point with no solid-angle density from here (in this surface's plane, e.g. a light
        // sampling itself) is a hidden point: p_B = 0 there, and with p_k in the light's own area
        // measure the terms only need ratios, so any positive p_k does (docs/estimator.md §1).
        above = false;
        carries = false;
        pk = 1.0;
        ls.pdf = clusterSelectPmf(cell, L, k);
      }
      // A point below the surface is hidden by the surface itself. A point that emits nothing
      // towards this vertex (a one-sided emitter's back, a spot's outside) is, for controlled
      // mixture sampling, a hidden point too, whatever lies between: the BSDF sample treats such
      // a hit as no light either (above), so each technique's density stays the density of its
      // own samples and every term stays unbiased, and no shadow ray is needed.
      bool reachable = above && carries;
      float pB = (ls.isDelta || !reachable) ? 0.0 : bsdfPdf(bsdf, wo, wi);
      float peff = ls.pdf + pB;
      vec3 f = vec3(0.0);
      if (reachable) f = bsdfEval(bsdf, wo, wi) * abs(wi.z) * ls.radiance;
      vec3 contribution = beta * f / peff;
      float ck = ls.pdf / max(pk, 1e-38);   // the cell's c_k (ls.pdf = c_k p_k)
      if (cmsTerms && !reachable) {
        settleLightSample(cell, k, pk, ck, 0.0, f, beta, path);
      } else if (!isBlack(contribution) || cmsTerms) {
        // CMS: whether the BSDF could have sampled this point (p_B) depends on its visibility, so
        // the sample's control-variate and statistics terms go with the shadow ray.
        ShadowRay s;
        s.origin = origin;
        shadowRay(origin, ls, s.direction, s.tMax);
        s.path = path;
        s.contribution = contribution;
        s.cell = cell;
        s.integrand = f;
        s.cluster = k;
        s.throughput = beta;
        s.pk = pk;
        s.pB = pB;
        s.ck = ck;
        s.flags = cmsTerms ? kShadowRayCms : 0u;
        s.pad = 0.0;
        uint slot = atomicAdd(queues.shadowCount, 1u);
        shadowQueue[slot] = s;
      }
    }
  }

  // One BSDF sample: the next extension ray.
  vec2 uDir = vec2(rngNextFloat(rng), rngNextFloat(rng));
  float uLobe = rngNextFloat(rng);
  vec3 wiLocal;
  float pdf;
  rngState[path] = rng;
  bool sampled = bsdfSample(bsdf, wo, uDir, uLobe, wiLocal, pdf) && pdf > 0.0;
  vec3 wiWorld = toWorld(frame, wiLocal);
  if (!sampled || !(dot(wiWorld, sh.geometricNormal) > 0.0)) {
    // A failed sample, or one into the surface, is still a sample with f = 0 that hits no light
    // (docs/estimator.md §2): g / p_eff = alpha_B, and it adds p_B^2 / p_eff^2 = 1 to A_BB.
    if (cv) radiance[path] -= beta * cellAlphaB(cell, L);
    if (CMS_SELECTION && cell != kNoCell && passGathersStatistics())
      addStat(cell, statsABB(L), sampleWeight(beta, path, cell));
    return;
  }
  vec3 bsdfCos = bsdfEval(bsdf, wo, wiLocal) * abs(wiLocal.z);
  vec3 weight = bsdfCos / pdf;
  // Without CMS a path that can carry nothing more ends; with it, the ray is still traced so the
  // next depth can settle this sample's control-variate and statistics terms.
  if (!CMS_SELECTION && isBlack(weight)) return;
  throughput[path] = beta * weight;
  misPdf[path] = pdf;
  rayOrigin[path] = origin;
  rayDirection[path] = wiWorld;
  if (CMS_SELECTION) {
    CvPathState state;
    state.throughput = beta;
    state.cell = cell;
    state.bsdfCos = bsdfCos;
    state.pad = 0.0;
    cvState[path] = state;
  }
  uint queueOut = 1u - pc.queueIn;
  uint slot = atomicAdd(queues.rayCount[queueOut], 1u);
  rayQueue[queueOut * pc.pathCount + slot] = path;
}
