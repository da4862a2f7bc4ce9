#pragma once
// A small reader of the layout a SPIR-V module declares: its struct types with their names, member
// names and explicit Offset decorations, the ArrayStride of arrays, and which struct is the
// push-constant block. Enough to compare what glslang computed for a buffer's struct with what
// C++ computes for the struct of the same name (tests/gpu/layout_contract_test.cpp).
// Only the word stream is read: header, then instructions of (word count << 16 | opcode).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace mixtrace::testing {

class SpirvLayout {
 public:
  struct Member {
    std::string name;
    uint32_t type = 0;
    std::optional<uint32_t> offset;  // set only where the struct has an explicit layout
  };
  struct Struct {
    uint32_t id = 0;
    std::string name;
    std::vector<Member> members;
    bool isBlock = false;  // a buffer or push-constant block itself, not a struct inside one
    bool hasExplicitLayout() const {
      for (const Member& m : members)
        if (!m.offset) return false;
      return !members.empty();
    }
  };

  SpirvLayout(const uint32_t* words, size_t wordCount) {
    if (wordCount < 5 || words[0] != kMagic) throw std::runtime_error("not a SPIR-V module");
    for (size_t at = 5; at < wordCount;) {
      const uint32_t count = words[at] >> 16, opcode = words[at] & 0xffffu;
      if (count == 0 || at + count > wordCount) throw std::runtime_error("truncated SPIR-V instruction");
      read(opcode, words + at, count);
      at += count;
    }
    for (auto& [id, s] : structs_) {
      s.isBlock = blocks_.count(id) > 0;
      auto name = names_.find(id);
      if (name != names_.end()) s.name = name->second;
      for (size_t i = 0; i < s.members.size(); ++i) {
        auto m = memberNames_.find({id, uint32_t(i)});
        if (m != memberNames_.end()) s.members[i].name = m->second;
        auto o = memberOffsets_.find({id, uint32_t(i)});
        if (o != memberOffsets_.end()) s.members[i].offset = o->second;
      }
    }
  }

  // Every struct type of the module (glslang declares a struct once per layout it is used with:
  // a buffer's copy has offsets, a function-local copy has none).
  std::vector<Struct> structs() const {
    std::vector<Struct> out;
    for (const auto& [id, s] : structs_) out.push_back(s);
    return out;
  }

  // ArrayStride of every array (sized or runtime) whose elements are of type `element`.
  std::vector<uint32_t> arrayStridesOf(uint32_t element) const {
    std::vector<uint32_t> out;
    for (const auto& [id, a] : arrays_)
      if (a.element == element) {
        auto s = arrayStrides_.find(id);
        if (s != arrayStrides_.end()) out.push_back(s->second);
      }
    return out;
  }

  // (element type, ArrayStride) of every array with an explicit stride.
  std::vector<std::pair<uint32_t, uint32_t>> arrayStrides() const {
    std::vector<std::pair<uint32_t, uint32_t>> out;
    for (const auto& [id, a] : arrays_)
      if (auto s = arrayStrides_.find(id); s != arrayStrides_.end()) out.push_back({a.element, s->second});
    return out;
  }

  // Bytes a value of `type` covers in an explicitly laid-out block: up to the end of its last
  // member for a struct (no tail padding in the scalar layout).
  uint32_t byteSize(uint32_t type) const {
    if (auto s = scalarBytes_.find(type); s != scalarBytes_.end()) return s->second;
    if (auto v = vectors_.find(type); v != vectors_.end()) return v->second.count * byteSize(v->second.component);
    if (auto a = arrays_.find(type); a != arrays_.end()) {
      auto length = constants_.find(a->second.lengthId);
      if (a->second.runtime || length == constants_.end()) throw std::runtime_error("array without a size");
      auto stride = arrayStrides_.find(type);
      const uint32_t elementBytes = stride != arrayStrides_.end() ? stride->second : byteSize(a->second.element);
      return length->second * elementBytes;
    }
    if (auto s = structs_.find(type); s != structs_.end()) {
      uint32_t end = 0;
      for (const Member& m : s->second.members) {
        if (!m.offset) throw std::runtime_error("struct " + s->second.name + " has no explicit layout");
        end = std::max(end, *m.offset + byteSize(m.type));
      }
      return end;
    }
    throw std::runtime_error("type %" + std::to_string(type) + " has no size here");
  }

  // The struct types of the module's push-constant variables (a `uniform Push { T pc; }` block).
  std::vector<uint32_t> pushConstantBlocks() const { return pushConstantBlocks_; }

  // The Binding decoration of every variable the module declares (glslang keeps only the
  // buffers the code reads or writes), sorted.
  std::vector<uint32_t> bindings() const {
    std::set<uint32_t> sorted;
    for (const auto& [id, binding] : bindings_) sorted.insert(binding);
    return {sorted.begin(), sorted.end()};
  }

 private:
  static constexpr uint32_t kMagic = 0x07230203u;
  enum Op : uint32_t {
    OpName = 5, OpMemberName = 6, OpTypeInt = 21, OpTypeFloat = 22, OpTypeVector = 23, OpTypeArray = 28,
    OpTypeRuntimeArray = 29, OpTypeStruct = 30, OpTypePointer = 32, OpConstant = 43, OpVariable = 59,
    OpDecorate = 71, OpMemberDecorate = 72,
  };
  static constexpr uint32_t kDecorationBlock = 2, kDecorationArrayStride = 6, kDecorationOffset = 35,
                            kDecorationBinding = 33;
  static constexpr uint32_t kStorageClassPushConstant = 9;

  struct Vector { uint32_t component, count; };
  struct Array { uint32_t element, lengthId; bool runtime; };

  // A literal string: UTF-8, nul-terminated, packed four bytes a word, lowest byte first.
  static std::string literalString(const uint32_t* w, size_t words) {
    std::string s;
    for (size_t i = 0; i < words; ++i)
      for (int b = 0; b < 4; ++b) {
        const char c = char((w[i] >> (8 * b)) & 0xffu);
        if (c == 0) return s;
        s += c;
      }
    return s;
  }

  void read(uint32_t opcode, const uint32_t* w, uint32_t count) {
    switch (opcode) {
      case OpName: names_[w[1]] = literalString(w + 2, count - 2); break;
      case OpMemberName: memberNames_[{w[1], w[2]}] = literalString(w + 3, count - 3); break;
      case OpTypeInt:
      case OpTypeFloat: scalarBytes_[w[1]] = w[2] / 8; break;
      case OpTypeVector: vectors_[w[1]] = {w[2], w[3]}; break;
      case OpTypeArray: arrays_[w[1]] = {w[2], w[3], false}; break;
      case OpTypeRuntimeArray: arrays_[w[1]] = {w[2], 0, true}; break;
      case OpTypeStruct: {
        Struct& s = structs_[w[1]];
        s.id = w[1];
        for (uint32_t i = 2; i < count; ++i) s.members.push_back({"", w[i], std::nullopt});
        break;
      }
      case OpTypePointer: pointees_[w[1]] = {w[2], w[3]}; break;
      case OpConstant:
        if (count == 4) constants_[w[2]] = w[3];  // 32-bit constants: the array lengths
        break;
      case OpVariable:
        if (w[3] == kStorageClassPushConstant) {
          auto p = pointees_.find(w[1]);
          if (p != pointees_.end()) pushConstantBlocks_.push_back(p->second.second);
        }
        break;
      case OpDecorate:
        if (count >= 4 && w[2] == kDecorationArrayStride) arrayStrides_[w[1]] = w[3];
        if (count >= 3 && w[2] == kDecorationBlock) blocks_.insert(w[1]);
        if (count >= 4 && w[2] == kDecorationBinding) bindings_[w[1]] = w[3];
        break;
      case OpMemberDecorate:
        if (count >= 5 && w[3] == kDecorationOffset) memberOffsets_[{w[1], w[2]}] = w[4];
        break;
      default: break;
    }
  }

  std::map<uint32_t, std::string> names_;
  std::map<std::pair<uint32_t, uint32_t>, std::string> memberNames_;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> memberOffsets_;
  std::map<uint32_t, uint32_t> arrayStrides_;
  std::map<uint32_t, uint32_t> scalarBytes_;
  std::map<uint32_t, Vector> vectors_;
  std::map<uint32_t, Array> arrays_;
  std::map<uint32_t, Struct> structs_;
  std::map<uint32_t, std::pair<uint32_t, uint32_t>> pointees_;  // pointer type -> (storage class, type)
  std::map<uint32_t, uint32_t> constants_;
  std::vector<uint32_t> pushConstantBlocks_;
  std::set<uint32_t> blocks_;
  std::map<uint32_t, uint32_t> bindings_;  // variable -> binding
};

}  // namespace mixtrace::testing
