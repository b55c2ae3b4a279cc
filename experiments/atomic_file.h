// Result files are written whole or not at all: the text goes to a temporary file beside
// the target, is flushed, and is renamed over it, so an interrupted run never leaves a
// half-written result.
#pragma once

#include <filesystem>
#include <string>

namespace radquad {

// Throws InputError naming the path when it cannot be written.
void writeFileAtomically(const std::filesystem::path& path, const std::string& contents);

// Creates an output folder and its parents; throws InputError naming it when that fails.
void createOutputDirectory(const std::filesystem::path& directory);

}  // namespace radquad
