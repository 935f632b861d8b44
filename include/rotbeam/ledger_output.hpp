// The ledger (ledger.hpp) in the output files: every reported term under its key, from the one table.
#pragma once

#include "rotbeam/ledger.hpp"

#include <nlohmann/json.hpp>
#include <string>

namespace rotbeam {

/// Every reported term of `values` (the energy terms and the momenta) under its key, into the object j.
void put_ledger_terms(nlohmann::json& j, const LedgerValues& values);

/// The energy terms as summary.json lists them under "ledger_terms": key, label and description of
/// each, in the table's order (what the pictures of the ledger iterate).
nlohmann::json ledger_terms_json();

}  // namespace rotbeam
