#pragma once
// Writing a file so that it is never seen half-written: the data go to a temporary file in the
// same directory, which is flushed to disk and then renamed over the destination. An interrupted
// or failed write leaves the old file (or none), never a truncated image; a second Ctrl-C during
// the write can leave the temporary file (".NAME.XXXXXX.partial") behind, never a broken NAME.
#include <functional>
#include <string>

namespace mixtrace {

// Calls `write` with the name of the temporary file to fill (it exists and is empty), then
// renames it to `path` (through a symbolic link: to the file it names). Throws mixtrace::Error
// naming `path` when the temporary file cannot be made, written or renamed; exceptions from
// `write` pass through. Either way the temporary file is removed.
void writeFileAtomically(const std::string& path, const std::function<void(const std::string& temporaryPath)>& write);

// The same for bytes already in memory.
void writeFileAtomically(const std::string& path, const std::string& bytes);

}  // namespace mixtrace
