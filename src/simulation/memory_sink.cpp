#include "memory_sink.hpp"

namespace rotbeam {

void MemorySink::piece(double t) {
  if (!window_.starts_piece(t)) return;
  starts_.emplace_back(result_.history.size(), result_.events.size());
  while (static_cast<int>(starts_.size()) > window_.complete_pieces_kept()) {
    const auto [rows, events] = starts_.front();
    starts_.pop_front();
    result_.history.erase(result_.history.begin(), result_.history.begin() + static_cast<std::ptrdiff_t>(rows));
    result_.events.erase(result_.events.begin(), result_.events.begin() + static_cast<std::ptrdiff_t>(events));
    for (auto& s : starts_) s.first -= rows, s.second -= events;
  }
}

void MemorySink::row(const HistoryRow& row) {
  piece(row.t);
  result_.history.push_back(row);
}

void MemorySink::event(const PassEvent& event) {
  piece(event.t);
  result_.events.push_back(event);
}

void MemorySink::revolution(const RevolutionRecord& record) {
  result_.revolutions.push_back(record);
  window_.revolution(record);
}

}  // namespace rotbeam
