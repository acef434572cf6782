// Writes a file under a temporary name and renames it into place when complete, so a reader never
// sees a half-written output.
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace msislab::io {

/// Calls write(stream) on "path.tmp-PID", then renames it to path. On any failure the temporary
/// is removed and InputError names the path.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);
/// The same for a whole text.
void write_text_atomically(const std::string& path, const std::string& text);

/// Creates the directory (and its parents) if needed; InputError naming it when that fails.
void create_output_dir(const std::string& dir);

/// The absolute, normalised form of a path, as result files record it.
std::string absolute_path(const std::string& path);

}  // namespace msislab::io
