#pragma once
// Starts the built `stillslam` binary as a child process the test can signal
// or kill while it runs, optionally with a file-size limit (a full disk
// without root) or with a signal already pending when it starts. stdout and
// stderr go to a pipe drained by a thread, so neither the file-size limit nor
// a full pipe can block or cut them.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace stillslam::test {

struct ChildOptions {
  std::optional<rlim_t> file_size_limit;  // RLIMIT_FSIZE in bytes; SIGXFSZ is ignored, so writes fail with EFBIG
  int pending_signal = 0;                 // blocked and raised before exec: pending from the first instruction
};

class ChildProcess {
 public:
  ChildProcess(const std::vector<std::string>& args, const ChildOptions& options = {}) {
    std::vector<std::string> all{STILLSLAM_BINARY};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return;  // dup2 below clears O_CLOEXEC on stdout/stderr
    pid_ = ::fork();
    if (pid_ == 0) {
      // Only async-signal-safe calls between fork and exec.
      ::dup2(fds[1], 1);
      ::dup2(fds[1], 2);
      ::close(fds[0]);
      ::close(fds[1]);
      if (options.file_size_limit) {
        ::signal(SIGXFSZ, SIG_IGN);
        const rlimit limit{*options.file_size_limit, *options.file_size_limit};
        ::setrlimit(RLIMIT_FSIZE, &limit);
      }
      if (options.pending_signal != 0) {
        sigset_t set;
        sigemptyset(&set);
        sigaddset(&set, options.pending_signal);
        ::sigprocmask(SIG_BLOCK, &set, nullptr);
        ::kill(::getpid(), options.pending_signal);
      }
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(fds[1]);
    reader_ = std::thread([this, fd = fds[0]] {
      char buffer[4096];
      ssize_t n = 0;
      while ((n = ::read(fd, buffer, sizeof(buffer))) > 0 || (n < 0 && errno == EINTR)) {
        if (n > 0) output_.append(buffer, static_cast<std::size_t>(n));
      }
      ::close(fd);
    });
  }
  ~ChildProcess() {
    if (pid_ > 0 && !waited_) {
      ::kill(pid_, SIGKILL);
      wait();
    }
    if (reader_.joinable()) reader_.join();
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  void send(int signal) const { ::kill(pid_, signal); }

  // True once the child has exited (then wait() returns at once).
  bool exited() {
    if (!waited_ && ::waitpid(pid_, &status_, WNOHANG) == pid_) {
      waited_ = true;
      if (reader_.joinable()) reader_.join();
    }
    return waited_;
  }

  // Waits for the exit; the raw waitpid status.
  int wait() {
    if (!waited_) {
      while (::waitpid(pid_, &status_, 0) < 0 && errno == EINTR) {
      }
      waited_ = true;
      if (reader_.joinable()) reader_.join();
    }
    return status_;
  }
  // Everything the child wrote on stdout and stderr (after wait()).
  const std::string& output() const { return output_; }

 private:
  pid_t pid_ = -1;
  int status_ = -1;
  bool waited_ = false;
  std::thread reader_;
  std::string output_;
};

// "exit 130" / "killed by signal 2" for test messages.
inline std::string describe_status(int status) {
  if (WIFEXITED(status)) return "exit " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "status " + std::to_string(status);
}

}  // namespace stillslam::test
