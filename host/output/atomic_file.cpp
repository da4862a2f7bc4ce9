#include "output/atomic_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/error.h"

namespace mixtrace {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPartialSuffix = ".partial";

// The permissions a newly created file gets (mkstemp makes 0600): 0666 less the umask, read once
// (umask can only be read by setting it).
mode_t newFileMode() {
  static const mode_t mode = [] {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    return mode_t(0666) & ~mask;
  }();
  return mode;
}

// Writes to `path` go to the file a symbolic link names, so the link survives.
fs::path destinationOf(const std::string& path) {
  std::error_code ec;
  if (fs::is_symlink(path, ec)) {
    const fs::path resolved = fs::weakly_canonical(fs::absolute(path), ec);
    if (!ec) return resolved;
  }
  return fs::path(path);
}

Error failure(const std::string& path, const std::string& what, int error) {
  return Error("cannot write '" + path + "': " + what + ": " + std::strerror(error));
}

}  // namespace

void writeFileAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  const fs::path destination = destinationOf(path);
  const fs::path directory = destination.has_parent_path() ? destination.parent_path() : fs::path(".");
  std::string name = (directory / ("." + destination.filename().string() + ".XXXXXX" + kPartialSuffix)).string();
  std::vector<char> pattern(name.begin(), name.end());
  pattern.push_back('\0');
  const int fd = ::mkstemps(pattern.data(), int(std::strlen(kPartialSuffix)));
  if (fd < 0) throw failure(path, "cannot create a file in '" + directory.string() + "'", errno);
  const std::string temporary(pattern.data());
  const auto discard = [&] {
    ::close(fd);
    ::unlink(temporary.c_str());
  };
  try {
    write(temporary);
  } catch (...) {
    discard();
    throw;
  }
  // The data reach the disk before the name does, so a crash cannot leave a renamed empty file.
  struct stat existing {};
  const mode_t mode = ::stat(destination.c_str(), &existing) == 0 ? (existing.st_mode & 07777) : newFileMode();
  if (::fchmod(fd, mode) != 0 || ::fsync(fd) != 0) {
    const int error = errno;
    discard();
    throw failure(path, "cannot flush it", error);
  }
  ::close(fd);
  if (::rename(temporary.c_str(), destination.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary.c_str());
    throw failure(path, "cannot rename the temporary file to it", error);
  }
  const int dirFd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY);
  if (dirFd >= 0) {
    ::fsync(dirFd);   // the rename itself on disk; best effort (some file systems refuse)
    ::close(dirFd);
  }
}

void writeFileAtomically(const std::string& path, const std::string& bytes) {
  writeFileAtomically(path, [&](const std::string& temporary) {
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_TRUNC);
    if (fd < 0) throw failure(path, "cannot open the temporary file", errno);
    size_t written = 0;
    while (written < bytes.size()) {
      const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const int error = n < 0 ? errno : EIO;
        ::close(fd);
        throw failure(path, "write failed", error);
      }
      written += size_t(n);
    }
    if (::close(fd) != 0) throw failure(path, "write failed", errno);
  });
}

}  // namespace mixtrace
