// The sparse CMS solve pass (cms/sparse_solve.comp): the per-triangle control variate's pair
// statistics (walked through the list of occupied slots), the cells' BSDF rows and the techniques'
// clusters and shares in; alpha_t and the solved flag per pair and alpha_B, validity and sum of alpha
// per cell out (shared/cms_sparse_solve.h). Pushed SparseSolveConstants. Declared once for the
// shader and the host (host/wavefront/passes/sparse_solve_pass.cpp).
#ifndef MIXTRACE_CMS_SPARSE_SOLVE_INTERFACE_H
#define MIXTRACE_CMS_SPARSE_SOLVE_INTERFACE_H
#include "shared/cms_layouts.h"
#include "shared/cms_pair_state.h"
#include "shared/cms_sparse_solve.h"
#include "shared/cms_state.h"

#define SPARSE_SOLVE_BUFFERS(X)                                                                      \
  BUFFER_PAIR_KEYS(X) BUFFER_PAIR_STATS(X) BUFFER_PAIR_SAMPLES(X) BUFFER_PAIR_ALPHA(X)              \
  BUFFER_PAIR_OCCUPIED(X) BUFFER_CELL_STATS(X) BUFFER_CELL_SAMPLES(X) BUFFER_CELL_SOLUTION(X)         \
  BUFFER_SPARSE_SCRATCH(X) BUFFER_SPARSE_ARGS(X) BUFFER_TECHNIQUE_CLUSTERS(X)

#endif
