#include "studies/process_pool.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

namespace softarm::studies {

ProcessPool::ProcessPool(int jobs, double timeout_s, std::filesystem::path scratch)
    : jobs_(std::max(1, jobs)), timeout_s_(timeout_s), scratch_(std::move(scratch)) {
  std::filesystem::create_directories(scratch_);
}

ProcessPool::~ProcessPool() {
  for (const Child& c : running_) {
    ::kill(c.pid, SIGKILL);
    ::waitpid(c.pid, nullptr, 0);
    std::filesystem::remove(output_file(c.pid));
  }
}

std::filesystem::path ProcessPool::output_file(pid_t pid) const {
  return scratch_ / ("point-" + std::to_string(pid) + ".json");
}

void ProcessPool::start(int task, const std::function<std::string()>& work) {
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(3);  // the parent died before prctl took effect
    int code = 0;
    try {
      const std::string text = work();
      const auto file = output_file(::getpid());
      const auto partial = file.string() + ".part";
      {
        std::ofstream out(partial, std::ios::binary);
        out << text;
        if (!out) code = 2;
      }
      if (code == 0) std::filesystem::rename(partial, file);  // whole or absent, never half
    } catch (...) {
      code = 1;
    }
    std::fflush(nullptr);
    ::_exit(code);  // no atexit handlers: they belong to the parent (MPI, open files)
  }
  running_.push_back({pid, task, std::chrono::steady_clock::now()});
}

std::vector<ProcessPool::Finished> ProcessPool::collect() {
  std::vector<Finished> done;
  const auto now = std::chrono::steady_clock::now();
  for (std::size_t i = 0; i < running_.size();) {
    Child& c = running_[i];
    const double seconds = std::chrono::duration<double>(now - c.started).count();
    int status = 0;
    pid_t r = ::waitpid(c.pid, &status, WNOHANG);
    Finished f;
    f.task = c.task;
    f.seconds = seconds;
    if (r == 0 && seconds > timeout_s_) {
      ::kill(c.pid, SIGKILL);
      ::waitpid(c.pid, &status, 0);
      f.failure = "stopped after " + std::to_string(static_cast<int>(timeout_s_)) +
                  " s (point_timeout_s): the solver did not finish; a finer load stepping or a coarser mesh may help";
      r = c.pid;
    } else if (r == 0) {
      ++i;
      continue;
    } else if (WIFSIGNALED(status)) {
      f.failure = "the solver process crashed (signal " + std::to_string(WTERMSIG(status)) + ", " +
                  strsignal(WTERMSIG(status)) + ")";
    } else if (WIFEXITED(status) && WEXITSTATUS(status) != 0) {
      f.failure = "the solver process exited with code " + std::to_string(WEXITSTATUS(status));
    } else {
      std::ifstream in(output_file(c.pid), std::ios::binary);
      std::stringstream text;
      text << in.rdbuf();
      f.output = text.str();
      f.ok = static_cast<bool>(in) || !f.output.empty();
      if (!f.ok) f.failure = "the solver process left no result";
    }
    std::filesystem::remove(output_file(c.pid));
    done.push_back(std::move(f));
    running_.erase(running_.begin() + static_cast<std::ptrdiff_t>(i));
  }
  return done;
}

}  // namespace softarm::studies
