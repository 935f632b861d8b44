// Resident memory of this process (for the long-run checks) and the memory the machine can still give.
#pragma once

namespace rotbeam {

/// Current resident set size [MiB] from /proc/self/status (VmRSS); 0 if unavailable.
double resident_memory_mib();

/// Memory available for new allocations without swapping [bytes] from /proc/meminfo (MemAvailable);
/// 0 if unavailable.
double available_memory_bytes();

}  // namespace rotbeam
