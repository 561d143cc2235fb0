#include "stillslam/io/ros2_message_codec.h"

#include "stillslam/io/cdr_reader.h"
#include "stillslam/io/cdr_writer.h"

namespace stillslam::ros2 {
namespace {

Header read_header(CdrReader& r) {
  Header h;
  h.sec = r.i32();
  h.nanosec = r.u32();
  h.frame_id = r.string();
  return h;
}

void write_header(CdrWriter& w, const Header& h) {
  w.i32(h.sec);
  w.u32(h.nanosec);
  w.string(h.frame_id);
}

Pose read_pose(CdrReader& r) {
  Pose p;
  r.f64_array(p.position.data(), 3);
  r.f64_array(p.orientation.data(), 4);
  return p;
}

void write_pose(CdrWriter& w, const Pose& p) {
  w.f64_array(p.position.data(), 3);
  w.f64_array(p.orientation.data(), 4);
}

std::vector<std::uint8_t> read_bytes(CdrReader& r) {
  std::size_t n = 0;
  const std::uint8_t* p = r.bytes(n);
  return std::vector<std::uint8_t>(p, p + n);
}

CdrReader reader(const Bytes& cdr, const std::string& what) { return CdrReader(cdr.data(), cdr.size(), what); }

}  // namespace

Header decode_header(const Bytes& cdr, const std::string& what) {
  CdrReader r = reader(cdr, what);
  return read_header(r);
}

std::int64_t decode_stamp_ns(const Bytes& cdr, const std::string& what) {
  CdrReader r = reader(cdr, what);
  Header h;
  h.sec = r.i32();
  h.nanosec = r.u32();
  return h.stamp_ns();
}

Image decode_image(const Bytes& cdr, const std::string& what) {
  CdrReader r = reader(cdr, what);
  Image m;
  m.header = read_header(r);
  m.height = r.u32();
  m.width = r.u32();
  m.encoding = r.string();
  m.is_bigendian = r.u8();
  m.step = r.u32();
  m.data = read_bytes(r);
  return m;
}

CompressedImage decode_compressed_image(const Bytes& cdr, const std::string& what) {
  CdrReader r = reader(cdr, what);
  CompressedImage m;
  m.header = read_header(r);
  m.format = r.string();
  m.data = read_bytes(r);
  return m;
}

CameraInfo decode_camera_info(const Bytes& cdr, const std::string& what) {
  CdrReader r = reader(cdr, what);
  CameraInfo m;
  m.header = read_header(r);
  m.height = r.u32();
  m.width = r.u32();
  m.distortion_model = r.string();
  m.d = r.f64_sequence();
  r.f64_array(m.k.data(), 9);
  r.f64_array(m.r.data(), 9);
  r.f64_array(m.p.data(), 12);
  m.binning_x = r.u32();
  m.binning_y = r.u32();
  m.roi_x_offset = r.u32();
  m.roi_y_offset = r.u32();
  m.roi_height = r.u32();
  m.roi_width = r.u32();
  m.roi_do_rectify = r.boolean();
  return m;
}

PoseStamped decode_pose_stamped(const Bytes& cdr, const std::string& what) {
  CdrReader r = reader(cdr, what);
  PoseStamped m;
  m.header = read_header(r);
  m.pose = read_pose(r);
  return m;
}

Odometry decode_odometry(const Bytes& cdr, const std::string& what) {
  CdrReader r = reader(cdr, what);
  Odometry m;
  m.header = read_header(r);
  m.child_frame_id = r.string();
  m.pose = read_pose(r);
  r.f64_array(m.pose_covariance.data(), 36);
  r.f64_array(m.linear.data(), 3);
  r.f64_array(m.angular.data(), 3);
  r.f64_array(m.twist_covariance.data(), 36);
  return m;
}

TfMessage decode_tf_message(const Bytes& cdr, const std::string& what) {
  CdrReader r = reader(cdr, what);
  TfMessage m;
  // A transform is at least a header (12 bytes) and 7 doubles.
  m.transforms.resize(r.sequence_length(12 + 56));
  for (TransformStamped& t : m.transforms) {
    t.header = read_header(r);
    t.child_frame_id = r.string();
    t.transform = read_pose(r);
  }
  return m;
}

Bytes encode(const Image& m) {
  CdrWriter w;
  write_header(w, m.header);
  w.u32(m.height);
  w.u32(m.width);
  w.string(m.encoding);
  w.u8(m.is_bigendian);
  w.u32(m.step);
  w.bytes(m.data.data(), m.data.size());
  return w.take();
}

Bytes encode(const CompressedImage& m) {
  CdrWriter w;
  write_header(w, m.header);
  w.string(m.format);
  w.bytes(m.data.data(), m.data.size());
  return w.take();
}

Bytes encode(const CameraInfo& m) {
  CdrWriter w;
  write_header(w, m.header);
  w.u32(m.height);
  w.u32(m.width);
  w.string(m.distortion_model);
  w.f64_sequence(m.d);
  w.f64_array(m.k.data(), 9);
  w.f64_array(m.r.data(), 9);
  w.f64_array(m.p.data(), 12);
  w.u32(m.binning_x);
  w.u32(m.binning_y);
  w.u32(m.roi_x_offset);
  w.u32(m.roi_y_offset);
  w.u32(m.roi_height);
  w.u32(m.roi_width);
  w.boolean(m.roi_do_rectify);
  return w.take();
}

Bytes encode(const PoseStamped& m) {
  CdrWriter w;
  write_header(w, m.header);
  write_pose(w, m.pose);
  return w.take();
}

Bytes encode(const Odometry& m) {
  CdrWriter w;
  write_header(w, m.header);
  w.string(m.child_frame_id);
  write_pose(w, m.pose);
  w.f64_array(m.pose_covariance.data(), 36);
  w.f64_array(m.linear.data(), 3);
  w.f64_array(m.angular.data(), 3);
  w.f64_array(m.twist_covariance.data(), 36);
  return w.take();
}

Bytes encode(const TfMessage& m) {
  CdrWriter w;
  w.u32(static_cast<std::uint32_t>(m.transforms.size()));
  for (const TransformStamped& t : m.transforms) {
    write_header(w, t.header);
    w.string(t.child_frame_id);
    write_pose(w, t.transform);
  }
  return w.take();
}

}  // namespace stillslam::ros2
