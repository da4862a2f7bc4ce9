// A 64-bit to 32-bit mix (the finaliser of MurmurHash3's 64-bit variant, folded), shared by the
// hashed tables (the CMS cell table, shared/cms_cells.h, and the (cell, technique) pair table,
// shared/cms_pair_layout.h): neighbouring keys land far apart.
#ifndef MIXTRACE_SHARED_HASH64_H
#define MIXTRACE_SHARED_HASH64_H
#include "shared/dialect.h"
SHARED_BEGIN

SHARED_FN uint hash64To32(uint64_t key) {
  key ^= key >> 33;
  key *= uint64_t(0xff51afd7ed558ccdUL);
  key ^= key >> 33;
  key *= uint64_t(0xc4ceb9fe1a85ec53UL);
  key ^= key >> 33;
  return uint(key) ^ uint(key >> 32);
}

SHARED_END
#endif
