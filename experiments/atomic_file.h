// Result files are written whole or not at all: the text goes to a temporary file beside
// the target, is flushed, and is renamed over it, so an interrupted run never leaves a
// half-written result.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace radquad {

// Throws InputError naming the path when it cannot be written, or when a device, a pipe or a
// socket is there (it would be replaced).
void writeFileAtomically(const std::filesystem::path& path, const std::string& contents);

// Checked before any work: `path` (given as `option`) can be written (it is not empty, its
// folder exists and a file can be created in it, and it is not a folder, a device, a pipe
// or a socket), and it is none of `inputs` (the same file under any name). Throws
// InputError naming the option and the path otherwise.
void checkOutputPath(const std::filesystem::path& path, const std::string& option,
                     const std::vector<std::filesystem::path>& inputs);

// Creates an output folder and its parents; throws InputError naming it when that fails.
void createOutputDirectory(const std::filesystem::path& directory);

}  // namespace radquad
