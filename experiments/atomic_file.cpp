#include "experiments/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "kernel/input_error.h"

namespace radquad {

void checkOutputPath(const std::filesystem::path& path, const std::string& option,
                     const std::vector<std::filesystem::path>& inputs) {
  const std::string named = option + " " + path.string();
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
}

void writeFileAtomically(const std::filesystem::path& path, const std::string& contents) {
  const std::filesystem::path directory =
      path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::string pattern = (directory / (path.filename().string() + ".tmp.XXXXXX")).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int descriptor = mkstemp(name.data());
  if (descriptor < 0) {
    throw InputError(path.string() + ": cannot write (" + std::strerror(errno) + ")");
  }
  const std::string temporary(name.data());
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
