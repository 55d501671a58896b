#include "studies/cluster.hpp"

#include <cstdlib>

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
