#include "io/output_guard.hpp"

#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <set>

#include "io/input_error.hpp"

namespace msislab::io {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarkerPrefix = "msislab output: ";
constexpr const char* kEntriesLine = "entries:";

/// The absolute, normalised path without a trailing separator ("out/" and "out" name one folder).
fs::path output_path(const std::string& path) {
  fs::path p = fs::absolute(path).lexically_normal();
  if (!p.has_filename() && p.has_parent_path()) p = p.parent_path();
  return p;
}

/// The path with every link resolved, for comparing two paths that may name one place.
fs::path resolved(const fs::path& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(path, ec);
  if (ec) p = path;
  if (!p.has_filename() && p.has_parent_path()) p = p.parent_path();
  return p;
}

/// True when `inner` is `outer` or lies below it.
bool lies_within(const fs::path& inner, const fs::path& outer) {
  auto o = outer.begin();
  for (auto i = inner.begin(); o != outer.end(); ++i, ++o) {
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

/// Refuses a path that is, or holds, one of the inputs or the current directory.
void refuse_inputs(const OutputRequest& request, const fs::path& target) {
  const fs::path real = resolved(target);
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (!ec && lies_within(resolved(cwd), real)) {
    fail_file(request.path,
              "is the current directory or holds it; " + request.command +
                  " writes its output as a new folder: give one (for example --out result)");
  }
  for (const std::string& input : request.inputs) {
    if (input.empty()) continue;
    if (!lies_within(resolved(output_path(input)), real)) continue;
    fail_file(request.path,
              resolved(output_path(input)) == real
                  ? "is an input of this " + request.command + "; give another output path"
                  : "holds the input " + input + " of this " + request.command +
                        "; give another output path");
  }
}

/// The first entries of a folder, for a message ("'keep.txt', 'data/'").
std::string some_entries(const fs::path& dir) {
  std::string listed;
  int count = 0;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (count == 3) return listed + ", ...";
    if (count++ > 0) listed += ", ";
    listed += "'" + entry.path().filename().string() + (entry.is_directory(ec) ? "/'" : "'");
  }
  return listed;
}

/// The entries a folder's marker lists; nullopt when it lists none (a folder filled in place).
std::optional<std::set<std::string>> listed_entries(const fs::path& dir) {
  std::ifstream in(dir / kOutputMarkerName);
  std::set<std::string> listed;
  bool listing = false;
  for (std::string line; std::getline(in, line);) {
    if (line == kEntriesLine) listing = true;
    if (listing && line.rfind("  ", 0) == 0) listed.insert(line.substr(2));
  }
  if (!listing) return std::nullopt;
  return listed;
}

/// The folder's entries that its marker does not list; none when the marker lists nothing (a folder
/// msislab fills in place, never replaces whole).
std::vector<std::string> unlisted_entries(const fs::path& dir) {
  std::vector<std::string> unlisted;
  const std::optional<std::set<std::string>> listed = listed_entries(dir);
  if (!listed) return unlisted;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name == kOutputMarkerName || listed->count(name) > 0) continue;
    // A folder msislab wrote into the output later (plot's figures/, a result) is msislab's too.
    if (entry.is_directory(ec) && !output_kind(entry.path().string()).empty()) continue;
    unlisted.push_back(name);
  }
  std::sort(unlisted.begin(), unlisted.end());
  return unlisted;
}

bool is_empty_folder(const fs::path& dir) {
  std::error_code ec;
  return fs::is_empty(dir, ec) && !ec;
}

constexpr const char* kPagePrefix = "<!-- written by msislab ";
// The PNG chunk msislab adds: keyword "Software", a NUL, the text "msislab".
constexpr char kPngText[] = "tEXtSoftware\0msislab";
constexpr std::size_t kPngTextSize = sizeof kPngText - 1;
constexpr std::size_t kPngHeaderEnd = 8 + 25;  // the signature, then IHDR (length, type, 13, CRC)

/// The first `size` bytes of a file (fewer when it is shorter).
std::string file_start(const std::string& path, std::size_t size) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(size, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  bytes.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return bytes;
}

void put_u32(std::vector<unsigned char>& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back((value >> shift) & 0xffU);
}

}  // namespace

std::string page_signature(const std::string& command) {
  return std::string(kPagePrefix) + command +
         "; msislab replaces this file only when it starts with this line -->\n";
}

bool page_written_by_msislab(const std::string& path) {
  const std::string prefix = kPagePrefix;
  return file_start(path, prefix.size()) == prefix;
}

std::vector<unsigned char> signed_png(std::vector<unsigned char> png) {
  static const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (png.size() < kPngHeaderEnd || !std::equal(magic, magic + 8, png.begin())) return png;
  std::vector<unsigned char> chunk;
  put_u32(chunk, static_cast<std::uint32_t>(kPngTextSize - 4));
  chunk.insert(chunk.end(), kPngText, kPngText + kPngTextSize);
  put_u32(chunk, static_cast<std::uint32_t>(
                     ::crc32(0L, chunk.data() + 4, static_cast<uInt>(kPngTextSize))));
  png.insert(png.begin() + static_cast<long>(kPngHeaderEnd), chunk.begin(), chunk.end());
  return png;
}

bool png_written_by_msislab(const std::string& path) {
  const std::string start = file_start(path, kPngHeaderEnd + 4 + kPngTextSize);
  return start.size() == kPngHeaderEnd + 4 + kPngTextSize &&
         start.compare(kPngHeaderEnd + 4, kPngTextSize, kPngText, kPngTextSize) == 0;
}

std::string output_kind(const std::string& dir) {
  std::ifstream in(fs::path(dir) / kOutputMarkerName);
  std::string line;
  if (!in || !std::getline(in, line)) return "";
  const std::string prefix = kMarkerPrefix;
  if (line.rfind(prefix, 0) != 0) return "";
  return line.substr(prefix.size());
}

void write_output_marker(const std::string& dir, const std::string& kind,
                         const std::string& command, const std::vector<std::string>* entries) {
  const fs::path path = fs::path(dir) / kOutputMarkerName;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << kMarkerPrefix << kind << "\n"
      << "written by 'msislab " << command << "'; msislab replaces this folder only when it "
      << "finds this file";
  if (entries) {
    out << " and nothing beside what it lists\n" << kEntriesLine << "\n";
    for (const std::string& entry : *entries) out << "  " << entry << "\n";
  } else {
    out << "\n";
  }
  out.flush();
  if (!out) fail_file(path.string(), "cannot write msislab's output marker");
}

void record_output_entries(const std::string& dir, const std::vector<std::string>& names) {
  std::optional<std::set<std::string>> listed = listed_entries(dir);
  if (!listed) return;  // a folder filled in place lists nothing
  const fs::path marker = fs::path(dir) / kOutputMarkerName;
  std::ofstream out(marker, std::ios::binary | std::ios::app);
  for (const std::string& name : names) {
    if (listed->insert(name).second) out << "  " << name << "\n";
  }
  out.flush();
  if (!out) fail_file(marker.string(), "cannot write msislab's output marker");
}

bool check_output_folder(const OutputRequest& request) {
  const fs::path target = output_path(request.path);
  refuse_inputs(request, target);
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(target, ec);
  if (!fs::exists(status)) return false;
  if (fs::is_symlink(status)) {
    fail_file(request.path, "is a symbolic link; give the folder itself or a new name");
  }
  if (!fs::is_directory(status)) {
    fail_file(request.path, "is a file, not a folder msislab wrote; give a new folder name");
  }
  const std::string kind = output_kind(target.string());
  if (request.force || is_empty_folder(target)) return true;
  if (kind == request.kind) {
    const std::vector<std::string> unlisted = unlisted_entries(target);
    if (unlisted.empty()) return true;
    fail_file(request.path, "holds '" + unlisted.front() +
                                "', which msislab did not write; move it away, or --force to "
                                "replace the folder whole");
  }
  if (!kind.empty()) {
    fail_file(request.path, "holds msislab's " + kind + ", not a " + request.kind +
                                "; give another folder (or --force to replace it whole)");
  }
  fail_file(request.path, "is a folder that msislab did not write (it holds " +
                              some_entries(target) +
                              "); give a new folder name, or --force to replace it whole");
}

void check_output_file(const OutputRequest& request,
                       bool (*written_by_msislab)(const std::string&)) {
  const fs::path target = output_path(request.path);
  const fs::path real = resolved(target);
  for (const std::string& input : request.inputs) {
    if (!input.empty() && resolved(output_path(input)) == real) {
      fail_file(request.path, "is an input of this " + request.command + "; give another name");
    }
  }
  std::error_code ec;
  const fs::file_status status = fs::status(target, ec);
  if (!fs::exists(status)) return;
  if (fs::is_directory(status)) {
    fail_file(request.path, "is a folder; give the name of a file to write");
  }
  if (!fs::is_regular_file(status) || !written_by_msislab(target.string())) {
    fail_file(request.path, "is a file that msislab did not write; give a new name");
  }
}

void claim_output_folder(const OutputRequest& request) {
  const bool exists = check_output_folder(request);
  const fs::path target = output_path(request.path);
  if (!exists) {
    std::error_code ec;
    fs::create_directories(target, ec);
    if (ec) fail_file(request.path, "cannot create the output folder: " + ec.message());
  }
  if (output_kind(target.string()) != request.kind) {
    write_output_marker(target.string(), request.kind, request.command, nullptr);
  }
}

StagedFolder::StagedFolder(OutputRequest request) : request_(std::move(request)) {
  check_output_folder(request_);
  const fs::path target = output_path(request_.path);
  target_ = target.string();
  const fs::path staging = target.parent_path() / ("." + target.filename().string() + ".partial-" +
                                                   std::to_string(::getpid()));
  std::error_code ec;
  fs::create_directories(target.parent_path(), ec);
  fs::remove_all(staging, ec);
  if (!fs::create_directory(staging, ec)) {
    fail_file(request_.path, "cannot create the output folder: " + ec.message());
  }
  staging_ = staging.string();
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

void StagedFolder::commit() {
  check_output_folder(request_);  // what stands there may have changed while the output was made
  std::vector<std::string> entries;
  std::error_code listing;
  for (const auto& entry : fs::directory_iterator(staging_, listing)) {
    entries.push_back(entry.path().filename().string());
  }
  std::sort(entries.begin(), entries.end());
  write_output_marker(staging_, request_.kind, request_.command, &entries);
  const fs::path target(target_);
  const fs::path old = target.parent_path() /
                       ("." + target.filename().string() + ".old-" + std::to_string(::getpid()));
  std::error_code ec;
  const bool had_target = fs::exists(fs::symlink_status(target, ec));
  ec.clear();
  if (had_target) fs::rename(target, old, ec);
  if (!ec) fs::rename(staging_, target, ec);
  if (ec) {
    const std::string why = ec.message();
    std::error_code ignored;
    if (had_target && !fs::exists(target, ignored)) fs::rename(old, target, ignored);
    fail_file(request_.path, "cannot put the folder in place: " + why);  // ~StagedFolder cleans
  }
  committed_ = true;
  fs::remove_all(old, ec);
}

}  // namespace msislab::io
