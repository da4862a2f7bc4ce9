#pragma once
// Denormal floats flushed to zero in the threads a CPU Vulkan driver starts.
//
// Lavapipe (Mesa 22.3) runs compute shaders on a pool of worker threads that it starts while the
// instance and device are created, and it never sets their floating-point mode (its rasterizer
// threads flush denormals, its compute threads keep the creating thread's mode). A new thread
// inherits its creator's mode, so whatever the host thread has then is what every dispatch runs
// with. With x86's default, an operation on a denormal operand or result costs a microcode assist
// of some hundred cycles, and the SIMD code computes every branch for every lane (lanes that do not
// take a branch compute it with whatever their registers hold): on the punctual scene about
// 15 % of the shade pass was such assists. GPUs flush fp32 denormals too (Vulkan leaves it to the
// implementation where a shader does not ask otherwise), so this is also the behaviour the shaders
// get on a GPU.
//
// While a FlushDenormalsInScope lives, the calling thread flushes denormal results to zero and reads
// denormal operands as zero; the destructor restores the mode it found. The host's own arithmetic
// (the CPU backend included) keeps IEEE denormals outside the scope. Nothing on architectures other
// than x86-64 and AArch64.
#include <cstdint>

namespace mixtrace {

class FlushDenormalsInScope {
 public:
  FlushDenormalsInScope();
  ~FlushDenormalsInScope();
  FlushDenormalsInScope(const FlushDenormalsInScope&) = delete;
  FlushDenormalsInScope& operator=(const FlushDenormalsInScope&) = delete;

 private:
  uint64_t saved_ = 0;
};

// Whether the calling thread flushes denormals now (for the tests).
bool threadFlushesDenormals();

}  // namespace mixtrace
