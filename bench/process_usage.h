// CPU time and peak resident memory of the benchmark process (getrusage), shared by the
// drivers in bench/.
#pragma once

#include <sys/resource.h>

namespace delmesh::bench {

/// User + system CPU seconds consumed so far by this process.
inline double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

/// Peak resident set size of this process so far, in bytes.
inline double peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0;
}

/// Peak resident set size in MiB.
inline double peak_rss_mb() { return peak_rss_bytes() / 1048576.0; }

}  // namespace delmesh::bench
