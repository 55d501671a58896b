#include "fem/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <cstdlib>
#include <thread>
#include <vector>

namespace softarm::fem {
namespace {
int initial_thread_count() {
  if (const char* env = std::getenv("SOFTARM_THREADS")) {
    const int n = std::atoi(env);
    if (n > 0) return n;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}
int g_threads = initial_thread_count();
}  // namespace

int thread_count() { return g_threads; }
void set_thread_count(int n) { g_threads = std::max(1, n); }

void parallel_for(int n, const std::function<void(int, int, int)>& body) {
  // Below a few hundred items the thread start-up costs more than it saves.
  const int threads = std::min(g_threads, std::max(1, n / 256));
  if (threads <= 1) {
    body(0, n, 0);
    return;
  }
  std::vector<std::thread> pool;
  const int chunk = (n + threads - 1) / threads;
  for (int t = 1; t < threads; ++t) {
    const int b = t * chunk, e = std::min(n, b + chunk);
    if (b < e) pool.emplace_back(body, b, e, t);
  }
  body(0, std::min(n, chunk), 0);
  for (auto& th : pool) th.join();
}

void parallel_tasks(int n, const std::function<void(int)>& task, const TaskProgress& progress) {
  std::atomic<int> next{0};
  std::exception_ptr failure;
  int done = 0;
  std::mutex mutex;  // the first failure, the count of ended tasks and the calls to `progress`
  const auto worker = [&] {
    for (int i = next++; i < n; i = next++) {
      try {
        task(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (!failure) failure = std::current_exception();
      }
      if (progress) {
        const std::lock_guard<std::mutex> lock(mutex);
        progress(++done, n);
      }
    }
  };
  const int threads = std::min(g_threads, n);
  if (threads <= 1) {
    worker();  // on this thread, with its thread count (one task may use every thread)
  } else {
    const int saved = g_threads;
    g_threads = 1;
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
    g_threads = saved;
  }
  if (failure) std::rethrow_exception(failure);
}

}  // namespace softarm::fem
