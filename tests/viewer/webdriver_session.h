#pragma once
// A headless Chromium driven through Debian's chromedriver (W3C WebDriver over
// HTTP): the live page keeps an event stream open, so `chromium --dump-dom`
// never returns; WebDriver reads the DOM of the running page instead.
#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <httplib.h>

namespace stillslam::test {

inline constexpr const char* kChromium = "/usr/bin/chromium";
inline constexpr const char* kChromedriver = "/usr/bin/chromedriver";

// A TCP port nobody listens on right now (the kernel's choice).
inline int free_port() {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof(a);
  int port = 0;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) == 0) {
    port = ntohs(a.sin_port);
  }
  ::close(fd);
  return port;
}

inline std::string decode_base64(const std::string& text) {
  std::string out;
  unsigned value = 0;
  int bits = 0;
  for (char c : text) {
    int d = -1;
    if (c >= 'A' && c <= 'Z') d = c - 'A';
    else if (c >= 'a' && c <= 'z') d = c - 'a' + 26;
    else if (c >= '0' && c <= '9') d = c - '0' + 52;
    else if (c == '+') d = 62;
    else if (c == '/') d = 63;
    if (d < 0) continue;  // padding
    value = (value << 6) | static_cast<unsigned>(d);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out += static_cast<char>((value >> bits) & 0xff);
    }
  }
  return out;
}

class WebDriverSession {
 public:
  // Starts chromedriver and a headless Chromium session; ok() says whether both came up.
  explicit WebDriverSession(const std::filesystem::path& profile_dir) {
    port_ = free_port();
    driver_ = ::fork();
    if (driver_ == 0) {
      const std::string port = "--port=" + std::to_string(port_);
      const int quiet = ::open("/dev/null", O_WRONLY);  // its start-up banner
      ::dup2(quiet, 1);
      ::execl(kChromedriver, kChromedriver, port.c_str(), "--log-level=SEVERE", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    client_ = std::make_unique<httplib::Client>("127.0.0.1", port_);
    client_->set_read_timeout(60, 0);
    const nlohmann::json args = {"--headless",           "--disable-gpu",
                                 "--no-sandbox",         "--no-first-run",
                                 "--use-gl=swiftshader", "--enable-unsafe-swiftshader",
                                 "--hide-scrollbars",    "--window-size=1500,900",
                                 "--user-data-dir=" + profile_dir.string()};
    const nlohmann::json caps = {
        {"capabilities", {{"alwaysMatch", {{"goog:chromeOptions", {{"binary", kChromium}, {"args", args}}}}}}}};
    for (int i = 0; i < 100 && session_.empty(); ++i) {
      if (auto res = client_->Post("/session", caps.dump(), "application/json")) {
        const nlohmann::json r = nlohmann::json::parse(res->body, nullptr, false);
        if (r.contains("value") && r["value"].contains("sessionId")) session_ = r["value"]["sessionId"];
        else error_ = res->body;
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));  // chromedriver still starting
    }
  }
  ~WebDriverSession() {
    if (!session_.empty()) client_->Delete("/session/" + session_);
    if (driver_ > 0) {
      ::kill(driver_, SIGTERM);
      ::waitpid(driver_, nullptr, 0);
    }
  }
  WebDriverSession(const WebDriverSession&) = delete;
  WebDriverSession& operator=(const WebDriverSession&) = delete;

  bool ok() const { return !session_.empty(); }
  const std::string& error() const { return error_; }

  bool open(const std::string& url) { return command("/url", {{"url", url}}).has_value(); }
  // The value of a script run in the page (`return ...;`).
  nlohmann::json run(const std::string& script) {
    auto v = command("/execute/sync", {{"script", script}, {"args", nlohmann::json::array()}});
    return v ? *v : nlohmann::json();
  }
  // A PNG of the window.
  std::string screenshot_png() {
    auto res = client_->Get("/session/" + session_ + "/screenshot");
    if (!res) return "";
    const nlohmann::json r = nlohmann::json::parse(res->body, nullptr, false);
    return r.contains("value") && r["value"].is_string() ? decode_base64(r["value"].get<std::string>()) : "";
  }

 private:
  std::optional<nlohmann::json> command(const std::string& path, const nlohmann::json& body) {
    auto res = client_->Post("/session/" + session_ + path, body.dump(), "application/json");
    if (!res || res->status != 200) return std::nullopt;
    const nlohmann::json r = nlohmann::json::parse(res->body, nullptr, false);
    return r.contains("value") ? std::optional<nlohmann::json>(r["value"]) : std::nullopt;
  }

  int port_ = 0;
  pid_t driver_ = -1;
  std::unique_ptr<httplib::Client> client_;
  std::string session_, error_;
};

}  // namespace stillslam::test
