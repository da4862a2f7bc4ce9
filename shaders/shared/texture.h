// Texture lookups from the texel buffer: glTF UV convention ((0,0) is the image's top-left
// corner), wrap modes per axis, bilinear filtering in linear space (colour textures are
// sRGB-decoded per texel before filtering, as a GPU's sRGB format would).
// The includer defines TEXTURE(i) -> TextureGpu and TEXEL(i) -> uint.
#ifndef MIXTRACE_SHARED_TEXTURE_H
#define MIXTRACE_SHARED_TEXTURE_H
#include "shared/dialect.h"
#include "shared/floor_quotient.h"
#include "shared/layouts.h"
#include "shared/sampling.h"
SHARED_BEGIN_WITH_BUFFERS

// The texel coordinate i wrapped into [0, n) by the glTF wrap mode. Repeat and mirror take the
// remainder from floorQuotient (shared/floor_quotient.h), not integer `%`, which lavapipe runs lane
// by lane (and every mode's branch); it is exact for |i| < 2^24. Beyond that (millions of
// repeats) the clamp keeps it a texel.
SHARED_FN int wrapTexelCoord(int i, int n, uint mode) {
  if (mode == kWrapClamp) return clamp(i, 0, n - 1);
  int period = mode == kWrapMirror ? 2 * n : n;
  int m = i - floorQuotient(i, period) * period;
  if (mode == kWrapMirror && m >= n) m = period - 1 - m;
  return clamp(m, 0, n - 1);
}

// An RGBA8 texel as floats in [0, 1], sRGB-decoded (colour channels only) when srgb.
SHARED_FN vec4 decodeTexel(uint texel, bool srgb) {
  vec4 c = vec4(float(texel & 255u), float((texel >> 8u) & 255u), float((texel >> 16u) & 255u),
                float(texel >> 24u)) * (1.0f / 255.0f);
  if (srgb) {
    c.x = srgbToLinear(c.x);
    c.y = srgbToLinear(c.y);
    c.z = srgbToLinear(c.z);
  }
  return c;
}

// The texture's colour at uv: bilinear, or the texel uv lies in where the glTF sampler's magFilter
// is NEAREST (kTextureNearest). Nearest runs the bilinear code with its fractions set to 0 (mix
// with weight 0 gives the first texel exactly), so SIMD lanes that sample textures with different
// filters share one path. There are no mip maps: minFilter is not read (without ray
// differentials a path tracer does not know a lookup's footprint; the pixel's samples average
// what a minified texture shows).
SHARED_FN vec4 sampleTexture(int index, vec2 uv, bool srgb) {
  TextureGpu t = TEXTURE(index);
  bool nearest = (t.sampling & kTextureNearest) != 0u;
  // Texel centres sit at half-integer coordinates; floor() keeps negative UVs continuous.
  float centre = nearest ? 0.0f : 0.5f;
  float x = uv.x * float(t.width) - centre;
  float y = uv.y * float(t.height) - centre;
  float fx0 = floor(x);
  float fy0 = floor(y);
  float fx = nearest ? 0.0f : x - fx0;
  float fy = nearest ? 0.0f : y - fy0;
  int x0 = int(fx0);
  int y0 = int(fy0);
  // The four texels' two columns and two rows, each wrapped once.
  uint modeX = t.sampling & 3u;
  uint modeY = (t.sampling >> 2u) & 3u;
  uint column0 = uint(wrapTexelCoord(x0, int(t.width), modeX));
  uint column1 = uint(wrapTexelCoord(x0 + 1, int(t.width), modeX));
  uint row0 = t.offset + uint(wrapTexelCoord(y0, int(t.height), modeY)) * t.width;
  uint row1 = t.offset + uint(wrapTexelCoord(y0 + 1, int(t.height), modeY)) * t.width;
  vec4 a = mix(decodeTexel(TEXEL(row0 + column0), srgb), decodeTexel(TEXEL(row0 + column1), srgb), fx);
  vec4 b = mix(decodeTexel(TEXEL(row1 + column0), srgb), decodeTexel(TEXEL(row1 + column1), srgb), fx);
  return mix(a, b, fy);
}

SHARED_END_WITH_BUFFERS
#endif
