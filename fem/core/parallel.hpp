#pragma once
// Minimal static-partition parallel loop for element assembly. The number of
// threads is global (CLI flag --threads, env SOFTARM_THREADS, default: all
// hardware threads); 1 means strictly serial.
#include <functional>

namespace softarm::fem {

int thread_count();
void set_thread_count(int n);

/// Calls body(begin, end, thread) on contiguous chunks of [0, n), one per thread.
void parallel_for(int n, const std::function<void(int begin, int end, int thread)>& body);

}  // namespace softarm::fem
