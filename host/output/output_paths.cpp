#include "output/output_paths.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <unistd.h>

#include "util/error.h"

namespace mixtrace {
namespace {

namespace fs = std::filesystem;

fs::path canonicalOf(const std::string& path) {
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  if (ec) return fs::path(path).lexically_normal();
  fs::path resolved = fs::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : resolved;
}

bool sameFile(const std::string& a, const std::string& b) {
  if (canonicalOf(a) == canonicalOf(b)) return true;
  std::error_code ec;
  return fs::exists(a, ec) && fs::exists(b, ec) && fs::equivalent(a, b, ec) && !ec;
}

}  // namespace

void checkWritableOutput(const NamedFile& output) {
  const fs::path given(output.path);
  const std::string directory = given.has_parent_path() ? given.parent_path().string() : ".";
  const std::string where = "cannot write " + output.quoted() + ": ";
  std::error_code ec;
  const fs::file_status directoryStatus = fs::status(directory, ec);
  if (!fs::exists(directoryStatus)) throw Error(where + "directory '" + directory + "' does not exist");
  if (!fs::is_directory(directoryStatus)) throw Error(where + "'" + directory + "' is not a directory");

  const fs::file_status fileStatus = fs::status(given, ec);
  if (fs::is_directory(fileStatus)) throw Error(where + "it is a directory");
  if (fs::exists(fileStatus) && !fs::is_regular_file(fileStatus)) throw Error(where + "it is not a regular file");

  // Outputs are written to a temporary file there and renamed (output/atomic_file.h), so the
  // directory must take a new file, whatever the file's own permissions.
  std::string probe = (fs::path(directory) / ".mixtrace-probe-XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0) throw Error(where + "cannot create files in '" + directory + "': " + std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
}

void checkNoSharedFiles(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
  for (size_t i = 0; i < outputs.size(); ++i) {
    for (size_t j = 0; j < i; ++j)
      if (sameFile(outputs[i].path, outputs[j].path))
        throw Error(outputs[j].quoted() + " and " + outputs[i].quoted() +
                    " name the same file; one would overwrite the other");
    for (const NamedFile& input : inputs)
      if (sameFile(outputs[i].path, input.path))
        throw Error(outputs[i].quoted() + " would overwrite " + input.quoted());
  }
}

}  // namespace mixtrace
