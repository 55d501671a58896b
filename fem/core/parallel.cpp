#include "fem/core/parallel.hpp"

#include <algorithm>
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

}  // namespace softarm::fem
