// Files of a pass (docs/model.md §7): history.csv, events.csv, summary.json. The rows and events stream to
// disk as the pass produces them (PassFiles, a PassSink), so memory stays bounded whatever the
// length of the run; summary.json is written last, atomically, so a folder holds a summary only
// beside the complete files of the same run.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/history_window.hpp"
#include "rotbeam/pass.hpp"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rotbeam {

class FolderLock;

/// Column names of history.csv for n modes.
std::string history_header(int n);
/// Column names of events.csv.
std::string events_header();
/// One history.csv line (with its newline) appended to `out`.
void append_history_line(std::string& out, const HistoryRow& row);
/// One events.csv line (with its newline) appended to `out`.
void append_event_line(std::string& out, const PassEvent& event);
/// Column names of revolutions.csv for n modes (runs over many revolutions, docs/model.md §11).
std::string revolutions_header(int n);
/// One revolutions.csv line (with its newline) appended to `out`.
void append_revolution_line(std::string& out, const RevolutionRecord& record);
std::string revolutions_csv(const PassResult& result, int n);
/// The whole files of an in-memory result.
std::string history_csv(const PassResult& result, int n);
std::string events_csv(const PassResult& result);
/// force_bins.csv (docs/model.md §7): the force on the surface in hub-angle bins, impacts included.
std::string force_bins_csv(const PassResult& result);
/// wear_profile.csv's text (docs/wear.md) and summary.json's `wear` object, from a pass's wear report.
std::string wear_profile_csv(const WearReport& w, const WearSettings& settings);
nlohmann::json wear_json(const WearReport& w);
/// summary.json: the metrics, contact intervals, warnings, failure (or null), the surface as it
/// describes itself, and the resolved config.
nlohmann::json summary_json(const PassResult& result, const Config& config, const Surface& surface);

/// Creates `dir` if needed and checks that files can be created in it (before a long run).
/// Throws std::runtime_error naming the path when it cannot.
void prepare_output_folder(const std::filesystem::path& dir);

/// Refuses, before any work, a folder in `dir` under the name of a file that `writer` ("the run",
/// "the sweep") writes there: an empty one was removed and replaced without a word, a full one
/// stopped the work at its end. Throws std::runtime_error "DIR/NAME: is a folder, where WRITER
/// writes its file NAME" for the first such name.
void refuse_folders_under_file_names(const std::filesystem::path& dir, const std::vector<std::string>& names,
                                     const std::string& writer);

/// Opens `dir` for a study that writes `files` with summary.json last (a brush, a wear run; `what`
/// names it: "a brush"): refuses a folder that holds another kind of output (a run, a sweep, a brush,
/// a wear run, a reproduction) and folders under the names of its files, creates the folder, locks it,
/// and removes an older summary.json (so the folder is not complete until the new one is written)
/// with, when there was one, the `pictures` drawn from it. Returns the lock; throws
/// std::runtime_error naming the path.
std::unique_ptr<FolderLock> open_study_folder(const std::filesystem::path& dir, const std::string& what,
                                              const std::vector<std::string>& files,
                                              const std::vector<std::string>& pictures);

/// Streams a pass into `dir`: history.csv and events.csv are written into temporaries beside their
/// final names as the rows and events arrive, and commit() renames them into place and then writes
/// summary.json (with the sizes of the two files under `files`, so a reader can tell a complete
/// folder). While a writer lives it holds a lock on `dir` (the file `.rotbeam.lock`, removed when it
/// ends): a second run into the same folder stops at once instead of mixing its files with the first's. At construction
/// an older summary.json and temporaries left by a killed run are removed; a writer destroyed
/// without commit removes its own. Throws std::runtime_error naming the path on I/O errors.
/// Bytes free for writing where `dir` is or would be made (the nearest folder above it that
/// exists); 0 when unknown.
double available_disk_bytes(const std::filesystem::path& dir);

class PassFiles final : public PassSink {
public:
  /// `history_revolutions` (output.history_revolutions): over many revolutions, history.csv and
  /// events.csv keep the last that many revolutions (0: all); revolutions.csv keeps every one.
  PassFiles(const std::filesystem::path& dir, int n, int history_revolutions = 0);
  ~PassFiles() override;
  PassFiles(const PassFiles&) = delete;
  PassFiles& operator=(const PassFiles&) = delete;

  void row(const HistoryRow& row) override;
  void event(const PassEvent& event) override;
  void revolution(const RevolutionRecord& record) override;
  /// Finishes the files of `result` (which ran with this writer as its sink).
  void commit(const PassResult& result, const Config& config, const Surface& surface);

private:
  /// Removes what an uncommitted run wrote (temporaries, pieces) and the folder's lock.
  void release() noexcept;
  struct Stream {
    std::filesystem::path final_path, temporary_path;
    std::FILE* file = nullptr;
    std::string buffer;
    std::uintmax_t bytes = 0;
    std::string header;
    // Over many revolutions with a window: the finished revolutions' pieces kept, oldest first
    // (the first may start with the header).
    std::vector<std::filesystem::path> pieces;
    bool first_piece_has_header = true;
  };
  void open(Stream& s, const std::string& name, const std::string& header);
  void flush(Stream& s);
  void close(Stream& s);
  // Ends the current piece of `s` and starts the next (windowed history), dropping pieces beyond the window.
  void rotate(Stream& s);
  // Joins the kept pieces and the current one into the final file.
  void assemble(Stream& s);

  std::filesystem::path dir_;
  int n_ = 0;
  HistoryWindow window_;  // output.history_revolutions
  long piece_count_ = 0;
  void start_next_piece();
  Stream history_, events_, revolutions_;
  std::unique_ptr<FolderLock> lock_;
  bool committed_ = false;
};

/// True when `dir` holds a complete run: a summary.json whose recorded file sizes match history.csv
/// and events.csv. `summary` receives the parsed summary.json when it is.
bool complete_run_folder(const std::filesystem::path& dir, nlohmann::json* summary = nullptr);

/// Writes the files of a finished in-memory result (summary.json last).
void write_pass_outputs(const std::filesystem::path& dir, const PassResult& result, const Config& config,
                        const Surface& surface);

}  // namespace rotbeam
