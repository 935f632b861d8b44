// Pieces shared by the rotbeam subcommands: case options, exit codes, error reporting.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/folder_lock.hpp"
#include "rotbeam/pass.hpp"
#include "rotbeam/outcome.hpp"
#include "rotbeam/stop_token.hpp"

#include <CLI/CLI.hpp>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace rotbeam::cli {

/// Exit codes of the rotbeam binary (documented in docs/cli.md).
enum ExitCode : int {
  kSuccess = 0,
  kRuntimeFailure = 1,  // I/O failure or an unexpected internal error
  kBadInput = 2,        // command line or configuration rejected
  kNoImpact = 3,        // `rotbeam impact`: the tip never reached the surface before the end angle
  kPartialBrush = 11,   // `rotbeam brush`: some filaments failed, the others' sums are written
  // 4–10 and 130: a pass stopped on a diagnosed numerical failure or a stop request; the partial
  // results are written. The code of each failure kind is in the library's table (outcome.hpp).
  kInterrupted = 130,  // SIGINT/SIGTERM: stopped cleanly, partial results written
};

/// The exit code of a numerical failure kind (the library's one table, failure_info).
inline int exit_code_for_failure(FailureKind kind) { return failure_info(kind).exit_code; }

/// The stop token of this process's command: set by SIGINT/SIGTERM once the handlers are installed.
const StopToken& interrupt_token();

/// Installs SIGINT/SIGTERM handlers that request a stop on interrupt_token() (a second signal kills).
void install_interrupt_handlers();

/// The CONFIG positional and the repeatable --set option of a case-based subcommand.
struct CaseOptions {
  std::optional<std::string> config_path;
  std::vector<std::string> overrides;
  void add_to(CLI::App& app);
  Config load() const;  // throws ConfigError
  /// load(), refusing a brush's configuration (`command` runs one filament).
  Config load_filament(const std::string& command) const;
};

/// The progress of a pass on stderr: on a terminal one line redrawn from one second on and cleared
/// at the end; otherwise (a log) a line "rotbeam: progress: …" at 10 s, then every minute; nothing
/// with `quiet`.
class PassProgressLine {
public:
  explicit PassProgressLine(bool quiet);
  ~PassProgressLine();
  /// The callback for PassControl::on_progress (empty when nothing is to be shown).
  std::function<void(const PassProgress&)> callback();

private:
  static constexpr double kLogProgressFirst = 10.0;     // [s] to the first progress line in a log
  static constexpr double kLogProgressInterval = 60.0;  // [s] between the next ones
  bool active_ = false, terminal_ = false, shown_ = false;
  double next_log_s_ = kLogProgressFirst;
};

/// A progress line of a study (many runs) on stderr when it is a terminal, redrawn every second so
/// that its clock moves while long runs are under way, cleared at the end. `set` gives the text as a
/// function of the elapsed wall time [s] (called under a lock, from this object's thread too).
class LiveLine {
public:
  explicit LiveLine(bool active);
  ~LiveLine();
  LiveLine(const LiveLine&) = delete;
  LiveLine& operator=(const LiveLine&) = delete;
  void set(std::function<std::string(double elapsed_s)> render);

private:
  void draw_locked();
  bool active_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::function<std::string(double)> render_;
  std::chrono::steady_clock::time_point start_;
  std::thread ticker_;
};

/// A uniquely named file in the system's temporary folder, `STEM-PID-XXXXXX SUFFIX`, removed when
/// this goes out of scope; create() first removes the ones of the same stem whose process is gone
/// (killed with SIGKILL, it could not remove its own).
class ScratchFile {
public:
  ScratchFile() = default;
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;
  ~ScratchFile();
  /// Creates the file (empty) and returns its path. Throws std::runtime_error when it cannot.
  std::string create(const std::string& stem, const std::string& suffix);

private:
  std::string path_;
};

/// A check for a list option (--speeds-rpm, --rtols, …): an empty or blank value is refused with
/// "an empty list; give VALUES" instead of being taken as "not given".
CLI::Validator non_empty_list(const std::string& example);

/// Prints "rotbeam: error: <message>" on one line to stderr.
void print_error(const std::string& message);

/// A number with `decimals` decimals; with an exponent (and as many significant digits) when
/// |v| ≥ 1e9 or it would show no significant digit, so no number prints as a long row of digits.
std::string fixed(double v, int decimals);

/// A duration for a progress line: "42 s", "12 min 05 s", "5 h 38 min", "3 d 04 h" (20325 s read as
/// a bare number of seconds).
std::string duration_text(double seconds);

/// A check for an option that names a file or folder: an empty name is refused ("an empty path")
/// rather than taken as not given (it wrote nothing and exited 0) or passed to the system.
CLI::Validator non_empty_path();

/// A path as a message shows it: "" for the empty one (not nothing before the colon), control and
/// bidirectional characters escaped (printable).
std::string path_text(const std::string& path);

/// A value the user gave (a speed, μ) in a summary's header: its shortest form that reads back
/// exactly, so that 999.9999 is not shown as the bound 1000.
std::string given_text(double v);

/// A number with 6 significant digits (%g), for messages.
std::string number_text(double v);
/// A fraction as a percentage for a summary line: two decimals ("2.00"), or as many significant
/// digits as tell it apart when two decimals would round it onto another value (0.999999999 is
/// "99.9999999", not "100.00").
std::string percent_text(double fraction);
/// The surface of a case for a header line: "depth 2.00 %" (plane), "cylinder R 30 mm at -500 rpm,
/// depth 2.00 %", "casing clearance 0.1 mm, 2 lobes of 0.3 mm" (docs/surfaces.md).
std::string surface_text(const Config& config);
/// "5 modes", with the beam theory and the rotation terms where they are not the thesis's
/// ("5 modes, elastica, without the Coriolis terms").
std::string modes_text(const Config& config);

/// Checks, before any work, a file the user named for an option: not a folder, in a folder that
/// exists, and (when `suffixes` is not empty) ending in one of them. Throws ConfigError naming the
/// option and the path.
void check_output_file(const std::string& option, const std::string& path, const std::vector<std::string>& suffixes);

/// Whether the folder's summary.json is a brush's ("kind": "brush", written by `rotbeam brush`).
bool brush_output_folder(const std::string& dir);

/// The lock `plot` and `animate` hold on the folder they draw (FolderLock::Use::drawing): a run into
/// it meanwhile is refused instead of leaving the pictures of the older run beside its files.
/// Throws ConfigError naming the folder when a run is writing there.
FolderLock drawing_lock(const std::string& dir);

}  // namespace rotbeam::cli
