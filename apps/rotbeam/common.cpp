#include "common.hpp"

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cctype>
#include <cmath>
#include <csignal>
#include <ctime>
#include <cstdlib>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace rotbeam::cli {

void CaseOptions::add_to(CLI::App& app) {
  app.add_option("config", config_path, "Case configuration (TOML); defaults reproduce the thesis base case");
  app.add_option("--set", overrides, "Override one key: section.key=value (value read as TOML; repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

Config CaseOptions::load() const {
  Config c = load_config(config_path, overrides);
  for (const std::string& w : plausibility_warnings(c)) std::cerr << "rotbeam: warning: " << w << "\n";
  return c;
}

Config CaseOptions::load_filament(const std::string& command) const {
  Config c = load();
  if (c.brush)
    throw ConfigError("brush: this configuration describes a brush ([brush]); `rotbeam " + command +
                      "` runs one filament: run the brush with `rotbeam brush`, or leave out the [brush] keys");
  return c;
}

PassProgressLine::PassProgressLine(bool quiet) : active_(!quiet), terminal_(isatty(STDERR_FILENO)) {}

PassProgressLine::~PassProgressLine() {
  if (shown_) std::fprintf(stderr, "\r%80s\r", "");
}

std::function<void(const PassProgress&)> PassProgressLine::callback() {
  if (!active_) return {};
  return [this](const PassProgress& p) {
    if (p.elapsed_s < 1.0) return;
    // On a terminal one line redrawn in place; in a log (a batch job, a pipe) a whole line at
    // kLogProgressFirst and every kLogProgressInterval after, so that a long pass says how far it is
    // where nobody watches a terminal.
    if (!terminal_) {
      if (p.elapsed_s < next_log_s_) return;
      next_log_s_ = p.elapsed_s + kLogProgressInterval;
    }
    const char* start = terminal_ ? "\r  " : "rotbeam: progress: ";
    const char* end = terminal_ ? "   " : "\n";
    const double done = (p.theta_deg - p.start_deg) / (p.end_deg - p.start_deg);
    const double eta = done > 0 ? p.elapsed_s * (1 - done) / done : 0.0;
    if (!p.stage.empty()) {
      std::fprintf(stderr, "%s%s, %d revolutions run, section distance %.2e, %s elapsed%s", start, p.stage.c_str(),
                   p.revolution, p.section_distance, duration_text(p.elapsed_s).c_str(), end);
    } else if (p.revolutions > 0) {
      std::fprintf(stderr, "%srevolution %d of %d, section distance %.2e, %s elapsed, ETA %s%s", start, p.revolution,
                   p.revolutions, p.section_distance, duration_text(p.elapsed_s).c_str(), duration_text(eta).c_str(), end);
    } else {
      std::fprintf(stderr, "%sθ = %.2f° of %.1f° (%.0f %%), %ld steps, %s elapsed, ETA %s%s", start, p.theta_deg,
                   p.end_deg, 100 * done, p.steps, duration_text(p.elapsed_s).c_str(), duration_text(eta).c_str(), end);
    }
    std::fflush(stderr);
    shown_ = terminal_;
  };
}

LiveLine::LiveLine(bool active) : active_(active), start_(std::chrono::steady_clock::now()) {
  if (!active_) return;
  ticker_ = std::thread([this] {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::seconds(1), [this] { return done_; })) draw_locked();
  });
}

LiveLine::~LiveLine() {
  if (!active_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
  }
  wake_.notify_all();
  ticker_.join();
  std::fprintf(stderr, "\r%100s\r", "");
  std::fflush(stderr);
}

void LiveLine::set(std::function<std::string(double)> render) {
  if (!active_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  render_ = std::move(render);
  draw_locked();
}

void LiveLine::draw_locked() {
  if (!render_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "\r%s   ", render_(elapsed).c_str());
  std::fflush(stderr);
}

ScratchFile::~ScratchFile() {
  if (!path_.empty()) std::remove(path_.c_str());
}

namespace {

// Removes the scratch files `STEM-PID-XXXXXX SUFFIX` in `folder` that a process no longer alive left
// (killed with SIGKILL, it could not remove its own). Only this user's regular files of exactly
// that form: any other name is not ours.
void remove_dead_scratch(const std::filesystem::path& folder, const std::string& stem, const std::string& suffix) {
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = e.path().filename().string();
    if (name.size() < stem.size() + 9 + suffix.size() || name.rfind(stem + "-", 0) != 0 ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string middle = name.substr(stem.size() + 1, name.size() - stem.size() - 1 - suffix.size());
    const std::size_t dash = middle.find('-');
    if (dash == std::string::npos || dash == 0 || middle.size() - dash - 1 != 6 ||
        middle.find_first_not_of("0123456789") != dash)
      continue;
    const long pid = std::strtol(middle.c_str(), nullptr, 10);
    struct stat st {};
    if (pid <= 0 || pid == ::getpid() || ::lstat(e.path().c_str(), &st) != 0 || !S_ISREG(st.st_mode) ||
        st.st_uid != ::getuid())
      continue;
    if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) std::filesystem::remove(e.path(), ec);
  }
}

}  // namespace

std::string ScratchFile::create(const std::string& stem, const std::string& suffix) {
  const std::filesystem::path folder = std::filesystem::temp_directory_path();
  remove_dead_scratch(folder, stem, suffix);
  std::string tmpl = (folder / (stem + "-" + std::to_string(::getpid()) + "-XXXXXX" + suffix)).string();
  const int fd = ::mkstemps(tmpl.data(), static_cast<int>(suffix.size()));
  if (fd < 0) throw std::runtime_error(tmpl + ": cannot create a scratch file");
  ::close(fd);
  path_ = tmpl;
  return path_;
}

CLI::Validator non_empty_list(const std::string& example) {
  return CLI::Validator(
      [example](std::string& s) -> std::string {
        return s.find_first_not_of(" \t") == std::string::npos ? "an empty list; give values, e.g. " + example : "";
      },
      "");
}

void print_error(const std::string& message) {
  std::string one_line = message;
  for (char& c : one_line)
    if (c == '\n') c = ' ';
  std::cerr << "rotbeam: error: " << printable(one_line) << std::endl;
}

namespace {
StopToken g_interrupt;

// The first signal's time [ms, monotonic]; 0 before one arrived. Lock-free, so signal-safe.
std::atomic<long long> g_first_signal_ms{0};
static_assert(std::atomic<long long>::is_always_lock_free);

extern "C" void on_interrupt(int signal) {
  // A second signal ends the process at once, unless it comes within a second of the first: `timeout`
  // and a terminal's Ctrl-C signal the process and its group, so one request often arrives twice.
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe
  const long long ms = static_cast<long long>(now.tv_sec) * 1000 + now.tv_nsec / 1000000 + 1;
  long long expected = 0;
  if (g_first_signal_ms.compare_exchange_strong(expected, ms)) {
    g_interrupt.request_stop();
    return;
  }
  if (ms - expected >= 1000) {
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
}
}  // namespace

const StopToken& interrupt_token() { return g_interrupt; }

void install_interrupt_handlers() {
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);
}

std::string fixed(double v, int decimals) {
  char buf[64];
  const double a = std::abs(v);
  if (std::isfinite(v) && (a >= 1e9 || (a > 0.0 && a < 0.5 * std::pow(10.0, -decimals))))
    std::snprintf(buf, sizeof buf, "%.*e", std::max(decimals, 1), v);
  else
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string duration_text(double seconds) {
  if (!std::isfinite(seconds)) return "unknown";
  char buf[48];
  const double s = std::round(std::max(0.0, seconds));
  if (s < 90) std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 90 * 60) std::snprintf(buf, sizeof buf, "%.0f min %02.0f s", std::floor(s / 60), std::fmod(s, 60));
  else if (s < 48 * 3600) std::snprintf(buf, sizeof buf, "%.0f h %02.0f min", std::floor(s / 3600), std::floor(std::fmod(s, 3600) / 60));
  else std::snprintf(buf, sizeof buf, "%.0f d %02.0f h", std::floor(s / 86400), std::floor(std::fmod(s, 86400) / 3600));
  return buf;
}

std::string given_text(double v) {
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

CLI::Validator non_empty_path() {
  return CLI::Validator([](std::string& s) -> std::string { return s.empty() ? "an empty path; give a name" : ""; },
                        "PATH");
}

std::string path_text(const std::string& path) { return path.empty() ? "\"\"" : printable(path); }

std::string modes_text(const Config& config) {
  const BeamParameters& b = config.beam;
  std::string s = std::to_string(b.modes) + (b.modes == 1 ? " mode" : " modes");
  if (b.theory != BeamTheory::foreshortening) s += std::string(", ") + beam_theory_name(b.theory);
  if (b.axial == BeamAxial::extensible) s += ", extensible";
  if (!b.centrifugal && !b.coriolis) s += ", without the rotation terms";
  else if (!b.centrifugal) s += ", without the centrifugal terms";
  else if (!b.coriolis) s += ", without the Coriolis terms";
  return s;
}

std::string surface_text(const Config& config) {
  const SurfaceParameters& s = config.surface;
  const std::string depth = "depth " + percent_text(s.depth_fraction) + " %";
  switch (s.shape) {
    case SurfaceShape::plane: return depth;
    case SurfaceShape::cylinder:
      return "cylinder R " + (s.radius_m < 10.0 ? given_text(s.radius_m * 1e3) + " mm" : given_text(s.radius_m) + " m") +
             (s.speed_rpm != 0.0 ? " at " + given_text(s.speed_rpm) + " rpm" : std::string()) + ", " + depth;
    case SurfaceShape::casing:
      return "casing clearance " + given_text(s.clearance_m * 1e3) + " mm, " +
             (s.lobes > 0 ? std::to_string(s.lobes) + " " + s.lobe_law + (s.lobes == 1 ? " lobe of " : " lobes of ") +
                                given_text(s.lobe_amplitude_m * 1e3) + " mm"
                          : std::string("concentric"));
  }
  return depth;
}

std::string percent_text(double fraction) {
  const double percent = 100.0 * fraction;
  const std::string two = fixed(percent, 2);
  if (std::abs(std::stod(two) - percent) <= 1e-12 * std::abs(percent)) return two;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", percent);
  return buf;
}

std::string number_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

void check_output_file(const std::string& option, const std::string& path, const std::vector<std::string>& suffixes) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  if (path.empty()) throw ConfigError(option + " \"\": an empty file name");
  if (fs::is_directory(p)) throw ConfigError(option + " " + path + ": is a folder; give a file name");
  const fs::path parent = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(parent)) throw ConfigError(option + " " + path + ": the folder " + parent.string() + " does not exist");
  if (suffixes.empty()) return;
  std::string suffix = p.extension().string();
  for (char& c : suffix) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string list;
  for (const std::string& s : suffixes) {
    if (suffix == s) return;
    list += (list.empty() ? "" : ", ") + s;
  }
  throw ConfigError(option + " " + path + ": must end in " + list);
}

bool brush_output_folder(const std::string& dir) {
  std::ifstream in(std::filesystem::path(dir) / "summary.json");
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  return j.is_object() && j.contains("kind") && j["kind"] == "brush";
}

FolderLock drawing_lock(const std::string& dir) {
  try {
    return FolderLock(dir, FolderLock::Use::drawing);
  } catch (const std::runtime_error& e) {
    throw ConfigError(e.what());
  }
}

}  // namespace rotbeam::cli
