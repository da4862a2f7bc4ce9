#include "vulkan/denormal_mode.h"

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#endif

namespace mixtrace {
namespace {

#if defined(__x86_64__) || defined(_M_X64)
// MXCSR: flush-to-zero (results) and denormals-are-zero (operands).
constexpr uint64_t kFlushBits = 0x8040u;
uint64_t readMode() { return _mm_getcsr(); }
void writeMode(uint64_t mode) { _mm_setcsr(uint32_t(mode)); }
#elif defined(__aarch64__)
// FPCR.FZ flushes both.
constexpr uint64_t kFlushBits = uint64_t(1) << 24;
uint64_t readMode() {
  uint64_t fpcr;
  __asm__ volatile("mrs %0, fpcr" : "=r"(fpcr));
  return fpcr;
}
void writeMode(uint64_t mode) { __asm__ volatile("msr fpcr, %0" : : "r"(mode)); }
#else
constexpr uint64_t kFlushBits = 0u;
uint64_t readMode() { return 0u; }
void writeMode(uint64_t) {}
#endif

}  // namespace

FlushDenormalsInScope::FlushDenormalsInScope() : saved_(readMode()) { writeMode(saved_ | kFlushBits); }

FlushDenormalsInScope::~FlushDenormalsInScope() { writeMode(saved_); }

bool threadFlushesDenormals() { return kFlushBits != 0u && (readMode() & kFlushBits) == kFlushBits; }

}  // namespace mixtrace
