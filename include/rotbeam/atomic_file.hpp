// Output files are written atomically: to a temporary file beside the target, then renamed.
// A reader never sees a half-written file under the final name.
#pragma once

#include <filesystem>
#include <string>

namespace rotbeam {

/// Writes `contents` to `path` atomically (temporary file + rename). A symbolic link is followed:
/// the file it names is replaced and the link stays. A node that is not a regular file (a device,
/// a pipe, /dev/stdout) is written into directly, never replaced. Throws std::runtime_error naming
/// the path on failure (also for a folder), leaving no temporary behind.
void write_file_atomically(const std::filesystem::path& path, const std::string& contents);

}  // namespace rotbeam
