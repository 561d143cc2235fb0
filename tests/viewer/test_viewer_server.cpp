// The viewer's HTTP endpoints against a publisher fed by the test (no SLAM):
// page, vendored three.js, counters, JPEG, event stream, pause / step / resume.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "stillslam/core/error.h"
#include "viewer/viewer_server.h"
// After Eigen: a macro of httplib's dependencies breaks Eigen's templates when seen first.
#include <httplib.h>

namespace stillslam::viewer {
namespace {

std::shared_ptr<FrameSnapshot> frame_snapshot(std::size_t index) {
  auto f = std::make_shared<FrameSnapshot>();
  f->index = index;
  f->frame_id = index;
  f->state = "ok";
  f->image = cv::Mat(120, 160, CV_8UC3, cv::Scalar(40, 80, 120));
  cv::circle(f->image, {80, 60}, 20, cv::Scalar(255, 255, 255), cv::FILLED);
  f->keypoints = {{10.f, 10.f}, {20.f, 20.f}};
  f->tracked = {true, false};
  f->removed_keypoints = {{80.f, 60.f}, {82.f, 61.f}, {79.f, 58.f}};
  FrameSnapshot::Instance person;
  person.class_name = "person";
  person.class_id = 0;
  person.score = 0.9f;
  person.box = cv::Rect(60, 40, 40, 40);
  person.outline = {{60, 60}, {80, 40}, {100, 60}, {80, 80}};
  person.dynamic = true;
  f->instances = {person};
  return f;
}

std::shared_ptr<AtlasSnapshot> atlas_snapshot() {
  auto a = std::make_shared<AtlasSnapshot>();
  MapSnapshot m;
  m.active = true;
  m.points = {{0.f, 0.f, 1.f}, {1.f, 0.f, 1.f}, {0.f, 1.f, 1.f}};
  m.keyframes = {{0, Eigen::Isometry3d::Identity()}};
  a->maps = {m};
  a->loops_closed = 1;
  return a;
}

class ViewerServerTest : public ::testing::Test {
 protected:
  ViewerServerTest() {
    ViewerOptions options;
    options.port = 0;
    options.image_rate = 60;
    server_ = std::make_unique<ViewerServer>(options, &pause_);
    client_ = std::make_unique<httplib::Client>("127.0.0.1", server_->port());
    publisher_.publish_frame(frame_snapshot(5));
    publisher_.publish_atlas(atlas_snapshot());
    server_->attach(&publisher_);
  }
  ~ViewerServerTest() override { server_->attach(nullptr); }

  PauseGate pause_;
  Publisher publisher_;
  std::unique_ptr<ViewerServer> server_;
  std::unique_ptr<httplib::Client> client_;
};

TEST_F(ViewerServerTest, ServesThePageAndThreeJs) {
  EXPECT_GT(server_->port(), 0);
  EXPECT_EQ(server_->url(), "http://127.0.0.1:" + std::to_string(server_->port()) + "/");
  auto page = client_->Get("/");
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_EQ(page->get_header_value("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(page->body.find("frame-canvas"), std::string::npos);
  auto three = client_->Get("/vendor/three/three.module.min.js");
  ASSERT_TRUE(three);
  EXPECT_EQ(three->status, 200);
  EXPECT_GT(three->body.size(), 500000u);
  auto script = client_->Get("/viewer.js");
  ASSERT_TRUE(script);
  EXPECT_NE(script->body.find("EventSource"), std::string::npos);
  auto missing = client_->Get("/nothing.html");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
}

TEST_F(ViewerServerTest, StateFrameAndMap) {
  auto state = client_->Get("/api/state");
  ASSERT_TRUE(state);
  const nlohmann::json s = nlohmann::json::parse(state->body);
  EXPECT_EQ(s["frame"], 5);
  EXPECT_EQ(s["features_kept"], 2);
  EXPECT_EQ(s["features_tracked"], 1);
  EXPECT_EQ(s["features_removed"], 3);
  EXPECT_EQ(s["map_points"], 3);
  EXPECT_EQ(s["keyframes"], 1);
  EXPECT_EQ(s["loops_closed"], 1);
  EXPECT_EQ(s["paused"], false);
  auto jpeg = client_->Get("/api/frame.jpg");
  ASSERT_TRUE(jpeg);
  EXPECT_EQ(jpeg->status, 200);
  const std::vector<std::uint8_t> bytes(jpeg->body.begin(), jpeg->body.end());
  const cv::Mat decoded = cv::imdecode(bytes, cv::IMREAD_COLOR);
  EXPECT_EQ(decoded.size(), cv::Size(160, 120));
  auto map = client_->Get("/api/map");
  ASSERT_TRUE(map);
  EXPECT_EQ(nlohmann::json::parse(map->body)["maps"][0]["points"].size(), 9u);
}

TEST_F(ViewerServerTest, PauseStepResume) {
  auto paused = client_->Post("/api/pause");
  ASSERT_TRUE(paused);
  EXPECT_EQ(nlohmann::json::parse(paused->body)["paused"], true);
  EXPECT_TRUE(pause_.paused());
  std::atomic<bool> stop{false};
  ASSERT_TRUE(client_->Post("/api/step"));
  EXPECT_TRUE(pause_.wait(&stop));  // the step's one frame
  auto resumed = client_->Post("/api/resume");
  ASSERT_TRUE(resumed);
  EXPECT_EQ(nlohmann::json::parse(resumed->body)["paused"], false);
  EXPECT_FALSE(pause_.paused());
}

TEST_F(ViewerServerTest, EventStreamSendsMapFrameAndStateThenNewerFrames) {
  std::string received;
  bool newer_published = false;
  auto res = client_->Get("/api/events", [&](const char* data, std::size_t size) {
    received.append(data, size);
    if (!newer_published && received.find("event: state") != std::string::npos) {
      publisher_.publish_frame(frame_snapshot(6));
      newer_published = true;
    }
    return received.find("\"frame\":6") == std::string::npos;  // stop once frame 6 came
  });
  EXPECT_NE(received.find("event: map"), std::string::npos);
  EXPECT_NE(received.find("event: frame"), std::string::npos);
  EXPECT_NE(received.find("data:image/jpeg;base64,"), std::string::npos);
  EXPECT_NE(received.find("\"removed\":[80.0,60.0,82.0,61.0,79.0,58.0]"), std::string::npos);
  EXPECT_NE(received.find("\"class\":\"person\""), std::string::npos);
  EXPECT_NE(received.find("\"frame\":6"), std::string::npos);
}

TEST(ViewerServer, APortInUseIsAnError) {
  ViewerOptions options;
  options.port = 0;
  ViewerServer first(options, nullptr);
  options.port = first.port();
  try {
    ViewerServer second(options, nullptr);
    FAIL() << "a second server on port " << options.port;
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot listen on 127.0.0.1:" + std::to_string(options.port)),
              std::string::npos)
        << e.what();
  }
  httplib::Client client("127.0.0.1", first.port());
  auto res = client.Post("/api/pause");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);  // no pause gate
}

}  // namespace
}  // namespace stillslam::viewer
