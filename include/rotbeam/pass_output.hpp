// Files of a pass (SPEC §7): history.csv, events.csv, summary.json, each written atomically.
#pragma once

#include "rotbeam/config.hpp"
#include "rotbeam/pass.hpp"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace rotbeam {

/// Column names of history.csv for n modes.
std::string history_header(int n);
std::string history_csv(const PassResult& result, int n);
std::string events_csv(const PassResult& result);
/// summary.json: the metrics, contact intervals, warnings, failure (or null) and the resolved config.
nlohmann::json summary_json(const PassResult& result, const Config& config);

/// Creates `dir` if needed and checks that files can be created in it (before a long run).
/// Throws std::runtime_error naming the path when it cannot.
void prepare_output_folder(const std::filesystem::path& dir);

/// Creates `dir` if needed and writes the three files atomically (summary.json last).
/// Throws std::runtime_error naming the path when it cannot.
void write_pass_outputs(const std::filesystem::path& dir, const PassResult& result, const Config& config);

}  // namespace rotbeam
