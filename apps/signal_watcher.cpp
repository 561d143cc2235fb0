#include "signal_watcher.h"

#include <pthread.h>
#include <spdlog/spdlog.h>

namespace stillslam::apps {

SignalWatcher::SignalWatcher() {
  sigemptyset(&set_);
  for (int s : {SIGINT, SIGTERM, SIGHUP, SIGQUIT}) {
    // A signal the caller set to be ignored stays ignored: nohup (SIGHUP), a
    // shell's background job (SIGINT, SIGQUIT). Blocked, it would be queued
    // and taken despite SIG_IGN.
    struct sigaction current {};
    if (sigaction(s, nullptr, &current) == 0 && current.sa_handler == SIG_IGN) continue;
    sigaddset(&set_, s);
  }
  pthread_sigmask(SIG_BLOCK, &set_, nullptr);
  // A closed pipe on stdout or stderr (the reader went with the session) is
  // an error on that write, not a reason to die before the outputs are written.
  ::signal(SIGPIPE, SIG_IGN);
  // A signal already pending (sent while the process started) is taken here,
  // before the command does anything else.
  const timespec now{0, 0};
  take(sigtimedwait(&set_, nullptr, &now));
  thread_ = std::thread([this] {
    const timespec timeout{0, 100'000'000};
    while (!done_) take(sigtimedwait(&set_, nullptr, &timeout));
  });
}

void SignalWatcher::take(int s) {
  if (s <= 0) return;
  int none = 0;
  if (signal_.compare_exchange_strong(none, s)) {
    stop_ = true;
    spdlog::warn("{}: stopping before the next frame and writing all outputs", signal_name(s));
  } else {
    spdlog::warn("{}: already stopping, the outputs are being written", signal_name(s));
  }
}

SignalWatcher::~SignalWatcher() {
  done_ = true;
  thread_.join();
}

std::string signal_name(int signal) {
  switch (signal) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    case SIGHUP: return "SIGHUP";
    case SIGQUIT: return "SIGQUIT";
    default: return "signal " + std::to_string(signal);
  }
}

}  // namespace stillslam::apps
