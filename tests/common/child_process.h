#pragma once
// Starts the built `stillslam` binary as a child process the test can signal
// or kill while it runs, optionally with a file-size limit (a full disk
// without root), with a signal already pending when it starts, or on a
// terminal the test can close. stdout and stderr go to a pipe (or the
// terminal) drained by a thread, so neither the file-size limit nor a full
// pipe can block or cut them.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace stillslam::test {

struct ChildOptions {
  std::optional<rlim_t> file_size_limit;  // RLIMIT_FSIZE in bytes; SIGXFSZ is ignored, so writes fail with EFBIG
  int pending_signal = 0;                 // blocked and raised before exec: pending from the first instruction
  // stdin/stdout/stderr on a pseudo-terminal that is the child's controlling
  // terminal (its own session); hang_up() closes it as a closed terminal
  // window or ssh session does, and the kernel sends SIGHUP.
  bool terminal = false;
};

class ChildProcess {
 public:
  ChildProcess(const std::vector<std::string>& args, const ChildOptions& options = {}) {
    std::vector<std::string> all{STILLSLAM_BINARY};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    int fds[2] = {-1, -1};  // read end, write end (a pipe; the terminal's master side and -1)
    std::string terminal_name;
    if (options.terminal) {
      fds[0] = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
      if (fds[0] < 0 || ::grantpt(fds[0]) != 0 || ::unlockpt(fds[0]) != 0) return;
      terminal_name = ::ptsname(fds[0]);
    } else if (::pipe2(fds, O_CLOEXEC) != 0) {  // dup2 below clears O_CLOEXEC on stdout/stderr
      return;
    }
    pid_ = ::fork();
    if (pid_ == 0) {
      // Only async-signal-safe calls between fork and exec.
      if (options.terminal) {
        ::setsid();
        fds[1] = ::open(terminal_name.c_str(), O_RDWR);  // the session leader's first terminal: its controlling one
        ::dup2(fds[1], 0);
      }
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
    if (fds[1] >= 0) ::close(fds[1]);
    // Polls so that hang_up() can close a terminal this thread reads from.
    reader_ = std::thread([this, fd = fds[0]] {
      char buffer[4096];
      for (;;) {
        if (hang_up_) break;
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, 10) <= 0) continue;
        const ssize_t n = ::read(fd, buffer, sizeof(buffer));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;  // end of the pipe; EIO once a terminal's other side is closed
        output_.append(buffer, static_cast<std::size_t>(n));
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
  // Closes the terminal (ChildOptions::terminal): the child gets SIGHUP.
  void hang_up() {
    hang_up_ = true;
    if (reader_.joinable()) reader_.join();
  }
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
  std::atomic<bool> hang_up_{false};
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
