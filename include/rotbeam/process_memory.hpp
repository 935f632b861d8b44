// Resident memory of this process (for the long-run checks).
#pragma once

namespace rotbeam {

/// Current resident set size [MiB] from /proc/self/status (VmRSS); 0 if unavailable.
double resident_memory_mib();

}  // namespace rotbeam
