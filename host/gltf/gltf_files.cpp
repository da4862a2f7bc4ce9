// Which files a glTF scene may make the loader read, and how they are read: regular files only,
// bounded in size, never blocking (FIFOs), and (for buffers and images) only under the asset root
// (by default the scene's own folder), with no current-directory fallback. tinygltf reaches the
// file system only through the callbacks installed here.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "gltf/gltf_internal.h"
#include "gltf/gltf_limits.h"
#include "util/error.h"

namespace mixtrace {
namespace gltf {
namespace {

namespace fs = std::filesystem;

const char* fileKind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string mebibytes(uint64_t bytes) { return std::to_string(bytes >> 20) + " MiB"; }  // limits are whole MiB

// Inside `root` (both canonical): no ".." at the front of the relative path.
bool isUnder(const fs::path& path, const fs::path& root) {
  const fs::path relative = path.lexically_relative(root);
  return !relative.empty() && *relative.begin() != "..";
}

}  // namespace

std::string readRegularFile(const std::string& path, uint64_t maxBytes, std::vector<unsigned char>& out) {
  out.clear();
  // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer, forever.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return std::string("cannot be opened (") + std::strerror(errno) + ")";
  struct stat info {};
  std::string problem;
  if (::fstat(fd, &info) != 0) {
    problem = std::string("cannot be inspected (") + std::strerror(errno) + ")";
  } else if (!S_ISREG(info.st_mode)) {
    problem = std::string("is ") + fileKind(info.st_mode) + ", not a regular file";
  } else if (uint64_t(info.st_size) > maxBytes) {
    problem = "is " + std::to_string(info.st_size) + " bytes, more than the " + mebibytes(maxBytes) + " limit";
  } else {
    // Read what fstat promised and no more: a file that grows meanwhile cannot extend the read.
    out.resize(size_t(info.st_size));
    size_t got = 0;
    while (got < out.size()) {
      const ssize_t n = ::read(fd, out.data() + got, out.size() - got);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        problem = std::string("could not be read (") + std::strerror(errno) + ")";
        break;
      }
      if (n == 0) break;  // shrank meanwhile
      got += size_t(n);
    }
    out.resize(got);
  }
  ::close(fd);
  if (!problem.empty()) out.clear();
  return problem;
}

AssetFiles::AssetFiles(const std::string& scenePath, const std::string& assetRoot) {
  std::error_code ec;
  const fs::path sceneDir = fs::weakly_canonical(fs::absolute(fs::path(scenePath), ec).parent_path(), ec);
  if (ec) throw Error(scenePath + ": cannot resolve the scene's folder (" + ec.message() + ")");
  baseDir_ = sceneDir.string();
  prefix_ = baseDir_.back() == '/' ? baseDir_ : baseDir_ + "/";
  if (assetRoot.empty()) {
    root_ = sceneDir;
  } else {
    root_ = fs::canonical(fs::path(assetRoot), ec);
    if (ec || !fs::is_directory(root_, ec)) throw Error("asset root '" + assetRoot + "' is not a directory");
  }
}

tinygltf::FsCallbacks AssetFiles::callbacks() {
  tinygltf::FsCallbacks fs{};
  fs.FileExists = [](const std::string& path, void* self) { return static_cast<AssetFiles*>(self)->exists(path); };
  // No expansion: tinygltf's default runs wordexp, which would give a URI "~" and "$VAR".
  fs.ExpandFilePath = [](const std::string& path, void*) { return path; };
  fs.ReadWholeFile = [](std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self) {
    return static_cast<AssetFiles*>(self)->read(*out, *err, path);
  };
  fs.WriteWholeFile = [](std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "the loader writes no files";
    return false;
  };
  fs.user_data = this;
  return fs;
}

std::string AssetFiles::hidePaths(std::string text) const {
  for (size_t at = text.find(prefix_); at != std::string::npos; at = text.find(prefix_, at)) text.erase(at, prefix_.size());
  return text;
}

bool AssetFiles::resolve(const std::string& joined, fs::path& resolved) {
  // tinygltf tries <baseDir>/<uri>, then ./<uri>: the second is the current-directory fallback,
  // which a scene must not depend on (nor use to reach files next to wherever it is rendered).
  if (joined.compare(0, prefix_.size(), prefix_) != 0) return false;
  const std::string uri = joined.substr(prefix_.size());
  if (!uri.empty() && uri[0] == '/') {
    refuse("URI '" + uri + "' is an absolute path; buffers and images must be named relative to the scene");
    return false;
  }
  std::error_code ec;
  resolved = fs::weakly_canonical(fs::path(joined), ec);
  // Decided before looking at whether the file exists, so a refusal tells nothing about outside.
  if (ec || !isUnder(resolved, root_)) {
    refuse("URI '" + uri + "' points outside the " + (rootIsSceneDir() ? "scene's folder" : "asset root") +
           " (--asset-root DIR admits files under DIR)");
    return false;
  }
  return true;
}

bool AssetFiles::exists(const std::string& joined) {
  fs::path resolved;
  if (!resolve(joined, resolved)) return false;
  std::error_code ec;
  return fs::exists(resolved, ec);
}

bool AssetFiles::read(std::vector<unsigned char>& out, std::string& err, const std::string& joined) {
  fs::path resolved;
  if (!resolve(joined, resolved)) return false;
  const std::string problem = readRegularFile(resolved.string(), kMaxFileBytes, out);
  if (problem.empty()) return true;
  refuse("URI '" + joined.substr(prefix_.size()) + "' " + problem);
  err += problem;
  return false;
}

void AssetFiles::refuse(const std::string& message) {
  if (firstRefusal_.empty()) firstRefusal_ = message;
}

bool AssetFiles::rootIsSceneDir() const { return root_ == fs::path(baseDir_); }

}  // namespace gltf
}  // namespace mixtrace
