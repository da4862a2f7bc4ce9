#pragma once
// How deep a JSON text nests, found by a flat scan (no recursion): JSON parsers recurse once per
// [ or {, so a small hostile file of a few thousand levels overflows their stack. The glTF loader
// refuses such files with this scan before parsing, and so does anything else that parses a
// scene's JSON (session/scene_files.cpp).
#include <cstddef>

namespace mixtrace {

constexpr size_t kJsonNestingOk = static_cast<size_t>(-1);

// The byte offset of the first [ or { that nests deeper than `maxDepth` (brackets inside strings,
// escapes included, do not count), or kJsonNestingOk when none does.
size_t jsonNestingExceededAt(const char* json, size_t size, int maxDepth);

}  // namespace mixtrace
