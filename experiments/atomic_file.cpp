#include "experiments/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "kernel/input_error.h"

namespace radquad {

namespace {

// A device, a pipe or a socket at the output path would be replaced by the renamed result
// (as root, /dev/full would become a regular file): refused.
void refuseSpecialFile(const std::filesystem::path& path, const std::string& named) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
      !std::filesystem::is_directory(status)) {
    throw InputError(named + ": not a regular file (a device, a pipe or a socket); refusing to "
                             "replace it");
  }
}

// Creates the temporary file a result for `path` is written to (PATH.tmp.XXXXXX in its
// folder); its descriptor, or -1 with errno set.
int createTemporaryBeside(const std::filesystem::path& path, std::string* name) {
  const std::filesystem::path directory =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  const std::string pattern = (directory / (path.filename().string() + ".tmp.XXXXXX")).string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  const int descriptor = mkstemp(buffer.data());
  if (descriptor >= 0) *name = buffer.data();
  return descriptor;
}

}  // namespace

void checkOutputPath(const std::filesystem::path& path, const std::string& option,
                     const std::vector<std::filesystem::path>& inputs) {
  const std::string named = option + " " + path.string();
  if (path.empty()) throw InputError(option + ": an empty path");
  std::error_code error;
  for (const std::filesystem::path& input : inputs) {
    if (std::filesystem::exists(path, error) && std::filesystem::equivalent(path, input, error)) {
      throw InputError(named + ": is the input " + input.string() + "; refusing to overwrite it");
    }
  }
  if (std::filesystem::is_directory(path, error)) throw InputError(named + ": is a folder");
  const std::filesystem::path directory =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(directory, error)) {
    throw InputError(named + ": the folder " + directory.string() + " does not exist");
  }
  if (::access(directory.c_str(), W_OK) != 0) {
    throw InputError(named + ": cannot write in " + directory.string() + " (" +
                     std::strerror(errno) + ")");
  }
  refuseSpecialFile(path, named);
  // Permissions do not tell everything (a read-only or virtual file system such as /sys or
  // /proc): the temporary file the result will be written to is created and removed now.
  std::string temporary;
  const int descriptor = createTemporaryBeside(path, &temporary);
  if (descriptor < 0) {
    throw InputError(named + ": cannot write in " + directory.string() + " (" +
                     std::strerror(errno) + ")");
  }
  ::close(descriptor);
  ::unlink(temporary.c_str());
}

void writeFileAtomically(const std::filesystem::path& path, const std::string& contents) {
  refuseSpecialFile(path, path.string());
  std::string temporary;
  const int descriptor = createTemporaryBeside(path, &temporary);
  if (descriptor < 0) {
    throw InputError(path.string() + ": cannot write (" + std::strerror(errno) + ")");
  }
  auto fail = [&](const char* what) {
    const std::string reason = std::strerror(errno);
    ::close(descriptor);
    ::unlink(temporary.c_str());
    throw InputError(path.string() + ": cannot write (" + what + ": " + reason + ")");
  };
  std::size_t written = 0;
  while (written < contents.size()) {
    const ssize_t n = ::write(descriptor, contents.data() + written, contents.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail("write");
    }
    written += std::size_t(n);
  }
  if (::fchmod(descriptor, 0644) != 0) fail("chmod");
  if (::fsync(descriptor) != 0) fail("fsync");
  if (::close(descriptor) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(temporary.c_str());
    throw InputError(path.string() + ": cannot write (close: " + reason + ")");
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(temporary.c_str());
    throw InputError(path.string() + ": cannot write (rename: " + reason + ")");
  }
}

void createOutputDirectory(const std::filesystem::path& directory) {
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) {
    throw InputError(directory.string() + ": cannot create the folder (" + error.message() + ")");
  }
}

}  // namespace radquad
