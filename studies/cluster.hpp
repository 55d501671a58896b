#pragma once
// The machines a study runs on. Started by `mpirun -np N softarm study …`, the
// N processes (ranks) share the points; rank 0 keeps the results file, the
// others send it each result as it finishes, so the file grows the same way as
// in a serial run and a restarted study resumes the same way. Started without
// mpirun, softarm does not initialise MPI at all (size 1, rank 0).
//
// Open MPI (Debian libopenmpi-dev): the standard way to spread independent
// solves over machines; the alternative (ssh + shared files) would be code of
// ours with none of MPI's launch, placement and failure handling.
#include <optional>
#include <string>
#include <vector>

namespace softarm::studies {

class Cluster {
 public:
  /// Initialises MPI when this process was launched by mpirun (once per process).
  static Cluster& instance();
  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  /// Whether softarm was built with MPI.
  static bool available();

  /// Rank 0's list, given to every rank.
  std::vector<int> broadcast(std::vector<int> values) const;
  /// Rank 0's string (an error message or ""), given to every rank.
  std::string broadcast(std::string text) const;
  /// As broadcast(std::string), but the ranks waiting for rank 0 sleep (every rank calls this one,
  /// not the other, for the same message).
  std::string broadcast_idle(std::string text) const;
  /// Every rank's `mine`, in rank order, given to every rank (collective: every rank calls it;
  /// those waiting for the others sleep).
  std::vector<std::string> all_gather(const std::string& mine) const;
  /// Non-root ranks: one finished result, and finally "done".
  void send_result(const std::string& line) const;
  void send_done() const;
  /// Rank 0: a result or a done message from another rank, if one has arrived (never blocks).
  struct Message {
    bool done = false;
    std::string line;
  };
  std::optional<Message> poll() const;
  void barrier() const;

  ~Cluster();

 private:
  Cluster();
  int rank_ = 0, size_ = 1;
  bool initialised_ = false;
};

}  // namespace softarm::studies
