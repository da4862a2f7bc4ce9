// Texture lookups from the texel buffer: glTF UV convention ((0,0) is the image's top-left
// corner), wrap modes per axis, bilinear filtering in linear space (colour textures are
// sRGB-decoded per texel before filtering, as a GPU's sRGB format would).
// The includer defines TEXTURE(i) -> TextureGpu and TEXEL(i) -> uint.
#ifndef MIXTRACE_SHARED_TEXTURE_H
#define MIXTRACE_SHARED_TEXTURE_H
#include "shared/dialect.h"
#include "shared/layouts.h"
#include "shared/sampling.h"
SHARED_BEGIN_WITH_BUFFERS

// The texel coordinate i wrapped into [0, n) by the glTF wrap mode. Repeat and mirror take the
// remainder from a float quotient rather than integer `%`: SIMD units have no integer division,
// so lavapipe divides lane by lane (and runs every mode's branch), which made the remainders a
// large part of a textured scene's shade pass. For |i| < 2^24 the correctly rounded quotient never
// crosses an integer (its distance to one is at least 1 / period, half an ulp at most), so the
// remainder is exact; GLSL allows a division 2.5 ulp off (a GPU's reciprocal), which can cross one,
// and the two corrections absorb that. Beyond 2^24 (millions of repeats) the clamp keeps it a texel.
SHARED_FN int wrapTexelCoord(int i, int n, uint mode) {
  if (mode == kWrapClamp) return clamp(i, 0, n - 1);
  int period = mode == kWrapMirror ? 2 * n : n;
  int m = i - int(floor(float(i) / float(period))) * period;
  if (m < 0) m += period;
  if (m >= period) m -= period;
  if (mode == kWrapMirror && m >= n) m = period - 1 - m;
  return clamp(m, 0, n - 1);
}

SHARED_FN vec4 fetchTexel(TextureGpu t, int x, int y, bool srgb) {
  uint x0 = uint(wrapTexelCoord(x, int(t.width), t.wrap & 3u));
  uint y0 = uint(wrapTexelCoord(y, int(t.height), (t.wrap >> 2u) & 3u));
  uint texel = TEXEL(t.offset + y0 * t.width + x0);
  vec4 c = vec4(float(texel & 255u), float((texel >> 8u) & 255u), float((texel >> 16u) & 255u),
                float(texel >> 24u)) * (1.0f / 255.0f);
  if (srgb) {
    c.x = srgbToLinear(c.x);
    c.y = srgbToLinear(c.y);
    c.z = srgbToLinear(c.z);
  }
  return c;
}

SHARED_FN vec4 sampleTexture(int index, vec2 uv, bool srgb) {
  TextureGpu t = TEXTURE(index);
  // Texel centres sit at half-integer coordinates; floor() keeps negative UVs continuous.
  float x = uv.x * float(t.width) - 0.5f;
  float y = uv.y * float(t.height) - 0.5f;
  float fx0 = floor(x);
  float fy0 = floor(y);
  float fx = x - fx0;
  float fy = y - fy0;
  int x0 = int(fx0);
  int y0 = int(fy0);
  vec4 a = mix(fetchTexel(t, x0, y0, srgb), fetchTexel(t, x0 + 1, y0, srgb), fx);
  vec4 b = mix(fetchTexel(t, x0, y0 + 1, srgb), fetchTexel(t, x0 + 1, y0 + 1, srgb), fx);
  return mix(a, b, fy);
}

SHARED_END_WITH_BUFFERS
#endif
