// A pass kept in memory (PassResult::history, events, revolutions) for a run without a sink of its
// own, its history windowed as files are (history_window.hpp).
#pragma once

#include "rotbeam/history_window.hpp"
#include "rotbeam/pass.hpp"

#include <deque>

namespace rotbeam {

class MemorySink final : public PassSink {
public:
  MemorySink(PassResult& result, int history_revolutions) : result_(result), window_(history_revolutions) {}
  void row(const HistoryRow& row) override;
  void event(const PassEvent& event) override;
  void revolution(const RevolutionRecord& record) override;

private:
  // A new piece starts at a row or event at t: the oldest pieces beyond the window are dropped.
  void piece(double t);

  PassResult& result_;
  HistoryWindow window_;
  std::deque<std::pair<std::size_t, std::size_t>> starts_;  // rows and events before each kept piece's end
};

}  // namespace rotbeam
