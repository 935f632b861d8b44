// The window of a run over many revolutions (output.history_revolutions = K): its history rows and
// events are kept for the last K revolutions only, the one under way included. The rows and events
// of revolution r all arrive before its record; the first row or event after the record's end starts
// the next piece, and of the pieces before it only the last K − 1 stay. One rule for every place the
// history is kept (the files, memory).
#pragma once

#include "rotbeam/pass.hpp"

namespace rotbeam {

class HistoryWindow {
public:
  /// `keep`: K, 0 for every revolution.
  explicit HistoryWindow(int keep) : keep_(keep) {}

  /// A revolution's record arrived: its rows and events are all in.
  void revolution(const RevolutionRecord& r) {
    if (keep_ > 0 && r.complete) {
      pending_ = true;
      after_t_ = r.t_end;
    }
  }
  /// Before a row or event at t: true when it starts a new piece (the caller closes the one under
  /// way and keeps only complete_pieces_kept() of those before it).
  bool starts_piece(double t) {
    if (!pending_ || !(t > after_t_)) return false;
    pending_ = false;
    return true;
  }
  /// The complete pieces kept beside the one being written (K − 1).
  int complete_pieces_kept() const { return keep_ - 1; }

private:
  int keep_;
  bool pending_ = false;
  double after_t_ = 0;  // the last complete revolution's end [s]
};

}  // namespace rotbeam
