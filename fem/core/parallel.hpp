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

/// Runs task(i) for every i in [0, n), up to thread_count() of them at once, each on one thread
/// (thread_count() is 1 inside a task, so its assembly and BLAS stay serial): for independent
/// solves too small to keep several threads busy (ring-pitch cells: ~40 % of their time on two
/// threads is the kernel's). The first exception a task throws is rethrown after all have ended.
/// `progress`, if given, is told after each task ends (one call at a time, in the order they end)
/// how many of the n have ended: what a progress line with an ETA needs.
using TaskProgress = std::function<void(int done, int total)>;
void parallel_tasks(int n, const std::function<void(int i)>& task, const TaskProgress& progress = {});

}  // namespace softarm::fem
