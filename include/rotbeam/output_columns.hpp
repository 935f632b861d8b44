// The columns of every CSV file a run or a brush writes (docs/cli.md, docs/brush.md), declared once:
// name, unit, kind and meaning. The writers take their headers from here (pass_output.cpp,
// brush_output.cpp), the Python module's one reader its checks (python/rotbeam/_csv.py, through
// rotbeam._core.output_columns), and a test checks that the documentation names every column.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace rotbeam {

enum class ColumnKind {
  number,           // a number on every row
  optional_number,  // a number, or empty where it is not defined (NaN in Python)
  integer,
  boolean,          // true or false
  word,             // one of `words`
  text,             // free text (CSV-quoted)
};

struct OutputColumn {
  std::string name;  // "t_s"; a name holding "{i}" is one column per mode, i = 1 … n ("q{i}_m")
  std::string unit;  // "s", "N s", "1" (a count or a ratio), "" (words and text)
  ColumnKind kind = ColumnKind::number;
  std::string description;
  std::vector<std::string> words;  // the words a `word` column holds
};

struct OutputFile {
  std::string name;  // "history.csv"
  std::vector<OutputColumn> columns;
};

/// Every CSV file of a run (history.csv, events.csv, force_bins.csv, revolutions.csv) and of a brush
/// (workpiece.csv, profile.csv, filaments.csv), in that order.
const std::vector<OutputFile>& output_files();

/// The file named `name`; throws std::invalid_argument for another name.
const OutputFile& output_file(std::string_view name);

/// The file's header line (without its newline) for n modes.
std::string csv_header(const OutputFile& file, int modes);

/// "free", "stick", …: the words of the filaments.csv `status` column.
const std::vector<std::string>& filament_status_words();

}  // namespace rotbeam
