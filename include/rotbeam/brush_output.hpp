// Files of a brush (docs/brush.md): workpiece.csv (the force, torque and power on the workpiece
// over one revolution), profile.csv (the mean filament across the contact zone), filaments.csv
// (one row per filament) and summary.json, written last, with
// the sizes of the other two, so that a folder holds a summary only beside the complete files.
#pragma once

#include "rotbeam/brush_result.hpp"
#include "rotbeam/config.hpp"

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

namespace rotbeam {

/// workpiece.csv: one row per bin of output.bin_deg over the reference hub angle (−180°, 180°].
std::string workpiece_csv(const BrushResult& result, double omega);
/// profile.csv: the mean filament's force against its own angle (every bin of the revolution; the
/// contact zone is where it is not zero), with workpiece.csv's columns.
std::string profile_csv(const BrushResult& result, double omega);
/// filaments.csv: one row per filament: its place, parameters and steady-state means.
std::string filaments_csv(const BrushResult& result);

/// One harmonic of the workpiece's force over the revolution: its order h (per revolution), its
/// frequency h·Ω/2π [Hz] and the one-sided amplitudes 2|c_h| (the mean at h = 0) of the normal and
/// tangential force [N] and the hub torque [N m], from the bins' momentum placed at their centres.
struct SpectrumLine {
  int order = 0;
  double frequency_hz = 0, normal_force_n = 0, tangential_force_n = 0, hub_torque_n_m = 0;
};
std::vector<SpectrumLine> workpiece_spectrum(const BrushResult& result, double omega);

/// spectrum.csv: workpiece_spectrum up to half the bin count, with each order as a multiple of the
/// filament-passing frequency (orders over brush.filaments).
std::string spectrum_csv(const BrushResult& result, double omega, int filaments_around);

/// representatives.csv: the filaments the brush ran (its distinct filaments, or the population's
/// representatives), what each stands for and its steady state's means.
std::string representatives_csv(const BrushResult& result);
/// summary.json of a brush: "kind": "brush", the metrics, the filaments' counts, warnings, the
/// failure (or null) and the resolved configuration.
nlohmann::json brush_summary_json(const BrushResult& result, const Config& config);

class FolderLock;

/// The folder of a brush, held while it runs: made if needed and locked (one writer at a time);
/// refused when it holds a run or a sweep, or a folder under one of the brush's file names; an
/// older brush's summary.json and pictures are removed at once, so that the folder does not look
/// complete until commit() writes summary.json last. Throws std::runtime_error naming the path.
/// A brush's wear per revolution (docs/wear.md): every finished filament's, summed, as wear_profile.csv
/// and summary.json's `wear` report it.
WearReport brush_wear_report(const BrushResult& result, const Config& config);

class BrushFiles {
public:
  explicit BrushFiles(const std::filesystem::path& dir);
  ~BrushFiles();
  BrushFiles(const BrushFiles&) = delete;
  BrushFiles& operator=(const BrushFiles&) = delete;
  void commit(const BrushResult& result, const Config& config);

private:
  std::filesystem::path dir_;
  std::unique_ptr<FolderLock> lock_;
};

}  // namespace rotbeam
