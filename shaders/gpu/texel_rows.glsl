// The accessors of the rows read as texels (access TEXELS, shared/buffer_table.h), included by
// gpu/buffers.glsl after the declarations: each struct assembled from its RGBA32UI texels, word k
// of the struct in component k % 4 of texel k / 4 (tests/gpu/texel_rows_test.cpp checks every
// accessor bit for bit). The accessors are macros, so a pass names only the rows it lists (the
// image of a row it does not list is undeclared); the assembling functions name no row.
#define ROW_TEXEL(row, texelsPerElement, i, k) imageLoad(row, int((texelsPerElement) * (i) + (k)))
// Word i of a word view (shared/buffer_table.h kWordsPerTexel), as a uint and as a float.
#define ROW_UINT(row, i) imageLoad(row, int((i) / kWordsPerTexel))[(i) % kWordsPerTexel]
#define ROW_WORD(row, i) uintBitsToFloat(ROW_UINT(row, i))

BvhNode bvhNodeFromTexels(uvec4 t0, uvec4 t1, uvec4 t2, uvec4 t3) {
  BvhNode node;
  node.leftMin = uintBitsToFloat(t0.xyz);
  node.leftRef = t0.w;
  node.leftMax = uintBitsToFloat(t1.xyz);
  node.rightRef = t1.w;
  node.rightMin = uintBitsToFloat(t2.xyz);
  node.pad0 = t2.w;
  node.rightMax = uintBitsToFloat(t3.xyz);
  node.pad1 = t3.w;
  return node;
}
#define BVH_NODE(i) \
  bvhNodeFromTexels( \
      ROW_TEXEL(bvhNodes, kTexelsPerBvhNode, i, 0u), \
      ROW_TEXEL(bvhNodes, kTexelsPerBvhNode, i, 1u), \
      ROW_TEXEL(bvhNodes, kTexelsPerBvhNode, i, 2u), \
      ROW_TEXEL(bvhNodes, kTexelsPerBvhNode, i, 3u))

TriangleGeom triangleGeomFromTexels(uvec4 t0, uvec4 t1, uvec4 t2) {
  TriangleGeom g;
  g.v0 = uintBitsToFloat(t0.xyz);
  g.toUnit = uintBitsToFloat(t0.w);
  g.e1 = uintBitsToFloat(t1.xyz);
  g.fromUnit = uintBitsToFloat(t1.w);
  g.e2 = uintBitsToFloat(t2.xyz);
  g.pad = t2.w;
  return g;
}
#define TRIANGLE(i) \
  triangleGeomFromTexels( \
      ROW_TEXEL(triangles, kTexelsPerTriangleGeom, i, 0u), \
      ROW_TEXEL(triangles, kTexelsPerTriangleGeom, i, 1u), \
      ROW_TEXEL(triangles, kTexelsPerTriangleGeom, i, 2u))

TriangleShading triangleShadingFromTexels(uvec4 t0, uvec4 t1, uvec4 t2, uvec4 t3, uvec4 t4, uvec4 t5, uvec4 t6) {
  TriangleShading s;
  s.n0 = uintBitsToFloat(t0.xyz);
  s.n1 = uintBitsToFloat(uvec3(t0.w, t1.xy));
  s.n2 = uintBitsToFloat(uvec3(t1.zw, t2.x));
  s.uv0 = uintBitsToFloat(t2.yz);
  s.uv1 = uintBitsToFloat(uvec2(t2.w, t3.x));
  s.uv2 = uintBitsToFloat(t3.yz);
  s.material = t3.w;
  s.emitter = int(t4.x);
  s.color0 = t4.yz;
  s.color1 = uvec2(t4.w, t5.x);
  s.color2 = t5.yz;
  s.tangent0 = t5.w;
  s.tangent1 = t6.x;
  s.tangent2 = t6.y;
  s.pad0 = t6.z;
  s.pad1 = t6.w;
  return s;
}
#define TRIANGLE_SHADING(i) \
  triangleShadingFromTexels( \
      ROW_TEXEL(triangleShading, kTexelsPerTriangleShading, i, 0u), \
      ROW_TEXEL(triangleShading, kTexelsPerTriangleShading, i, 1u), \
      ROW_TEXEL(triangleShading, kTexelsPerTriangleShading, i, 2u), \
      ROW_TEXEL(triangleShading, kTexelsPerTriangleShading, i, 3u), \
      ROW_TEXEL(triangleShading, kTexelsPerTriangleShading, i, 4u), \
      ROW_TEXEL(triangleShading, kTexelsPerTriangleShading, i, 5u), \
      ROW_TEXEL(triangleShading, kTexelsPerTriangleShading, i, 6u))

MaterialGpu materialFromTexels(uvec4 t0, uvec4 t1, uvec4 t2, uvec4 t3, uvec4 t4) {
  MaterialGpu m;
  m.baseColor = uintBitsToFloat(t0.xyz);
  m.metallic = uintBitsToFloat(t0.w);
  m.emission = uintBitsToFloat(t1.xyz);
  m.roughness = uintBitsToFloat(t1.w);
  m.baseColorTexture = int(t2.x);
  m.metallicRoughnessTexture = int(t2.y);
  m.emissiveTexture = int(t2.z);
  m.flags = t2.w;
  m.alpha = uintBitsToFloat(t3.x);
  m.alphaCutoff = uintBitsToFloat(t3.y);
  m.normalTexture = int(t3.z);
  m.normalScale = uintBitsToFloat(t3.w);
  m.transmission = uintBitsToFloat(t4.x);
  m.transmissionTexture = int(t4.y);
  m.ior = uintBitsToFloat(t4.z);
  m.padMaterial = t4.w;
  return m;
}
#define MATERIAL(i) \
  materialFromTexels( \
      ROW_TEXEL(materials, kTexelsPerMaterial, i, 0u), \
      ROW_TEXEL(materials, kTexelsPerMaterial, i, 1u), \
      ROW_TEXEL(materials, kTexelsPerMaterial, i, 2u), \
      ROW_TEXEL(materials, kTexelsPerMaterial, i, 3u), \
      ROW_TEXEL(materials, kTexelsPerMaterial, i, 4u))

LightGpu lightFromTexels(uvec4 t0, uvec4 t1, uvec4 t2, uvec4 t3) {
  LightGpu l;
  l.kind = t0.x;
  l.firstEmitter = t0.y;
  l.emitterCount = t0.z;
  l.spotScale = uintBitsToFloat(t0.w);
  l.position = uintBitsToFloat(t1.xyz);
  l.spotOffset = uintBitsToFloat(t1.w);
  l.direction = uintBitsToFloat(t2.xyz);
  l.intensity = uintBitsToFloat(uvec3(t2.w, t3.xy));
  l.pad0 = t3.z;
  l.pad1 = t3.w;
  return l;
}
#define LIGHT(i) \
  lightFromTexels( \
      ROW_TEXEL(lights, kTexelsPerLight, i, 0u), \
      ROW_TEXEL(lights, kTexelsPerLight, i, 1u), \
      ROW_TEXEL(lights, kTexelsPerLight, i, 2u), \
      ROW_TEXEL(lights, kTexelsPerLight, i, 3u))

EmitterGpu emitterFromTexel(uvec4 t) {
  EmitterGpu e;
  e.triangle = t.x;
  e.light = t.y;
  e.pmf = uintBitsToFloat(t.z);
  e.cdf = uintBitsToFloat(t.w);
  return e;
}
#define EMITTER(i) emitterFromTexel(ROW_TEXEL(emitters, kTexelsPerEmitter, i, 0u))

LightBvhNodeGpu lightBvhNodeFromTexels(uvec4 t0, uvec4 t1, uvec4 t2, uvec4 t3) {
  LightBvhNodeGpu n;
  n.boundsMin = uintBitsToFloat(t0.xyz);
  n.power = uintBitsToFloat(t0.w);
  n.boundsMax = uintBitsToFloat(t1.xyz);
  n.cosThetaO = uintBitsToFloat(t1.w);
  n.axis = uintBitsToFloat(t2.xyz);
  n.cosThetaE = uintBitsToFloat(t2.w);
  n.kind = t3.x;
  n.first = t3.y;
  n.second = t3.z;
  n.third = t3.w;
  return n;
}
// (LIGHT_BVH(i) is defined by the passes that walk the light BVH, as this.)
#define LIGHT_BVH_FROM_TEXELS(i) \
  lightBvhNodeFromTexels( \
      ROW_TEXEL(lightBvh, kTexelsPerLightBvhNode, i, 0u), \
      ROW_TEXEL(lightBvh, kTexelsPerLightBvhNode, i, 1u), \
      ROW_TEXEL(lightBvh, kTexelsPerLightBvhNode, i, 2u), \
      ROW_TEXEL(lightBvh, kTexelsPerLightBvhNode, i, 3u))

ClusterGpu clusterFromTexel(uvec4 t) {
  ClusterGpu c;
  c.firstLight = t.x;
  c.lightCount = t.y;
  c.kind = t.z;
  c.power = uintBitsToFloat(t.w);
  return c;
}
