// One glTF mesh primitive instance -> world-space triangles.
#include <algorithm>
#include <cmath>
#include <utility>

#include "gltf/gltf_internal.h"

namespace mixtrace {
namespace gltf {
namespace {

bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

int attributeAccessor(const tinygltf::Primitive& primitive, const char* name) {
  const auto it = primitive.attributes.find(name);
  return it == primitive.attributes.end() ? -1 : it->second;
}

// The primitive's vertices, already in world space.
struct WorldVertices {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;  // empty: the file has none; NaN marks an unusable normal
  std::vector<glm::vec2> uvs;      // the material's first mapping; empty: the file has none
  std::vector<glm::vec2> uvs2;     // its second mapping (MaterialUvs); empty: none
  std::vector<glm::vec4> colors;   // COLOR_0, linear RGBA; empty: the file has none
  std::vector<glm::vec4> tangents; // TANGENT (xyz unit, w = +-1); empty: the file has none
};

// Whether the file declares KHR_mesh_quantization, which allows integer vertex attributes.
bool quantized(const LoadContext& ctx) {
  const auto& used = ctx.model.extensionsUsed;
  return std::find(used.begin(), used.end(), "KHR_mesh_quantization") != used.end();
}

// The component types an attribute may have: FLOAT always; with KHR_mesh_quantization the
// extension's integer types (its table: POSITION any of (UNSIGNED_)BYTE/SHORT, normalized or not;
// NORMAL normalized BYTE or SHORT; TEXCOORD any of them, normalized or not).
bool positionFormat(const AccessorReader& a, bool quantization) {
  const int t = a.componentType();
  if (t == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
  return quantization && (t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                          t == TINYGLTF_COMPONENT_TYPE_SHORT || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
}
bool normalFormat(const AccessorReader& a, bool quantization) {
  const int t = a.componentType();
  if (t == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
  return quantization && a.normalized() && (t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_SHORT);
}
bool texcoordFormat(const AccessorReader& a, bool quantization) {
  const int t = a.componentType();
  if (t == TINYGLTF_COMPONENT_TYPE_FLOAT) return true;
  const bool unsignedNormalized =
      a.normalized() && (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  return unsignedNormalized || (quantization && positionFormat(a, true));
}

// The texture coordinates `mapping` names (its TEXCOORD set through its transform), one per
// vertex; empty where the primitive has none or they are unusable (with a warning).
std::vector<glm::vec2> readUvs(const LoadContext& ctx, const tinygltf::Primitive& primitive, const std::string& where,
                               const UvMapping& uvMapping, bool quantization, size_t count) {
  std::vector<glm::vec2> out;
  const std::string uvName = "TEXCOORD_" + std::to_string(uvMapping.set);
  const int uvAccessor = attributeAccessor(primitive, uvName.c_str());
  if (uvAccessor < 0 && uvMapping.set != 0 && attributeAccessor(primitive, "TEXCOORD_0") >= 0)
    ctx.warning(where + " has no " + uvName + ", which its material's textures read; they get (0, 0)");
  if (uvAccessor < 0) return out;
  const AccessorReader uvs(ctx, uvAccessor, uvName + " of " + where);
  const bool validFormat = uvs.type() == TINYGLTF_TYPE_VEC2 && texcoordFormat(uvs, quantization);
  if (!validFormat) {
    ctx.warning(uvName + " of " + where + " is neither FLOAT nor normalized UNSIGNED_BYTE/SHORT VEC2" +
                (quantization ? " nor a KHR_mesh_quantization integer VEC2" : "") + "; texture coordinates ignored");
    return out;
  }
  if (uvs.count() != count) ctx.fail(uvName + " of " + where + " has a different count than POSITION");
  out.resize(count);
  for (size_t i = 0; i < count; ++i) {
    const glm::vec2 uv = uvMapping.apply(uvs.vec2(i));
    out[i] = (std::isfinite(uv.x) && std::isfinite(uv.y)) ? uv : glm::vec2(0.0f);
  }
  return out;
}

WorldVertices transformVertices(const LoadContext& ctx, const tinygltf::Primitive& primitive, const std::string& where,
                                const glm::dmat4& world, const MaterialUvs& materialUvs, bool needsTangents) {
  WorldVertices v;
  const int positionAccessor = attributeAccessor(primitive, "POSITION");
  if (positionAccessor < 0) ctx.fail(where + " has no POSITION attribute");
  const bool quantization = quantized(ctx);
  const AccessorReader positions(ctx, positionAccessor, "POSITION of " + where);
  if (positions.type() != TINYGLTF_TYPE_VEC3 || !positionFormat(positions, quantization)) {
    ctx.fail("POSITION of " + where + " must be a FLOAT VEC3 accessor" +
             (quantization ? " or an integer one (KHR_mesh_quantization)" : " (integers need KHR_mesh_quantization)"));
  }
  const size_t count = positions.count();
  v.positions.resize(count);
  for (size_t i = 0; i < count; ++i) {
    // Transform in double so large translations do not cost precision before the final rounding.
    const glm::dvec4 p = world * glm::dvec4(glm::dvec3(positions.vec3(i)), 1.0);
    if (!fitsInFloat(p.x) || !fitsInFloat(p.y) || !fitsInFloat(p.z)) {
      // Refused rather than dropped as degenerate: a file whose geometry float cannot hold is not
      // the scene it describes. (Non-finite values compare false and stay with the degenerate.)
      const double worst = std::max({std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
      checkedFloat(ctx, worst, "POSITION element " + std::to_string(i) + " of " + where + " after its node's transform");
    }
    v.positions[i] = glm::vec3(p.x, p.y, p.z);
  }

  const int normalAccessor = attributeAccessor(primitive, "NORMAL");
  if (normalAccessor >= 0) {
    const AccessorReader normals(ctx, normalAccessor, "NORMAL of " + where);
    if (normals.type() != TINYGLTF_TYPE_VEC3 || !normalFormat(normals, quantization)) {
      ctx.fail("NORMAL of " + where + " must be a FLOAT VEC3 accessor" +
               (quantization ? " or a normalized BYTE/SHORT one (KHR_mesh_quantization)"
                             : " (normalized integers need KHR_mesh_quantization)"));
    }
    if (normals.count() != count) ctx.fail("NORMAL of " + where + " has a different count than POSITION");
    // Normals are covectors: they transform by the inverse transpose to stay perpendicular to
    // surfaces under non-uniform scale.
    const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(world)));
    const float nan = std::nanf("");
    v.normals.resize(count);
    for (size_t i = 0; i < count; ++i) {
      const glm::dvec3 n = normalMatrix * glm::dvec3(normals.vec3(i));
      const double length = glm::length(n);
      v.normals[i] = (length > 0.0 && std::isfinite(length)) ? glm::vec3(n / length) : glm::vec3(nan);
    }
  }

  const int tangentAccessor = needsTangents ? attributeAccessor(primitive, "TANGENT") : -1;
  if (tangentAccessor >= 0) {
    const AccessorReader tangents(ctx, tangentAccessor, "TANGENT of " + where);
    const int t = tangents.componentType();
    const bool validFormat = tangents.type() == TINYGLTF_TYPE_VEC4 &&
                             (t == TINYGLTF_COMPONENT_TYPE_FLOAT ||
                              (quantization && tangents.normalized() &&
                               (t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_SHORT)));
    if (!validFormat) {
      ctx.warning("TANGENT of " + where + " is neither a FLOAT VEC4 nor a quantized one; tangents generated from the UVs");
    } else {
      if (tangents.count() != count) ctx.fail("TANGENT of " + where + " has a different count than POSITION");
      // Tangents are vectors of the surface: they transform by the model matrix. A mirroring
      // transform turns the frame's handedness, so w flips with it.
      const glm::dmat3 linear(world);
      const double flip = glm::determinant(linear) < 0.0 ? -1.0 : 1.0;
      v.tangents.resize(count);
      for (size_t i = 0; i < count; ++i) {
        const glm::dvec3 d = linear * glm::dvec3(tangents.component(i, 0), tangents.component(i, 1), tangents.component(i, 2));
        const double length = glm::length(d);
        const double w = tangents.component(i, 3) < 0.0f ? -flip : flip;
        v.tangents[i] = (length > 0.0 && std::isfinite(length)) ? glm::vec4(glm::vec3(d / length), float(w)) : glm::vec4(0.0f);
      }
    }
  }

  const int colorAccessor = attributeAccessor(primitive, "COLOR_0");
  if (colorAccessor >= 0) {
    const AccessorReader colors(ctx, colorAccessor, "COLOR_0 of " + where);
    const int t = colors.componentType();
    // The specification's formats: VEC3 or VEC4 of FLOAT, or of normalized UNSIGNED_BYTE/SHORT.
    const bool validFormat =
        (colors.type() == TINYGLTF_TYPE_VEC3 || colors.type() == TINYGLTF_TYPE_VEC4) &&
        (t == TINYGLTF_COMPONENT_TYPE_FLOAT ||
         (colors.normalized() && (t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
    if (!validFormat) {
      ctx.warning("COLOR_0 of " + where + " is neither FLOAT nor normalized UNSIGNED_BYTE/SHORT VEC3/VEC4; ignored");
    } else {
      if (colors.count() != count) ctx.fail("COLOR_0 of " + where + " has a different count than POSITION");
      const int channels = colors.type() == TINYGLTF_TYPE_VEC4 ? 4 : 3;
      v.colors.resize(count);
      for (size_t i = 0; i < count; ++i) {
        glm::vec4 c(1.0f);
        for (int k = 0; k < channels; ++k) {
          const float x = colors.component(i, k);
          c[k] = std::isfinite(x) ? std::min(std::max(x, 0.0f), 1.0f) : 1.0f;  // the spec's range is [0, 1]
        }
        v.colors[i] = c;
      }
    }
  }
  v.uvs = readUvs(ctx, primitive, where, materialUvs.first, quantization, count);
  if (materialUvs.second) v.uvs2 = readUvs(ctx, primitive, where, *materialUvs.second, quantization, count);
  return v;
}

// Vertex indices of the primitive: its index accessor, or 0..n-1 when it has none.
std::vector<uint32_t> readIndices(const LoadContext& ctx, const tinygltf::Primitive& primitive,
                                  const std::string& where, size_t vertexCount) {
  std::vector<uint32_t> indices;
  if (primitive.indices < 0) {
    if (vertexCount > 0xffffffffull) ctx.fail(where + " has more than 2^32 vertices");
    indices.resize(vertexCount);
    for (size_t i = 0; i < vertexCount; ++i) indices[i] = uint32_t(i);
    return indices;
  }
  const AccessorReader reader(ctx, primitive.indices, "indices of " + where);
  const int type = reader.componentType();
  if (reader.type() != TINYGLTF_TYPE_SCALAR ||
      (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
       type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)) {
    ctx.fail("indices of " + where + " must be an UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT SCALAR accessor");
  }
  indices.resize(reader.count());
  for (size_t i = 0; i < indices.size(); ++i) {
    indices[i] = reader.unsignedValue(i);
    if (indices[i] >= vertexCount) {
      ctx.fail("index " + std::to_string(indices[i]) + " (element " + std::to_string(i) + " of " + where +
               ") is out of range of its " + std::to_string(vertexCount) + " vertices");
    }
  }
  return indices;
}

// The triangles of a TRIANGLES, TRIANGLE_STRIP or TRIANGLE_FAN primitive as a list, three corners
// each, in the winding the glTF 2.0 specification gives them (3.7.2.1): strip triangle i is
// {v_i, v_(i+1+i%2), v_(i+2-i%2)}, fan triangle i is {v_(i+1), v_(i+2), v_0}, so every triangle
// of a strip or fan keeps the front face of its first.
std::vector<uint32_t> triangleList(int mode, std::vector<uint32_t> indices) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return indices;
  std::vector<uint32_t> list;
  const size_t n = indices.size();
  if (n < 3) return list;
  list.reserve(3 * (n - 2));
  for (size_t i = 0; i + 2 < n; ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      list.insert(list.end(), {indices[i], indices[i + 1 + i % 2], indices[i + 2 - i % 2]});
    } else {   // TINYGLTF_MODE_TRIANGLE_FAN
      list.insert(list.end(), {indices[i + 1], indices[i + 2], indices[0]});
    }
  }
  return list;
}

// Per-vertex tangents where the file has none (glTF prescribes MikkTSpace, which no Debian package
// ships): each triangle's dp/du and dp/dv from its UVs, summed at its corners (so larger
// triangles weigh more), then at each vertex the sum of dp/du made perpendicular to the vertex
// normal, with w the sign that makes w cross(n, t) point along -dp/dv (glTF's +Y of a normal map
// is up in the image, towards smaller v). MikkTSpace differs in weighting the corners by angle
// and in splitting vertices where the frames disagree; on a smooth, consistently mapped surface
// the two agree, at UV seams and mirrored UV islands they can differ.
std::vector<glm::vec4> tangentsFromUvs(const WorldVertices& v, const std::vector<glm::vec2>& uvs,
                                       const std::vector<uint32_t>& indices) {
  std::vector<glm::dvec3> du(v.positions.size(), glm::dvec3(0.0)), dv(v.positions.size(), glm::dvec3(0.0)),
      faces(v.positions.size(), glm::dvec3(0.0));   // summed face normals: the normal where the file has none
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
    const glm::dvec3 e1 = glm::dvec3(v.positions[b]) - glm::dvec3(v.positions[a]);
    const glm::dvec3 e2 = glm::dvec3(v.positions[c]) - glm::dvec3(v.positions[a]);
    const glm::dvec2 w1 = glm::dvec2(uvs[b]) - glm::dvec2(uvs[a]), w2 = glm::dvec2(uvs[c]) - glm::dvec2(uvs[a]);
    for (uint32_t i : {a, b, c}) faces[i] += glm::cross(e1, e2);
    const double r = w1.x * w2.y - w2.x * w1.y;
    if (!(std::abs(r) > 1e-20) || !std::isfinite(r)) continue;   // degenerate UVs: no direction
    const glm::dvec3 pu = (e1 * w2.y - e2 * w1.y) / r, pv = (e2 * w1.x - e1 * w2.x) / r;
    if (!std::isfinite(pu.x + pu.y + pu.z + pv.x + pv.y + pv.z)) continue;
    for (uint32_t i : {a, b, c}) {
      du[i] += pu;
      dv[i] += pv;
    }
  }
  std::vector<glm::vec4> out(v.positions.size(), glm::vec4(0.0f));
  for (size_t i = 0; i < out.size(); ++i) {
    const double faceLength = glm::length(faces[i]);
    const glm::dvec3 n = !v.normals.empty() && isFinite(v.normals[i]) ? glm::dvec3(v.normals[i])
                         : faceLength > 0.0                           ? faces[i] / faceLength
                                                                      : glm::dvec3(0.0);
    const glm::dvec3 t = du[i] - n * glm::dot(n, du[i]);
    const double length = glm::length(t);
    if (!(length > 0.0) || !std::isfinite(length)) continue;
    const double w = glm::dot(glm::cross(n, t), -dv[i]) < 0.0 ? -1.0 : 1.0;
    out[i] = glm::vec4(glm::vec3(t / length), float(w));
  }
  return out;
}

}  // namespace

glm::vec2 UvMapping::apply(glm::vec2 uv) const {
  if (identity()) return uv;
  const glm::dvec2 s = scale * glm::dvec2(uv);
  const double c = std::cos(rotation), n = std::sin(rotation);
  return glm::vec2(offset + glm::dvec2(c * s.x + n * s.y, -n * s.x + c * s.y));
}

bool isSurfaceMode(int mode) {
  return mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN;
}

size_t appendPrimitive(const LoadContext& ctx, int meshIndex, int primitiveIndex, const glm::dmat4& world,
                       uint32_t material, const MaterialUvs& uvs, bool needsTangents, uint32_t primitiveId,
                       std::vector<Triangle>& out, GeometryStats& stats) {
  const tinygltf::Primitive& primitive = ctx.model.meshes[size_t(meshIndex)].primitives[size_t(primitiveIndex)];
  const std::string where = "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitiveIndex);
  WorldVertices v = transformVertices(ctx, primitive, where, world, uvs, needsTangents);
  if (!isSurfaceMode(primitive.mode)) ctx.fail(where + " is not made of triangles");   // the caller skips those
  const std::vector<uint32_t> indices = triangleList(primitive.mode, readIndices(ctx, primitive, where, v.positions.size()));
  // Generated tangents follow the coordinates the normal map reads.
  const std::vector<glm::vec2>& normalUvs = (uvs.secondSlots & shared::kMaterialSecondUvNormal) ? v.uvs2 : v.uvs;
  if (needsTangents && v.tangents.empty() && !normalUvs.empty()) v.tangents = tangentsFromUvs(v, normalUvs, indices);
  stats.leftoverIndices += indices.size() % 3;

  // A mirroring transform turns counter-clockwise into clockwise; swapping two vertices keeps the
  // glTF front face (CCW) and hence the geometric normal on the side the file meant.
  const bool mirrored = glm::determinant(glm::dmat3(world)) < 0.0;
  const size_t before = out.size();
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    uint32_t corner[3] = {indices[t], indices[t + 1], indices[t + 2]};
    if (mirrored) std::swap(corner[1], corner[2]);
    Triangle tri;
    for (int k = 0; k < 3; ++k) tri.p[k] = v.positions[corner[k]];
    if (!isFinite(tri.p[0]) || !isFinite(tri.p[1]) || !isFinite(tri.p[2])) {
      ++stats.degenerate;
      continue;
    }
    const glm::dvec3 p0(tri.p[0]);
    const glm::dvec3 cross = glm::cross(glm::dvec3(tri.p[1]) - p0, glm::dvec3(tri.p[2]) - p0);
    const double twiceArea = glm::length(cross);
    if (!(twiceArea > 0.0) || !std::isfinite(twiceArea)) {
      ++stats.degenerate;
      continue;
    }
    const glm::vec3 geometric(cross / twiceArea);
    for (int k = 0; k < 3; ++k) {
      if (v.normals.empty()) {
        tri.n[k] = geometric;  // spec: flat normals when the file has none
      } else if (isFinite(v.normals[corner[k]])) {
        tri.n[k] = v.normals[corner[k]];
      } else {
        tri.n[k] = geometric;
        ++stats.invalidNormals;
      }
      tri.uv[k] = v.uvs.empty() ? glm::vec2(0.0f) : v.uvs[corner[k]];
      if (!v.uvs2.empty()) tri.uv2[k] = v.uvs2[corner[k]];
      if (!v.colors.empty()) tri.color[k] = v.colors[corner[k]];
      if (!v.tangents.empty()) tri.tangent[k] = v.tangents[corner[k]];
    }
    tri.material = material;
    tri.primitive = primitiveId;
    out.push_back(tri);
  }
  return out.size() - before;
}

}  // namespace gltf
}  // namespace mixtrace
