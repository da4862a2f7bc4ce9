// The CMS solve pass (cms/solve.comp), between training iterations: every cell's statistics in,
// its control-variate coefficients and selection pmf out. Pushed SolveParams
// (shared/cms_layouts.h). Declared once for the shader and the host (host/wavefront/passes/solve_pass.cpp).
#ifndef MIXTRACE_CMS_SOLVE_INTERFACE_H
#define MIXTRACE_CMS_SOLVE_INTERFACE_H
#include "shared/cms_layouts.h"
#include "shared/cms_state.h"

#define SOLVE_BUFFERS(X) BUFFER_CELL_STATS(X) BUFFER_CELL_SAMPLES(X) BUFFER_CELL_SOLUTION(X) BUFFER_CLUSTER_DEFAULTS(X)

#endif
