#pragma once
// Checks made before a render starts on the files it will write, so that a typo costs nothing
// and no output destroys another output or an input (the scene, its buffers and images).
#include <string>
#include <vector>

namespace mixtrace {

struct NamedFile {
  std::string role;   // how the user knows it: "--out", "--stats", "the scene", ...
  std::string path;   // as given
  std::string quoted() const { return role + " '" + path + "'"; }
};

// The file's directory exists, is a directory and accepts new files (tried by creating and
// removing one: permission bits say nothing for root or a read-only mount); the file itself, if
// it exists, is a regular file (not a directory, a device, a FIFO). Throws mixtrace::Error.
void checkWritableOutput(const NamedFile& output);

// No two outputs name the same file, and no output names an input; compared as canonical paths
// (through symbolic links, "..", "./") and, for files that exist, by identity (hard links).
// Throws mixtrace::Error naming both.
void checkNoSharedFiles(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs);

}  // namespace mixtrace
