// Output files are written atomically: to a temporary file beside the target, then renamed.
// A reader never sees a half-written file under the final name.
#pragma once

#include <filesystem>
#include <string>

namespace rotbeam {

/// Writes `contents` to `path` atomically (temporary file + rename). Throws std::runtime_error
/// naming the path on failure, leaving no temporary behind.
void write_file_atomically(const std::filesystem::path& path, const std::string& contents);

}  // namespace rotbeam
