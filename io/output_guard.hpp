// The one rule for every output msislab writes: it creates a path, or replaces only what it wrote
// itself. A folder msislab writes carries a marker file naming the kind of output; a page or image
// carries a signature inside it. Anything else at an output path (a plain file where a folder is
// asked for, a folder of other things, an input of the same command, a folder that holds an input
// or the current directory) is refused with io::InputError (exit status 2) naming the path, before
// anything is written. Folders are built beside their target and renamed into place whole, so a
// failure leaves neither a half-written output nor the staging folder behind (docs/cli.md).
#pragma once

#include <string>
#include <vector>

namespace msislab::io {

/// The marker's file name inside every folder msislab writes.
inline constexpr const char* kOutputMarkerName = ".msislab-output";

/// What a command asks to write at one path.
struct OutputRequest {
  std::string path;                 ///< the folder or file to write
  std::string kind;                 ///< what it holds: "dataset", "result", "montecarlo", ...
  std::string command;              ///< the msislab command, for the marker and the messages
  std::vector<std::string> inputs;  ///< the command's input files and folders
  bool force = false;               ///< --force: a foreign folder may be replaced (never an input)
};

/// The kind a folder's marker names; empty when the folder has no msislab marker.
std::string output_kind(const std::string& dir);

/// Writes the marker of `kind` into the existing folder `dir`. With `entries`, the marker lists
/// them as the folder's whole content (a folder replaced whole later: anything else found in it
/// then is the user's, and the folder is refused); without, the folder is one msislab fills in
/// place.
void write_output_marker(const std::string& dir, const std::string& kind,
                         const std::string& command, const std::vector<std::string>* entries);

/// Adds `names` (files msislab writes into an existing output later, such as eval's scores) to the
/// entries the folder's marker lists, so that a later replacement of the folder knows them for
/// msislab's. Nothing happens to a folder whose marker lists nothing.
void record_output_entries(const std::string& dir, const std::vector<std::string>& names);

/// Checks that the folder request.path may be written as request.kind: absent, empty, or holding
/// msislab's marker of the same kind and nothing the marker does not list but folders with a
/// marker of their own (or any folder with
/// request.force). Refuses, naming the path: a non-folder, an input, a folder holding an input or
/// the current directory, a foreign folder, another kind of output, a file the user put into one.
/// Returns true when the folder exists (a later write replaces or adds to it).
bool check_output_folder(const OutputRequest& request);

/// Checks that the file request.path may be written: absent, or a file that `written_by_msislab`
/// recognises as msislab's own; never a folder, an input, or another kind of file.
void check_output_file(const OutputRequest& request,
                       bool (*written_by_msislab)(const std::string&));

/// The first line of every Markdown page msislab writes on its own (an HTML comment, unseen when
/// the page is rendered), by which it knows the page for its own later.
std::string page_signature(const std::string& command);
/// True when the file starts with page_signature.
bool page_written_by_msislab(const std::string& path);

/// The PNG with a tEXt chunk "Software: msislab" after its header, by which msislab knows an
/// image file for its own later. Unchanged when the bytes are not a PNG.
std::vector<unsigned char> signed_png(std::vector<unsigned char> png);
/// True when the file is a PNG carrying signed_png's chunk.
bool png_written_by_msislab(const std::string& path);

/// Checks request.path (check_output_folder), creates it with its marker when absent and returns
/// it; for outputs that are filled in place (Monte Carlo and sweep folders, which resume).
void claim_output_folder(const OutputRequest& request);

/// A folder built under a staging name beside its target and put in place whole by commit().
/// The constructor checks the request (check_output_folder); commit() checks the target again
/// (it may have changed meanwhile), writes the marker and renames the staged folder into place,
/// replacing an earlier output of the same kind. A StagedFolder destroyed before commit(), or a
/// commit() that fails, removes the staging folder and leaves the target as it was.
class StagedFolder {
 public:
  explicit StagedFolder(OutputRequest request);
  ~StagedFolder();
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  /// Where the command writes its files until commit().
  const std::string& path() const { return staging_; }
  void commit();

 private:
  OutputRequest request_;
  std::string target_;
  std::string staging_;
  bool committed_ = false;
};

}  // namespace msislab::io
