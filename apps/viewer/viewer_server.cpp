#include "viewer/viewer_server.h"

#include <atomic>
#include <thread>

#include "stillslam/core/error.h"
#include "viewer/viewer_feed.h"
#include "viewer/web_files.h"
// After Eigen (through viewer_feed.h): a macro of httplib's system headers breaks
// Eigen's templates when seen first.
#include <httplib.h>

namespace stillslam::viewer {

namespace {

// What a page connection has sent so far.
struct Sent {
  std::uint64_t version = 0, state = 0, frame = 0, map = 0;
};

void send_json(httplib::Response& res, const nlohmann::json& body) {
  res.set_header("Cache-Control", "no-store");
  res.set_content(body.dump(), "application/json");
}

}  // namespace

bool is_loopback_host(const std::string& host) {
  return host == "localhost" || host == "::1" || host.rfind("127.", 0) == 0;
}

struct ViewerServer::Impl {
  ViewerOptions options;
  PauseGate* pause;
  ViewerFeed feed;
  httplib::Server server;
  std::atomic<bool> stopping{false};
  int port = 0;
  std::thread thread;

  Impl(const ViewerOptions& o, PauseGate* p) : options(o), pause(p), feed(o, p) {}

  void add_routes();
  // One call of the event stream's content provider: waits for a newer
  // update and writes the parts this connection has not sent.
  bool stream(Sent& sent, httplib::DataSink& sink);
};

bool ViewerServer::Impl::stream(Sent& sent, httplib::DataSink& sink) {
  const LatestValue<ViewerUpdate>::Read r = feed.updates().wait_newer(sent.version, std::chrono::milliseconds(500));
  if (stopping) return false;
  if (!r.value || r.version == sent.version) {
    static constexpr std::string_view kKeepAlive = ": keep-alive\n\n";
    return sink.write(kKeepAlive.data(), kKeepAlive.size());
  }
  const ViewerUpdate& u = *r.value;
  // Map first: the page draws the frame's camera in the newest map.
  const auto send = [&sink](const std::shared_ptr<const std::string>& part) {
    return !part || sink.write(part->data(), part->size());
  };
  if (u.map_seq != sent.map && !send(u.map)) return false;
  if (u.frame_seq != sent.frame && !send(u.frame)) return false;
  if (u.state_seq != sent.state && !send(u.state)) return false;
  sent = {r.version, u.state_seq, u.frame_seq, u.map_seq};
  return true;
}

void ViewerServer::Impl::add_routes() {
  server.Get("/api/state", [this](const httplib::Request&, httplib::Response& res) { send_json(res, feed.state()); });
  server.Get("/api/map", [this](const httplib::Request&, httplib::Response& res) { send_json(res, feed.atlas()); });
  server.Get("/api/frame.jpg", [this](const httplib::Request&, httplib::Response& res) {
    const std::vector<std::uint8_t> jpeg = feed.jpeg();
    if (jpeg.empty()) {
      res.status = 404;
      res.set_content("no frame yet", "text/plain");
      return;
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(reinterpret_cast<const char*>(jpeg.data()), jpeg.size(), "image/jpeg");
  });
  server.Get("/api/events", [this](const httplib::Request&, httplib::Response& res) {
    res.set_header("Cache-Control", "no-store");
    feed.client_connected();
    auto sent = std::make_shared<Sent>();
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, sent](std::size_t, httplib::DataSink& sink) { return stream(*sent, sink); },
        [this](bool) { feed.client_disconnected(); });
  });
  const auto control = [this](void (PauseGate::*action)()) {
    return [this, action](const httplib::Request&, httplib::Response& res) {
      if (pause == nullptr) {
        res.status = 404;
        res.set_content("this run cannot be paused", "text/plain");
        return;
      }
      (pause->*action)();
      send_json(res, feed.state());
    };
  };
  server.Post("/api/pause", control(&PauseGate::pause));
  server.Post("/api/step", control(&PauseGate::step));
  server.Post("/api/resume", control(&PauseGate::resume));
  server.Get(R"(/.*)", [](const httplib::Request& req, httplib::Response& res) {
    const WebFile* file = find_web_file(req.path);
    if (file == nullptr) {
      res.status = 404;
      res.set_content("not found: " + req.path, "text/plain");
      return;
    }
    res.set_content(file->data.data(), file->data.size(), std::string(file->content_type).c_str());
  });
}

ViewerServer::ViewerServer(const ViewerOptions& options, PauseGate* pause)
    : impl_(std::make_unique<Impl>(options, pause)) {
  options.check();
  impl_->add_routes();
  httplib::Server& server = impl_->server;
  // httplib's default adds SO_REUSEPORT: a second run on the same port would
  // then bind too and share the connections. SO_REUSEADDR only.
  server.set_socket_options([](socket_t sock) {
    const int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  });
  bool bound = false;
  if (options.port == 0) {
    impl_->port = server.bind_to_any_port(options.host);
    bound = impl_->port > 0;
  } else {
    bound = server.bind_to_port(options.host, options.port);
    impl_->port = options.port;
  }
  if (!bound) {
    throw Error("viewer: cannot listen on " + options.host + ":" + std::to_string(options.port) +
                " (the port is in use, or the host is not an address of this machine); pass another port with "
                "--viewer PORT (0: any free port) or Viewer.port, or another --viewer-host");
  }
  impl_->thread = std::thread([this] { impl_->server.listen_after_bind(); });
}

ViewerServer::~ViewerServer() {
  impl_->stopping = true;
  impl_->server.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
  impl_->feed.attach(nullptr);
}

int ViewerServer::port() const { return impl_->port; }

std::string ViewerServer::url() const {
  const std::string& host = impl_->options.host;
  const bool ipv6 = host.find(':') != std::string::npos;
  return "http://" + (ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(impl_->port) + "/";
}

void ViewerServer::attach(const Publisher* publisher) { impl_->feed.attach(publisher); }

void ViewerServer::set_groundtruth(const Trajectory& groundtruth) { impl_->feed.set_groundtruth(groundtruth); }

}  // namespace stillslam::viewer
