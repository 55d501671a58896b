#include "fem/core/parallel.hpp"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdlib>
#include <exception>
#include <memory>
#include <mutex>
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

// Where a task of parallel_tasks offers the rest of a visit (visit_in_order_with_help) to the
// workers whose tasks have run out. A chunk is claimed once, by compare-and-swap: the visiting
// thread from the front, lenders from the back; the visitor waits for a lent chunk to be done.
constexpr int kChunk = 8;
enum ChunkState : int { kFree = 0, kOwned = 1, kLending = 2, kLent = 3 };

struct HelpJob {
  int n = 0, chunks = 0;
  const std::function<void(int)>* lend = nullptr;
  std::unique_ptr<std::atomic<int>[]> state;
  std::atomic<bool> stop{false};
  int lenders_inside = 0;  // under the board's mutex
  std::exception_ptr failure;  // the first exception a lender threw (under the board's mutex)
  int failed_at = -1;          // the item that threw it (written before its chunk is marked lent)
};

struct HelpBoard {
  std::mutex mutex;
  std::condition_variable changed;  // a job posted or withdrawn, a lender left, the tasks ended
  std::vector<HelpJob*> jobs;
  std::atomic<int> idle{0};  // workers waiting to lend
  bool tasks_running = false;  // one parallel_tasks with several threads at a time (g_threads is 1 inside)
};
HelpBoard g_board;
std::atomic<long> g_lent_items{0};

// Lends chunks of `job` from the back until it meets the visitor's (everything before is its).
void lend_chunks(HelpJob& job) {
  for (int c = job.chunks - 1; c >= 0 && !job.stop.load(std::memory_order_relaxed); --c) {
    int expected = kFree;
    if (!job.state[c].compare_exchange_strong(expected, kLending)) {
      if (expected == kOwned) return;
      continue;  // another lender's
    }
    const int end = std::min(job.n, (c + 1) * kChunk);
    g_lent_items += end - c * kChunk;
    for (int i = c * kChunk; i < end; ++i) {
      try {
        (*job.lend)(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(g_board.mutex);
        job.failure = std::current_exception();
        job.failed_at = i;
        job.stop = true;
        break;
      }
    }
    job.state[c].store(kLent, std::memory_order_release);
  }
}

// A worker of parallel_tasks with no task left: lends to the running tasks until they end.
void lend_until_tasks_end() {
  std::unique_lock<std::mutex> lock(g_board.mutex);
  ++g_board.idle;
  for (;;) {
    g_board.changed.wait(lock, [] { return !g_board.jobs.empty() || !g_board.tasks_running; });
    if (!g_board.tasks_running) break;
    HelpJob* job = g_board.jobs.front();
    // One pass over a job: whatever this worker cannot take is the visitor's already.
    g_board.jobs.erase(g_board.jobs.begin());
    ++job->lenders_inside;
    --g_board.idle;
    lock.unlock();
    lend_chunks(*job);
    lock.lock();
    ++g_board.idle;
    --job->lenders_inside;
    g_board.changed.notify_all();
  }
  --g_board.idle;
}
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
  std::atomic<int> unfinished{n};
  const int threads = std::min(g_threads, n);
  // With several threads, a worker whose tasks have run out lends to the tasks still running. (A
  // parallel_tasks inside a task has one thread, g_threads being 1 there: it neither lends nor
  // touches the board.)
  const bool lending = threads > 1;
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
      if (--unfinished == 0 && lending) {
        const std::lock_guard<std::mutex> lock(g_board.mutex);
        g_board.tasks_running = false;
        g_board.changed.notify_all();
      }
    }
    if (lending) lend_until_tasks_end();
  };
  if (!lending) {
    worker();  // on this thread, with its thread count (one task may use every thread)
  } else {
    const int saved = g_threads;
    g_threads = 1;
    {
      const std::lock_guard<std::mutex> lock(g_board.mutex);
      g_board.tasks_running = true;
    }
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& th : pool) th.join();
    g_threads = saved;
  }
  if (failure) std::rethrow_exception(failure);
}

long lent_items() { return g_lent_items.load(); }

void visit_in_order_with_help(int n, const std::function<bool(int)>& own, const std::function<void(int)>& lend,
                              const std::function<bool(int)>& take) {
  // Outside parallel_tasks nobody lends; inside, only a worker waiting now may (a read that races
  // is harmless: it decides the speed, not the result).
  if (n < 2 * kChunk || g_board.idle.load(std::memory_order_relaxed) == 0) {
    for (int i = 0; i < n; ++i)
      if (!own(i)) return;
    return;
  }
  HelpJob job;
  job.n = n;
  job.chunks = (n + kChunk - 1) / kChunk;
  job.lend = &lend;
  job.state = std::make_unique<std::atomic<int>[]>(job.chunks);
  for (int c = 0; c < job.chunks; ++c) job.state[c].store(kFree, std::memory_order_relaxed);
  {
    const std::lock_guard<std::mutex> lock(g_board.mutex);
    g_board.jobs.push_back(&job);
  }
  g_board.changed.notify_all();
  // However the visit ends (own or take may throw too), the job leaves the board and no lender is
  // inside it before it goes out of scope.
  struct Withdraw {
    HelpJob& job;
    ~Withdraw() {
      job.stop = true;
      std::unique_lock<std::mutex> lock(g_board.mutex);
      std::erase(g_board.jobs, &job);
      g_board.changed.wait(lock, [this] { return job.lenders_inside == 0; });
    }
  };
  bool reached_failure = false;  // a serial visit would have met the item that threw
  {
    const Withdraw withdraw{job};
    bool stopped = false;
    for (int c = 0; c < job.chunks && !stopped; ++c) {
      const int end = std::min(n, (c + 1) * kChunk);
      int expected = kFree;
      if (job.state[c].compare_exchange_strong(expected, kOwned)) {
        for (int i = c * kChunk; i < end && !stopped; ++i) stopped = !own(i);
        continue;
      }
      while (job.state[c].load(std::memory_order_acquire) != kLent) std::this_thread::yield();
      // A lender that threw did so in the first lent chunk this visit meets (every chunk before is
      // this thread's, and the lender stops at its failure): take the items before the one that
      // threw, then throw where a visit alone would have.
      const int last = job.stop.load() ? job.failed_at : end;
      for (int i = c * kChunk; i < last && !stopped; ++i) stopped = !take(i);
      if (!stopped && last < end) {
        reached_failure = true;
        break;
      }
    }
  }
  if (reached_failure && job.failure) std::rethrow_exception(job.failure);
}

}  // namespace softarm::fem
