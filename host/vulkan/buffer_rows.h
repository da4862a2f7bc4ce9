#pragma once
// Every row of every buffer table (shaders/shared/buffer_table.h) in one list, for what must see
// them all: that no two rows share a binding number (layout_checks.cpp) and the descriptor type
// of each binding (pipeline.cpp: a TEXELS row is a storage texel buffer, the rest are storage
// buffers).
#include <cstdint>

#include "shared/cms_pair_state.h"
#include "shared/cms_sparse_solve.h"
#include "shared/cms_state.h"
#include "shared/method_buffers.h"
#include "shared/path_state.h"
#include "shared/scene_buffers.h"
#include "tests/pair_lookup_interface.h"
#include "tests/texel_rows_interface.h"
#include "viewer/display_interface.h"

#define EVERY_BUFFER_ROW(X)                                                                          \
  SCENE_BUFFERS(X) PATH_STATE_BUFFERS(X) CMS_STATE_BUFFERS(X) CMS_STATE_VIEWS(X) CMS_PAIR_VIEWS(X) METHOD_BUFFERS(X) BUFFER_WINDOW(X) \
  PAIR_LOOKUP_BUFFERS(X) BUFFER_SPARSE_SCRATCH(X) BUFFER_TECHNIQUE_CLUSTERS(X) TEXEL_ROWS_OUT_BUFFERS(X)

namespace mixtrace {

// Whether `binding` is a TEXELS row's: bound as a storage texel buffer of RGBA32UI texels.
constexpr bool isTexelBinding(uint32_t binding) {
#define ROW_IS_TEXELS(ID, name, number, access, Type, extent, label) \
  if (binding == uint32_t(number)) return BUFFER_IS_TEXELS_##access;
  EVERY_BUFFER_ROW(ROW_IS_TEXELS)
#undef ROW_IS_TEXELS
  return false;
}

}  // namespace mixtrace
