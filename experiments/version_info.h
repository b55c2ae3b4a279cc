// What `radquad --version` and the Python module's version report: the project's version
// (CMakeLists.txt), the commit the binary was built from and how it was compiled.
#pragma once

#include <string>

namespace radquad {

// The project's version, "MAJOR.MINOR.PATCH".
const char* projectVersion();
// The source tree's commit at build time (40 hex digits, "-modified" appended when tracked
// files other than results/ and plots/ differed from it), or "unknown" outside a git checkout.
const char* buildCommit();
// "native" (-march=native, RADQUAD_NATIVE=ON, the default) or "portable" (baseline x86-64).
const char* buildFlavour();

// "radquad VERSION (commit COMMIT, FLAVOUR build)".
inline std::string versionLine() {
  return std::string("radquad ") + projectVersion() + " (commit " + buildCommit() + ", " +
         buildFlavour() + " build)";
}

}  // namespace radquad
