// The common dialect of the headers in shaders/shared: each is included by GLSL shaders and by
// C++ (with GLM), so a struct that crosses the host/GPU boundary and the math both sides need
// (BSDF, sampling, light pdfs) are written once.
//
// Rules for shared code:
//   - wrap the contents in SHARED_BEGIN / SHARED_END; mark functions SHARED_FN;
//   - use INOUT(T) / OUT(T) for reference parameters;
//   - float literals carry the f suffix (C++ would otherwise compute in double);
//   - atan2(y, x) for the two-argument arctangent (GLSL's atan(y, x));
//   - only .x .y .z .w component access (no swizzles), no struct constructors (assign fields),
//     no GLSL-only built-ins (atomics, barriers, textures);
//   - buffers are reached through macros the includer defines (see lights.h).
#ifndef MIXTRACE_SHARED_DIALECT_H
#define MIXTRACE_SHARED_DIALECT_H

#ifdef __cplusplus
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
// Scalar maths resolves to the float overloads of <cmath>; vector arguments find GLM's by ADL.
#define SHARED_BEGIN namespace mixtrace { namespace shared { using namespace glm; typedef unsigned int uint; \
  using std::sqrt; using std::abs; using std::pow; using std::exp; using std::log; using std::sin; \
  using std::cos; using std::tan; using std::acos; using std::asin; using std::floor; using std::ceil; using std::atan2;
#define SHARED_END } }
// For headers that read buffers through includer-defined macros (BVH_NODE, LIGHT, ...): internal
// linkage in C++, so two translation units binding the macros differently never collide (ODR).
#define SHARED_BEGIN_WITH_BUFFERS SHARED_BEGIN namespace {
#define SHARED_END_WITH_BUFFERS } SHARED_END
#define SHARED_FN inline
#define INOUT(T) T&
#define OUT(T) T&
#else
#define SHARED_BEGIN
#define SHARED_END
#define SHARED_BEGIN_WITH_BUFFERS
#define SHARED_END_WITH_BUFFERS
#define SHARED_FN
#define INOUT(T) inout T
#define OUT(T) out T
// C's two-argument arctangent; GLSL spells it atan(y, x).
#define atan2(y, x) atan(y, x)
#endif

#endif
