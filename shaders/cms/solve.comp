#version 460
#extension GL_GOOGLE_include_directive : require
// Controlled mixture sampling, between iterations: solves every cell's system from the statistics
// the shade pass gathered and writes its control-variate coefficients and selection pmf (the maths
// and its robustness rules: shared/cms_solve.h). One invocation per cell; the cells are spread
// over a 2D grid of workgroups so that any cell count fits the dispatch limits
// (host/wavefront/passes/solve_pass.cpp).
#include "cms/solve_interface.h"
#define PASS_BUFFERS SOLVE_BUFFERS
#define PASS_CONSTANTS SolveParams
#include "gpu/buffers.glsl"

#define CELL_STATS(i) cellStats[i]
#define CELL_SAMPLES(i) cellSamples[i]
#define CELL_SOLUTION(i) cellSolution[i]
#define CLUSTER_DEFAULT(i) clusterDefaults[i]
#include "shared/cms_solve.h"

layout(local_size_x = kWorkgroupSize) in;

void main() {
  uint cell = gl_GlobalInvocationID.y * (gl_NumWorkGroups.x * kWorkgroupSize) + gl_GlobalInvocationID.x;
  if (cell >= pc.cellCount) return;
  solveCell(cell, pc);
}
