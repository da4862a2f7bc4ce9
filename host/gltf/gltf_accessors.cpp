// Bounds-checked accessor reading. tinygltf parses accessors and bufferViews but never checks that
// they fit their buffers, so every range is validated here before a single byte is read.
#include <algorithm>
#include <cstring>
#include <limits>

#include "gltf/gltf_internal.h"
#include "gltf/gltf_limits.h"

namespace mixtrace {
namespace gltf {

int componentSizeOf(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // INT and DOUBLE are not valid glTF 2.0 accessor types
  }
}

int componentCountOf(int accessorType) {
  switch (accessorType) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

const unsigned char* bufferViewBytes(const LoadContext& ctx, int viewIndex, size_t& byteLength,
                                     const std::string& role) {
  const tinygltf::Model& model = ctx.model;
  if (viewIndex < 0 || size_t(viewIndex) >= model.bufferViews.size()) {
    ctx.fail(role + " refers to bufferView " + std::to_string(viewIndex) + ", which does not exist");
  }
  const tinygltf::BufferView& view = model.bufferViews[size_t(viewIndex)];
  if (view.buffer < 0 || size_t(view.buffer) >= model.buffers.size()) {
    ctx.fail("bufferView " + std::to_string(viewIndex) + " refers to buffer " + std::to_string(view.buffer) +
             ", which does not exist");
  }
  const tinygltf::Buffer& buffer = model.buffers[size_t(view.buffer)];
  const size_t size = buffer.data.size();
  if (view.byteOffset > size || view.byteLength > size - view.byteOffset) {
    ctx.fail("bufferView " + std::to_string(viewIndex) + " (bytes " + std::to_string(view.byteOffset) + ".." +
             std::to_string(view.byteOffset + view.byteLength) + ") lies outside buffer " +
             std::to_string(view.buffer) +
             ", which has " + std::to_string(size) + " bytes");
  }
  byteLength = view.byteLength;
  return buffer.data.data() + view.byteOffset;
}

AccessorReader::AccessorReader(const LoadContext& ctx, int accessorIndex, const std::string& role) {
  const tinygltf::Model& model = ctx.model;
  const std::string name = role + " (accessor " + std::to_string(accessorIndex) + ")";
  if (accessorIndex < 0 || size_t(accessorIndex) >= model.accessors.size()) {
    ctx.fail(role + " refers to accessor " + std::to_string(accessorIndex) + ", which does not exist");
  }
  const tinygltf::Accessor& accessor = model.accessors[size_t(accessorIndex)];
  if (accessor.sparse.isSparse) ctx.fail(name + " uses sparse storage, which is not supported");
  index_ = accessorIndex;
  componentType_ = accessor.componentType;
  componentSize_ = componentSizeOf(componentType_);
  type_ = accessor.type;
  normalized_ = accessor.normalized;
  count_ = accessor.count;
  const int components = componentCountOf(type_);
  if (componentSize_ == 0 || components == 0) {
    ctx.fail(name + " has an invalid component type " + std::to_string(componentType_));
  }
  const size_t elementSize = size_t(componentSize_) * size_t(components);
  if (accessor.bufferView < 0) {  // spec: no bufferView means every element is zero
    if (count_ > kMaxDatalessAccessorElements) {
      ctx.fail(name + " has no bufferView but claims " + std::to_string(count_) + " elements (at most " +
               std::to_string(kMaxDatalessAccessorElements) + " zeros are accepted without data)");
    }
    return;
  }

  size_t viewLength = 0;
  const unsigned char* view = bufferViewBytes(ctx, accessor.bufferView, viewLength, name);
  const int declaredStride = model.bufferViews[size_t(accessor.bufferView)].byteStride;
  if (declaredStride < 0 || (declaredStride != 0 && size_t(declaredStride) < elementSize)) {
    ctx.fail(name + " has byteStride " + std::to_string(declaredStride) + ", smaller than its " +
             std::to_string(elementSize) + "-byte elements");
  }
  stride_ = declaredStride != 0 ? size_t(declaredStride) : elementSize;
  if (count_ == 0) return;
  // Last byte read: byteOffset + stride * (count - 1) + elementSize, computed without overflow.
  bool fits = accessor.byteOffset <= viewLength;
  if (fits) {
    const size_t room = viewLength - accessor.byteOffset;
    fits = room >= elementSize && (count_ - 1) <= (room - elementSize) / stride_;
  }
  if (!fits) {
    ctx.fail(name + " needs " + std::to_string(count_) + " elements of stride " + std::to_string(stride_) +
             " from byte " + std::to_string(accessor.byteOffset) + ", past the end of bufferView " +
             std::to_string(accessor.bufferView) + " (" + std::to_string(viewLength) + " bytes)");
  }
  data_ = view + accessor.byteOffset;
}

float AccessorReader::component(size_t i, int c) const {
  if (!data_) return 0.0f;
  const unsigned char* p = element(i) + size_t(c) * size_t(componentSize_);
  switch (componentType_) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float v;
      std::memcpy(&v, p, 4);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized_ ? float(p[0]) / 255.0f : float(p[0]);
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const float v = float(static_cast<int8_t>(p[0]));
      return normalized_ ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return normalized_ ? float(v) / 65535.0f : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return normalized_ ? std::max(float(v) / 32767.0f, -1.0f) : float(v);
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return normalized_ ? float(double(v) / 4294967295.0) : float(v);
    }
    default: return 0.0f;
  }
}

uint32_t AccessorReader::unsignedValue(size_t i) const {
  if (!data_) return 0;
  const unsigned char* p = element(i);
  switch (componentType_) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return p[0];
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
    default: return 0;
  }
}

}  // namespace gltf
}  // namespace mixtrace
