// `rotbeam merge`: the folders of a sweep's shards (`rotbeam sweep --shard I/N`) combined into one
// sweep folder (issue 20, docs/distributed.md). Everything is checked before anything is written.
#include "rotbeam/sweep.hpp"

#include "rotbeam/atomic_file.hpp"
#include "rotbeam/detail/csv.hpp"
#include "rotbeam/folder_lock.hpp"
#include "rotbeam/pass_output.hpp"

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <unistd.h>

namespace rotbeam {

namespace fs = std::filesystem;

namespace {

// A shard's folder as merge reads it.
struct ShardFolder {
  fs::path dir;
  nlohmann::json description;  // sweep.json
  Shard shard;
  std::map<int, std::vector<std::string>> rows;  // sweep.csv's rows by case number (1-based)
};

std::string shown(const fs::path& p) { return p.empty() ? std::string("\"\"") : printable(p.string()); }

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(shown(path) + ": cannot read it");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// "case-0001, case-0004, … (8 cases)": the first few of a list of case folders.
std::string some_cases(const std::vector<std::string>& folders) {
  std::string out;
  for (std::size_t k = 0; k < folders.size() && k < 4; ++k) out += (k ? ", " : "") + folders[k];
  if (folders.size() > 4) out += ", …";
  return out + " (" + std::to_string(folders.size()) + (folders.size() == 1 ? " case)" : " cases)");
}

// The leaves of a JSON object by dotted key.
void leaves(const nlohmann::json& j, const std::string& prefix, std::map<std::string, nlohmann::json>& out) {
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it.value().is_object())
      leaves(it.value(), key, out);
    else
      out[key] = it.value();
  }
}

// The first key where two configurations differ, as "key = A in X, B in Y".
std::string config_difference(const nlohmann::json& a, const nlohmann::json& b, const std::string& name_a,
                              const std::string& name_b) {
  std::map<std::string, nlohmann::json> la, lb;
  leaves(a, "", la);
  leaves(b, "", lb);
  for (const auto& [key, value] : la) {
    const auto other = lb.find(key);
    if (other == lb.end()) return key + " = " + value.dump() + " in " + name_a + ", not set in " + name_b;
    if (other->second != value) return key + " = " + value.dump() + " in " + name_a + ", " + other->second.dump() + " in " + name_b;
  }
  for (const auto& [key, value] : lb)
    if (!la.count(key)) return key + " = " + value.dump() + " in " + name_b + ", not set in " + name_a;
  return "";
}

// The grid of a description, as "key: v1,v2,…; key: …".
std::string grid_text(const nlohmann::json& axes) {
  std::string out;
  for (const auto& a : axes) {
    out += (out.empty() ? "" : "; ") + a.at("key").get<std::string>() + "=";
    std::string values;
    for (const auto& v : a.at("values")) values += (values.empty() ? "" : ",") + v.get<std::string>();
    out += values;
  }
  return out;
}

ShardFolder read_shard_folder(const fs::path& dir) {
  ShardFolder f;
  f.dir = dir;
  std::error_code ec;
  if (!fs::exists(dir, ec)) throw ConfigError(shown(dir) + ": no such folder");
  if (!fs::is_directory(dir, ec)) throw ConfigError(shown(dir) + ": not a folder");
  if (!fs::exists(dir / "sweep.json", ec))
    throw ConfigError(shown(dir) + (fs::exists(dir / "sweep.csv", ec)
                                        ? ": a sweep folder without sweep.json (an older rotbeam's): run its sweep "
                                          "again with this version (it resumes) to describe it"
                                        : ": not a sweep folder (no sweep.json)"));
  try {
    f.description = nlohmann::json::parse(read_text(dir / "sweep.json"));
    const nlohmann::json& d = f.description;
    if (d.at("format") != "rotbeam sweep") throw std::runtime_error("format");
    f.shard.index = d.at("shard").at("index").get<int>();
    f.shard.count = d.at("shard").at("count").get<int>();
    d.at("version").get<std::string>();
    d.at("cases").get<std::size_t>();
    d.at("brush").get<bool>();
    d.at("config").get<nlohmann::json::object_t>();
    d.at("varying_keys").get<std::vector<std::string>>();
    for (const auto& a : d.at("axes")) {
      a.at("key").get<std::string>();
      a.at("values").get<std::vector<std::string>>();
    }
    if (f.shard.count < 1 || f.shard.index < 0 || f.shard.index >= f.shard.count) throw std::runtime_error("shard");
  } catch (const ConfigError&) {
    throw;
  } catch (const std::exception&) {
    throw ConfigError(shown(dir / "sweep.json") + ": not a sweep description rotbeam wrote (damaged or edited)");
  }
  const std::string shard_text = std::to_string(f.shard.index) + "/" + std::to_string(f.shard.count);
  if (!fs::exists(dir / "sweep.csv", ec))
    throw ConfigError(shown(dir) + ": no sweep.csv: its sweep (shard " + shard_text +
                      ") has not finished (stopped, killed, or still running); run it again to resume it");
  bool ok = true;
  const std::vector<std::vector<std::string>> records = detail::parse_csv(read_text(dir / "sweep.csv"), ok);
  if (!ok || records.empty()) throw ConfigError(shown(dir / "sweep.csv") + ": not a sweep index rotbeam wrote");
  for (std::size_t r = 1; r < records.size(); ++r) {
    if (records[r].size() != records[0].size())
      throw ConfigError(shown(dir / "sweep.csv") + ": line " + std::to_string(r + 1) + " has " +
                        std::to_string(records[r].size()) + " fields, the header " + std::to_string(records[0].size()));
    int number = 0;
    try {
      std::size_t used = 0;
      number = std::stoi(records[r][0], &used);
      if (used != records[r][0].size()) throw std::invalid_argument("case");
    } catch (const std::exception&) {
      throw ConfigError(shown(dir / "sweep.csv") + ": line " + std::to_string(r + 1) + ": case '" +
                        printable(records[r][0]) + "' is not a case number");
    }
    f.rows[number] = records[r];
  }
  f.rows[0] = records[0];  // the header, under case 0
  return f;
}

// Copies the file `from` to `to` (replaced if there) with read and write, so that a failure says
// its cause: std::filesystem::copy_file reported a disk that filled during the copy as
// "Input/output error". A partial copy is removed. Throws std::runtime_error naming `to`.
void copy_file_contents(const fs::path& from, const fs::path& to) {
  const auto fail = [&](const std::string& what, int err) {
    throw std::runtime_error(shown(to) + ": cannot copy " + shown(from) + " (" + what + std::strerror(err) + ")");
  };
  const int in = ::open(from.c_str(), O_RDONLY | O_CLOEXEC);
  if (in < 0) fail("reading it: ", errno);
  const int out = ::open(to.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out < 0) {
    const int err = errno;
    ::close(in);
    fail("", err);
  }
  int err = 0;
  bool reading = false;
  char buf[1 << 16];
  for (;;) {
    const ssize_t got = ::read(in, buf, sizeof buf);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) {
      err = errno, reading = true;
      break;
    }
    if (got == 0) break;
    for (ssize_t put = 0; put < got && err == 0;) {
      const ssize_t n = ::write(out, buf + put, static_cast<std::size_t>(got - put));
      if (n < 0 && errno != EINTR) err = errno;
      if (n > 0) put += n;
    }
    if (err != 0) break;
  }
  ::close(in);
  if (::close(out) != 0 && err == 0) err = errno;
  if (err != 0) {
    std::error_code ec;
    fs::remove(to, ec);
    fail(reading ? "reading it: " : "", err);
  }
}

// Hard-links `from` to `to`, or copies it where the file system cannot link (another device, no
// permission). Returns true for a link.
bool link_or_copy(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  fs::create_hard_link(from, to, ec);
  if (!ec) return true;
  copy_file_contents(from, to);
  return false;
}

// The output folder while the merge writes it: removed (its contents, and itself when the merge
// made it) unless the merge finishes.
class OutputFolder {
public:
  explicit OutputFolder(const fs::path& dir) : dir_(dir) {
    std::error_code ec;
    made_ = !fs::exists(fs::symlink_status(dir, ec));
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir))
      throw ConfigError("-o " + shown(dir) + ": cannot create the output folder (" +
                        (ec ? ec.message() : std::string("not a folder")) + ")");
  }
  ~OutputFolder() {
    if (kept_) return;
    lock_.reset();
    std::error_code ec;
    if (made_) {
      fs::remove_all(dir_, ec);
    } else {
      for (const fs::directory_entry& e : fs::directory_iterator(dir_, ec)) fs::remove_all(e.path(), ec);
    }
  }
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  void lock() {
    try {
      lock_.emplace(dir_);
    } catch (const std::runtime_error& e) {
      throw ConfigError(std::string("-o ") + e.what());
    }
  }
  void keep() { kept_ = true; }

private:
  fs::path dir_;
  bool made_ = false, kept_ = false;
  std::optional<FolderLock> lock_;
};

}  // namespace

MergeReport merge_sweeps(const MergeOptions& options) {
  MergeReport report;
  if (options.dirs.empty()) throw ConfigError("merge: give the folders of the shards (rotbeam merge DIR… -o OUT)");
  if (options.output.empty()) throw ConfigError("-o \"\": an empty path");

  // The output: a new folder, or an empty one (nothing of the user's is replaced).
  {
    std::error_code ec;
    const fs::file_status st = fs::status(options.output, ec);
    if (fs::exists(st)) {
      if (!fs::is_directory(st)) throw ConfigError("-o " + shown(options.output) + ": exists and is not a folder");
      if (!fs::is_empty(options.output, ec))
        throw ConfigError("-o " + shown(options.output) +
                          ": the folder exists and holds files; merge writes into a new (or empty) folder");
    }
  }

  // Every shard folder, read and checked against the first.
  std::vector<ShardFolder> shards;
  std::set<fs::path> seen;
  for (const fs::path& dir : options.dirs) {
    std::error_code ec;
    const fs::path real = fs::weakly_canonical(dir, ec);
    if (!seen.insert(ec ? dir : real).second) throw ConfigError(shown(dir) + ": given twice");
    shards.push_back(read_shard_folder(dir));
  }
  const ShardFolder& first = shards.front();
  const nlohmann::json& d0 = first.description;
  for (std::size_t k = 1; k < shards.size(); ++k) {
    const nlohmann::json& d = shards[k].description;
    const std::string a = shown(first.dir), b = shown(shards[k].dir);
    const std::string refuse = "merge: " + b + " is not a shard of the sweep in " + a + ": ";
    if (d.at("version") != d0.at("version"))
      throw ConfigError(refuse + "run by rotbeam " + d.at("version").get<std::string>() + ", " + a + " by " +
                        d0.at("version").get<std::string>());
    if (d.at("axes") != d0.at("axes"))
      throw ConfigError(refuse + "another grid (" + grid_text(d.at("axes")) + " against " + grid_text(d0.at("axes")) + ")");
    if (d.at("config") != d0.at("config") || d.at("varying_keys") != d0.at("varying_keys") ||
        d.at("brush") != d0.at("brush")) {
      std::string why = config_difference(d0.at("config"), d.at("config"), a, b);
      if (why.empty()) why = "the keys that vary between cases differ";
      throw ConfigError(refuse + "another configuration (" + why + ")");
    }
    if (shards[k].shard.count != first.shard.count)
      throw ConfigError(refuse + "it is shard " + std::to_string(shards[k].shard.index) + "/" +
                        std::to_string(shards[k].shard.count) + ", " + a + " shard " + std::to_string(first.shard.index) +
                        "/" + std::to_string(first.shard.count) + " (the same N for every shard)");
  }
  const int count = first.shard.count;
  std::vector<const ShardFolder*> by_index(static_cast<std::size_t>(count), nullptr);
  for (const ShardFolder& f : shards) {
    const ShardFolder*& slot = by_index[static_cast<std::size_t>(f.shard.index)];
    if (slot)
      throw ConfigError("merge: " + shown(slot->dir) + " and " + shown(f.dir) + " are both shard " +
                        std::to_string(f.shard.index) + "/" + std::to_string(count));
    slot = &f;
  }

  // The grid, and which shard holds each case.
  std::vector<SweepAxis> axes;
  for (const auto& a : d0.at("axes")) axes.push_back({a.at("key").get<std::string>(), a.at("values").get<std::vector<std::string>>()});
  const std::vector<SweepCase> cases = sweep_cases(axes);
  if (cases.size() != d0.at("cases").get<std::size_t>())
    throw ConfigError(shown(first.dir / "sweep.json") + ": its grid does not have the " +
                      std::to_string(d0.at("cases").get<std::size_t>()) + " cases it says");
  {
    std::string missing;
    for (int i = 0; i < count; ++i) {
      if (by_index[static_cast<std::size_t>(i)]) continue;
      std::vector<std::string> folders;
      for (std::size_t c = 0; c < cases.size(); ++c)
        if (Shard{i, count}.contains(c)) folders.push_back(cases[c].folder);
      if (folders.empty()) continue;  // a shard beyond the grid holds no case
      missing += (missing.empty() ? "" : "; ") + std::string("shard ") + std::to_string(i) + "/" +
                 std::to_string(count) + ": " + some_cases(folders);
    }
    if (!missing.empty())
      throw ConfigError("merge: cases missing, the folders of these shards were not given: " + missing +
                        "; nothing written");
  }

  // Every case: its shard's row (finished), and its folder complete and of this sweep.
  report.sweep.axes = axes;
  report.sweep.cases = cases;
  report.sweep.results.resize(cases.size());
  report.sweep.grid_cases = cases.size();
  report.sweep.brush = d0.at("brush").get<bool>();
  report.shard_count = count;
  for (const ShardFolder& f : shards)  // a shard beyond the grid's cases (shard 3/4 of 2 cases) holds none
    if (static_cast<std::size_t>(f.shard.index) < cases.size()) ++report.shards;
  std::string expected_header = [&] {
    SweepReport empty;
    empty.axes = axes;
    empty.brush = report.sweep.brush;
    std::string h = sweep_csv(empty);
    return h.substr(0, h.size() - 1);
  }();
  std::map<std::string, nlohmann::json> common;
  leaves(d0.at("config"), "", common);
  const std::set<std::string> varying(d0.at("varying_keys").begin(), d0.at("varying_keys").end());
  for (const ShardFolder& f : shards) {
    std::string header;
    for (const std::string& field : f.rows.at(0)) header += (header.empty() ? "" : ",") + detail::csv_field(field);
    if (header != expected_header)
      throw ConfigError(shown(f.dir / "sweep.csv") + ": its columns are not those of the sweep in its sweep.json "
                        "(written by another sweep: run this shard's sweep again to resume it)");
    std::vector<std::string> unfinished, absent;
    for (std::size_t c = 0; c < cases.size(); ++c) {
      if (!f.shard.contains(c)) {
        if (f.rows.count(static_cast<int>(c) + 1))
          throw ConfigError(shown(f.dir / "sweep.csv") + ": lists " + cases[c].folder + ", which is not in shard " +
                            std::to_string(f.shard.index) + "/" + std::to_string(count));
        continue;
      }
      const auto row = f.rows.find(static_cast<int>(c) + 1);
      if (row == f.rows.end()) {
        absent.push_back(cases[c].folder);
        continue;
      }
      const std::vector<std::string>& fields = row->second;
      for (std::size_t k = 0; k < axes.size(); ++k)
        if (fields[2 + k] != cases[c].values[k])
          throw ConfigError(shown(f.dir / "sweep.csv") + ": " + cases[c].folder + " has " + axes[k].key + " = " +
                            printable(fields[2 + k]) + ", the grid " + cases[c].values[k]);
      const std::string& status = fields[2 + axes.size()];
      SweepCaseResult& r = report.sweep.results[c];
      if (status == "done") {
        r.status = SweepStatus::done;
      } else if (status == "resumed") {
        r.status = SweepStatus::resumed;
        r.resumed = true;
      } else if (status == "failed") {
        r.status = SweepStatus::failed;
      } else {
        unfinished.push_back(cases[c].folder + " " + printable(status));
        continue;
      }
      r.message = fields.back();
      nlohmann::json summary;
      const fs::path folder = f.dir / cases[c].folder;
      if (!complete_run_folder(folder, &summary) || !summary.contains("config"))
        throw ConfigError(shown(folder) + ": incomplete (summary.json missing, or its files not at the sizes it lists); "
                          "run shard " + std::to_string(f.shard.index) + "/" + std::to_string(count) + "'s sweep again");
      std::map<std::string, nlohmann::json> keys;
      leaves(summary["config"], "", keys);
      for (const auto& [key, value] : keys)
        if (!varying.count(key) && (!common.count(key) || common.at(key) != value))
          throw ConfigError(shown(folder) + ": a run of another configuration (" + key + " = " + value.dump() +
                            ", the sweep's " + (common.count(key) ? common.at(key).dump() : std::string("not set")) + ")");
      r.summary = std::move(summary);
    }
    if (!absent.empty())
      throw ConfigError(shown(f.dir / "sweep.csv") + ": cases of shard " + std::to_string(f.shard.index) + "/" +
                        std::to_string(count) + " not listed: " + some_cases(absent) + "; run its sweep again");
    if (!unfinished.empty())
      throw ConfigError("merge: cases not finished in " + shown(f.dir) + ": " + some_cases(unfinished) + "; run shard " +
                        std::to_string(f.shard.index) + "/" + std::to_string(count) +
                        "'s sweep again (it resumes) and merge then; nothing written");
  }

  // Written: each case's files (its data files, then summary.json), sweep.json, then sweep.nc (the
  // hook) and sweep.csv last. A stop or a failure removes it all.
  OutputFolder out(options.output);
  out.lock();
  for (std::size_t c = 0; c < cases.size(); ++c) {
    if (options.stop && options.stop->stop_requested()) {
      report.interrupted = true;
      return report;  // `out` removes what was written
    }
    const ShardFolder& f = *by_index[c % static_cast<std::size_t>(count)];
    const fs::path from = f.dir / cases[c].folder, to = options.output / cases[c].folder;
    std::error_code ec;
    fs::create_directory(to, ec);
    if (ec) throw std::runtime_error(shown(to) + ": cannot create the folder (" + ec.message() + ")");
    const nlohmann::json& summary = report.sweep.results[c].summary;
    for (const auto& [name, entry] : summary.at("files").items()) {
      (void)entry;
      (link_or_copy(from / name, to / name) ? report.linked_files : report.copied_files) += 1;
    }
    (link_or_copy(from / "summary.json", to / "summary.json") ? report.linked_files : report.copied_files) += 1;
    if (options.on_case) options.on_case(c + 1, cases.size());
  }
  SweepPlan plan;
  plan.axes = axes;
  plan.cases = cases;
  plan.brush = report.sweep.brush;
  plan.common_config = d0.at("config");
  plan.varying_keys = d0.at("varying_keys").get<std::vector<std::string>>();
  nlohmann::json description = sweep_description(plan, Shard{});
  description["version"] = d0.at("version");
  write_file_atomically(options.output / "sweep.json", description.dump(2) + "\n");
  for (const SweepCaseResult& r : report.sweep.results) {
    report.sweep.ran += r.status == SweepStatus::done || (r.status == SweepStatus::failed && !r.resumed);
    report.sweep.resumed += r.status == SweepStatus::resumed;
    report.sweep.failed += r.status == SweepStatus::failed;
  }
  const std::string index = sweep_csv(report.sweep);
  if (options.before_index) {
    const fs::path tmp = options.output / ("sweep.csv.tmp." + std::to_string(::getpid()) + ".1");
    {
      std::ofstream t(tmp, std::ios::binary | std::ios::trunc);
      t << index;
      t.flush();
      if (!t) {  // the index for sweep.nc, on a full disk: sweep.nc names it, with the cause
        const int err = errno;
        throw std::runtime_error(shown(options.output / "sweep.nc") + ": cannot write (its index: " + std::strerror(err) + ")");
      }
    }
    options.before_index(tmp);
    std::error_code ec;
    fs::remove(tmp, ec);
  }
  if (options.stop && options.stop->stop_requested()) {
    report.interrupted = true;
    return report;
  }
  write_file_atomically(options.output / "sweep.csv", index);
  out.keep();
  return report;
}

}  // namespace rotbeam
