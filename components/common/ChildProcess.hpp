// A process started by the launcher or a test: its stdout and stderr go to a log file, it is asked
// to stop with a signal (SIGINT by default, as Ctrl-C would) and killed if it does not end within
// a grace period, and it never outlives its owner. Header-only so tests can use it without linking
// the process library.
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace uavslam::process {

class ChildProcess {
 public:
  // Starts argv[0] (a path) with argv. own_process_group: the child does not get the Ctrl-C of
  // our terminal, so its owner decides when and in which order it stops.
  ChildProcess(const std::vector<std::string>& argv, const std::string& log_path,
               bool own_process_group = false)
      : log_path_(log_path) {
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 2, log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0644);
    posix_spawn_file_actions_adddup2(&actions, 2, 1);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    if (own_process_group) {
      posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
      posix_spawnattr_setpgroup(&attributes, 0);
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    if (posix_spawn(&pid_, args[0], &actions, &attributes, args.data(), environ) != 0) pid_ = -1;
    posix_spawnattr_destroy(&attributes);
    posix_spawn_file_actions_destroy(&actions);
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess() { stop(std::chrono::seconds(5)); }

  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }

  // True while the process runs (reaps it once it has ended).
  bool running() {
    if (pid_ <= 0 || reaped_) return false;
    int status = 0;
    if (waitpid(pid_, &status, WNOHANG) == pid_) {
      reaped_ = true;
      exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      return false;
    }
    return true;
  }

  // Waits for the process to end by itself; false on timeout.
  bool wait(std::chrono::milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (running() && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return !running();
  }

  // `signal_number` (SIGINT by default), then SIGKILL after `grace`. Returns the exit code
  // (128 + the signal when a signal ended it, -1 if it never started).
  int stop(std::chrono::milliseconds grace, int signal_number = SIGINT) {
    if (running()) {
      kill(pid_, signal_number);
      if (!wait(grace)) {
        kill(pid_, SIGKILL);
        wait(std::chrono::seconds(5));
      }
    }
    return exit_code_;
  }

  // The exit code once it has ended: 0..255, or 128 + the signal that ended it; -1 before.
  int exit_code() const { return exit_code_; }

  const std::string& log_path() const { return log_path_; }
  std::string log() const {
    std::ifstream in(log_path_);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int exit_code_ = -1;
  std::string log_path_;
};

}  // namespace uavslam::process
