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

/// Visits i = 0, 1, …, n − 1 in order on this thread: own(i) where this thread computes i itself,
/// take(i) where another thread has run lend(i) before, which leaves i's result where take(i) reads
/// it. Only threads of parallel_tasks whose tasks have run out lend (so inside a task, once fewer
/// tasks than threads are left: a cell rod's slowest cell), working from the end while this thread
/// works from the start, in chunks; with none idle, or outside parallel_tasks, every i is own(i).
/// Where i's result depends on i alone and own and take combine the results in order, the run gives
/// the same bits whoever computed what. own or take returning false ends the visit there (after any
/// lending thread has left); an exception thrown by lend is rethrown here where the visit reaches
/// the item that threw (a visit that stops before it returns as a visit alone would).
void visit_in_order_with_help(int n, const std::function<bool(int i)>& own, const std::function<void(int i)>& lend,
                              const std::function<bool(int i)>& take);

/// How many items idle threads have lent so far in this process (what a test reads to know that a
/// visit was helped).
long lent_items();

}  // namespace softarm::fem
