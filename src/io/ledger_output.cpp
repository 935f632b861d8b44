#include "rotbeam/ledger_output.hpp"

namespace rotbeam {

void put_ledger_terms(nlohmann::json& j, const LedgerValues& values) {
  for (const LedgerTermInfo& info : kLedgerTerms)
    if (info.report != LedgerReport::internal) j[info.key] = values[info.term];
}

nlohmann::json ledger_terms_json() {
  nlohmann::json terms = nlohmann::json::array();
  for (const LedgerTermInfo& info : kLedgerTerms)
    if (info.report == LedgerReport::energy)
      terms.push_back({{"key", info.key}, {"label", info.label}, {"description", info.description}});
  return terms;
}

}  // namespace rotbeam
