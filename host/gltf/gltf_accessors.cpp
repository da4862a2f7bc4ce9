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
    if (accessor.sparse.isSparse) applySparse(ctx, accessor, name, elementSize);
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
  if (accessor.sparse.isSparse) applySparse(ctx, accessor, name, elementSize);
}

// Sparse storage (glTF 2.0 3.6.2.3): the base elements (read above, or zeros), then `count`
// substitutions, strictly increasing indices below the accessor's count, their values tightly
// packed in the accessor's own component type. Applied to a dense copy, which the reader then reads.
void AccessorReader::applySparse(const LoadContext& ctx, const tinygltf::Accessor& accessor, const std::string& name,
                                 size_t elementSize) {
  const auto& sparse = accessor.sparse;
  if (sparse.count < 1) ctx.fail(name + " has sparse storage with count " + std::to_string(sparse.count) + " (at least 1)");
  const size_t n = size_t(sparse.count);
  if (n > count_) {
    ctx.fail(name + " substitutes " + std::to_string(n) + " sparse elements of its " + std::to_string(count_));
  }
  const int indexSize = componentSizeOf(sparse.indices.componentType);
  if (sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      sparse.indices.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
    ctx.fail(name + " has sparse indices of component type " + std::to_string(sparse.indices.componentType) +
             " (UNSIGNED_BYTE, UNSIGNED_SHORT or UNSIGNED_INT)");
  }
  // Each part's bytes: inside its bufferView (checked against its buffer), without overflow.
  auto partBytes = [&](int viewIndex, int byteOffset, size_t bytesPerElement, const char* part) {
    size_t length = 0;
    const unsigned char* view = bufferViewBytes(ctx, viewIndex, length, name + " sparse " + part);
    if (byteOffset < 0 || size_t(byteOffset) > length || (length - size_t(byteOffset)) / bytesPerElement < n) {
      ctx.fail(name + " sparse " + part + " need " + std::to_string(n) + " elements of " +
               std::to_string(bytesPerElement) + " bytes from byte " + std::to_string(byteOffset) + ", past the end of bufferView " +
               std::to_string(viewIndex) + " (" + std::to_string(length) + " bytes)");
    }
    return view + byteOffset;
  };
  const unsigned char* indices = partBytes(sparse.indices.bufferView, sparse.indices.byteOffset, size_t(indexSize), "indices");
  const unsigned char* values = partBytes(sparse.values.bufferView, sparse.values.byteOffset, elementSize, "values");

  auto dense = std::make_shared<std::vector<unsigned char>>(count_ * elementSize, 0);
  if (data_)
    for (size_t i = 0; i < count_; ++i) std::memcpy(dense->data() + i * elementSize, element(i), elementSize);
  uint64_t previous = 0;
  for (size_t k = 0; k < n; ++k) {
    uint32_t index = 0;
    const unsigned char* p = indices + k * size_t(indexSize);
    if (indexSize == 1) index = p[0];
    else if (indexSize == 2) { uint16_t v; std::memcpy(&v, p, 2); index = v; }
    else std::memcpy(&index, p, 4);
    if (index >= count_ || (k > 0 && index <= previous)) {
      ctx.fail(name + " sparse index " + std::to_string(index) + " (substitution " + std::to_string(k) +
               ") is out of range or not increasing");
    }
    previous = index;
    std::memcpy(dense->data() + size_t(index) * elementSize, values + k * elementSize, elementSize);
  }
  dense_ = dense;
  data_ = dense_->data();
  stride_ = elementSize;
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
