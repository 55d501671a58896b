#include "studies/cluster.hpp"

#include <cstdlib>

#include <chrono>
#include <thread>

#ifdef SOFTARM_WITH_MPI
#include <mpi.h>
#endif

namespace softarm::studies {

namespace {
#ifdef SOFTARM_WITH_MPI
constexpr int kResultTag = 1, kDoneTag = 2;

/// Rank 0's contents of a resizable container of `type` elements, given to every rank.
template <class Container>
void broadcast_from_root(Container& values, MPI_Datatype type) {
  int n = static_cast<int>(values.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD);
  values.resize(n);
  if (n) MPI_Bcast(values.data(), n, type, 0, MPI_COMM_WORLD);
}
#endif

#ifdef SOFTARM_WITH_MPI
/// Waits for `request` asleep, a few milliseconds at a time: a rank waiting on the others (a design's
/// rank 0 searching, a rank whose cells finished first) leaves its core to them instead of spinning.
void wait_idle(MPI_Request& request) {
  int done = 0;
  for (;;) {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}
#endif

/// Launched by mpirun (Open MPI, or a PMI-based launcher)?
bool launched_by_mpirun() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK");
}
}  // namespace

bool Cluster::available() {
#ifdef SOFTARM_WITH_MPI
  return true;
#else
  return false;
#endif
}

Cluster& Cluster::instance() {
  static Cluster cluster;
  return cluster;
}

Cluster::Cluster() {
#ifdef SOFTARM_WITH_MPI
  if (!launched_by_mpirun()) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  initialised_ = true;
#endif
}

Cluster::~Cluster() {
#ifdef SOFTARM_WITH_MPI
  if (initialised_) MPI_Finalize();
#endif
}

std::vector<int> Cluster::broadcast(std::vector<int> values) const {
#ifdef SOFTARM_WITH_MPI
  if (initialised_) broadcast_from_root(values, MPI_INT);
#endif
  return values;
}

std::string Cluster::broadcast(std::string text) const {
#ifdef SOFTARM_WITH_MPI
  if (initialised_) broadcast_from_root(text, MPI_CHAR);
#endif
  return text;
}

std::vector<std::string> Cluster::all_gather(const std::string& mine) const {
  std::vector<std::string> all(static_cast<std::size_t>(size_));
#ifdef SOFTARM_WITH_MPI
  if (initialised_) {
    int length = static_cast<int>(mine.size());
    std::vector<int> lengths(size_), offsets(size_, 0);
    MPI_Request request;
    MPI_Iallgather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, MPI_COMM_WORLD, &request);
    wait_idle(request);
    for (int r = 1; r < size_; ++r) offsets[r] = offsets[r - 1] + lengths[r - 1];
    std::string joined(static_cast<std::size_t>(offsets.back() + lengths.back()), '\0');
    MPI_Allgatherv(mine.data(), length, MPI_CHAR, joined.data(), lengths.data(), offsets.data(), MPI_CHAR,
                   MPI_COMM_WORLD);
    for (int r = 0; r < size_; ++r) all[r] = joined.substr(offsets[r], lengths[r]);
    return all;
  }
#endif
  all.front() = mine;
  return all;
}

std::string Cluster::broadcast_idle(std::string text) const {
#ifdef SOFTARM_WITH_MPI
  if (initialised_) {
    int n = static_cast<int>(text.size());
    MPI_Request request;
    MPI_Ibcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
    wait_idle(request);
    text.resize(static_cast<std::size_t>(n));
    if (n) MPI_Bcast(text.data(), n, MPI_CHAR, 0, MPI_COMM_WORLD);
  }
#endif
  return text;
}

void Cluster::send_result(const std::string& line) const {
#ifdef SOFTARM_WITH_MPI
  MPI_Send(line.data(), static_cast<int>(line.size()), MPI_CHAR, 0, kResultTag, MPI_COMM_WORLD);
#else
  (void)line;
#endif
}

void Cluster::send_done() const {
#ifdef SOFTARM_WITH_MPI
  char nothing = 0;
  MPI_Send(&nothing, 0, MPI_CHAR, 0, kDoneTag, MPI_COMM_WORLD);
#endif
}

std::optional<Cluster::Message> Cluster::poll() const {
#ifdef SOFTARM_WITH_MPI
  if (!initialised_) return std::nullopt;
  int flag = 0;
  MPI_Status status;
  MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
  if (!flag) return std::nullopt;
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  Message m;
  m.line.resize(count);
  MPI_Recv(m.line.data(), count, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  m.done = status.MPI_TAG == kDoneTag;
  return m;
#else
  return std::nullopt;
#endif
}

void Cluster::barrier() const {
#ifdef SOFTARM_WITH_MPI
  if (initialised_) MPI_Barrier(MPI_COMM_WORLD);
#endif
}

}  // namespace softarm::studies
