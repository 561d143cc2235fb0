#include "stillslam/sim/asset_extraction.h"

#include <algorithm>
#include <fstream>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "stillslam/core/error.h"

namespace stillslam::sim {
namespace fs = std::filesystem;
namespace {

constexpr int kPersonClass = 1;  // labels/config.yaml of coco128_yolo

struct Polygon {
  int cls = 0;
  std::vector<cv::Point2f> pts;  // pixels
  cv::Rect2f box() const { return cv::boundingRect(pts); }
};

std::vector<Polygon> read_labels(const fs::path& file, cv::Size size) {
  std::vector<Polygon> out;
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ss(line);
    Polygon p;
    if (!(ss >> p.cls)) continue;
    float x, y;
    while (ss >> x >> y) p.pts.emplace_back(x * size.width, y * size.height);
    if (p.pts.size() >= 3) out.push_back(std::move(p));
  }
  return out;
}

struct Candidate {
  fs::path image;
  std::string id;
  double score = 0;
  Polygon poly;
  int index = 0;
};

// Fraction of a 8x6 grid with at least 4 FAST corners, plus a little for the total.
double corner_score(const cv::Mat& bgr) {
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  std::vector<cv::KeyPoint> kps;
  cv::FAST(gray, kps, 20, true);
  const int gx = 8, gy = 6;
  std::vector<int> cells(gx * gy, 0);
  for (const auto& k : kps) {
    const int cx = std::min(gx - 1, static_cast<int>(k.pt.x * gx / gray.cols));
    const int cy = std::min(gy - 1, static_cast<int>(k.pt.y * gy / gray.rows));
    ++cells[cy * gx + cx];
  }
  const double covered =
      static_cast<double>(std::count_if(cells.begin(), cells.end(), [](int c) { return c >= 4; }));
  return covered / cells.size() + 1e-5 * kps.size();
}

std::string stem_of(const fs::path& p) { return p.stem().string(); }

}  // namespace

ExtractedAssets extract_assets(const fs::path& coco_dir, const fs::path& data_dir,
                               const AssetExtractionOptions& options) {
  if (!fs::is_directory(coco_dir / "images") || !fs::is_directory(coco_dir / "labels")) {
    throw Error("sim assets: " + coco_dir.string() +
                " must be a COCO128 YOLO-seg folder with images/ and labels/");
  }
  std::vector<Candidate> textures, people, sitting;
  std::vector<fs::path> images;
  for (const auto& e : fs::recursive_directory_iterator(coco_dir / "images")) {
    if (e.is_regular_file() && e.path().extension() == ".jpg") images.push_back(e.path());
  }
  std::sort(images.begin(), images.end());
  for (const auto& img_path : images) {
    const std::string split = img_path.parent_path().filename().string();
    const fs::path label = coco_dir / "labels" / split / (stem_of(img_path) + ".txt");
    if (!fs::exists(label)) continue;  // unlabelled photos may show people
    cv::Mat img = cv::imread(img_path.string(), cv::IMREAD_COLOR);
    if (img.empty()) continue;
    const auto polys = read_labels(label, img.size());
    std::vector<const Polygon*> persons;
    for (const auto& p : polys) {
      if (p.cls == kPersonClass) persons.push_back(&p);
    }
    if (persons.empty()) {
      textures.push_back({img_path, stem_of(img_path), corner_score(img), {}, 0});
      continue;
    }
    for (size_t i = 0; i < persons.size(); ++i) {
      const cv::Rect2f b = persons[i]->box();
      const bool inside = b.x > 2 && b.y > 2 && b.x + b.width < img.cols - 3 &&
                          b.y + b.height < img.rows - 3;
      if (!inside || b.height < options.min_person_height ||
          b.height < options.min_aspect * b.width) {
        continue;
      }
      bool overlapped = false;
      for (size_t j = 0; j < persons.size(); ++j) {
        if (j != i && (b & persons[j]->box()).area() > 0.05 * b.area()) overlapped = true;
      }
      if (overlapped) continue;
      const std::string key = stem_of(img_path) + "_" + std::to_string(i);
      const auto listed = [&](const std::vector<std::string>& list) {
        return std::find(list.begin(), list.end(), key) != list.end();
      };
      if (listed(options.sitting)) {
        sitting.push_back({img_path, stem_of(img_path), b.height, *persons[i], static_cast<int>(i)});
      } else if (!listed(options.exclude)) {
        people.push_back({img_path, stem_of(img_path), b.height, *persons[i], static_cast<int>(i)});
      }
    }
  }
  auto by_score = [](const Candidate& a, const Candidate& b) {
    return a.score != b.score ? a.score > b.score : a.image < b.image;
  };
  std::sort(textures.begin(), textures.end(), by_score);
  std::sort(people.begin(), people.end(), by_score);
  textures.resize(std::min<size_t>(textures.size(), options.textures));
  people.resize(std::min<size_t>(people.size(), options.cutouts));
  for (auto& p : sitting) p.index = -1 - p.index;  // marks "sitting" below, keeps the instance number
  people.insert(people.end(), sitting.begin(), sitting.end());

  ExtractedAssets out;
  fs::create_directories(data_dir / "textures");
  fs::create_directories(data_dir / "cutouts");
  std::ostringstream tex_rows, cut_rows;
  for (const auto& t : textures) {
    const std::string name = "coco_" + t.id + ".jpg";
    fs::copy_file(t.image, data_dir / "textures" / name, fs::copy_options::overwrite_existing);
    fs::permissions(data_dir / "textures" / name,
                    fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
    out.texture_files.push_back(name);
    tex_rows << "| " << name << " | " << t.image.parent_path().filename().string() << "/" << t.id
             << ".jpg | " << cv::format("%.3f", t.score) << " |\n";
  }
  for (const auto& p : people) {
    cv::Mat img = cv::imread(p.image.string(), cv::IMREAD_COLOR);
    cv::Mat alpha = cv::Mat::zeros(img.size(), CV_8UC1);
    std::vector<cv::Point> pts;
    for (const auto& q : p.poly.pts) pts.emplace_back(cvRound(q.x), cvRound(q.y));
    cv::fillPoly(alpha, std::vector<std::vector<cv::Point>>{pts}, cv::Scalar(255), cv::LINE_8);
    const cv::Rect crop = cv::boundingRect(alpha) & cv::Rect(0, 0, img.cols, img.rows);
    cv::Mat bgra;
    cv::cvtColor(img, bgra, cv::COLOR_BGR2BGRA);
    std::vector<cv::Mat> ch;
    cv::split(bgra, ch);
    ch[3] = alpha;
    cv::merge(ch, bgra);
    const bool seated = p.index < 0;
    const int index = seated ? -1 - p.index : p.index;
    const std::string name = (seated ? "sitting_" : "person_") + p.id + "_" + std::to_string(index) + ".png";
    cv::imwrite((data_dir / "cutouts" / name).string(), bgra(crop));
    out.cutout_files.push_back(name);
    cut_rows << "| " << name << " | " << p.image.parent_path().filename().string() << "/" << p.id
             << ".jpg | person polygon #" << index << (seated ? " (sitting)" : "") << " | " << crop.width
             << "x" << crop.height
             << " |\n";
  }
  const std::string license =
      "Source: COCO 2017 images via GitHub lightly-ai/coco128_yolo @ "
      "6d6f7a059ea63efffdbe48aca2d52c04d4c510e9 (images/ and YOLO-seg labels/). Each COCO image "
      "keeps its own Flickr license (Creative Commons: CC BY, CC BY-SA, CC BY-NC, CC BY-NC-SA, "
      "CC BY-ND, CC BY-NC-ND families; look the id up in COCO's instances_<split>2017.json "
      "`license` field for the exact one and its attribution). COCO annotations: CC BY 4.0. "
      "Use these files for research and testing only.\n\n"
      "Regenerate with `stillslam simulate --extract-assets <coco128 folder> --data-dir data --cutouts " +
      std::to_string(options.cutouts) + [&] {
        std::string list;
        for (const auto& e : options.exclude) list += " --exclude-cutout " + e;
        for (const auto& e : options.sitting) list += " --sitting-cutout " + e;
        return list;
      }() + "`.\n\n";
  std::ofstream(data_dir / "textures" / "README.md")
      << "# Photo textures for the simulator\n\n"
      << "COCO photos whose instance labels contain no person (class 1), ranked by how evenly "
         "FAST corners cover them (score = fraction of an 8x6 grid with >= 4 corners).\n\n"
      << license << "| file | source (split/id) | score |\n|---|---|---|\n"
      << tex_rows.str();
  std::ofstream(data_dir / "cutouts" / "README.md")
      << "# Person cut-outs for the simulator\n\n"
      << "RGBA crops of COCO person instances: alpha = the COCO polygon (so the simulator's "
         "ground-truth masks are exact). Chosen: whole body (bbox height >= "
      << options.min_person_height << " px, height/width >= " << options.min_aspect
      << "), not touching the image border, not overlapping another person; largest first. "
         "sitting_*.png are seated people (chosen by hand) for people who stay still.\n\n"
      << "Excluded after looking at them (cut off by furniture or the frame edge, crouching, "
         "sitting, polygon artefacts):";
  std::ofstream(data_dir / "cutouts" / "README.md", std::ios::app)
      << (options.exclude.empty() ? std::string(" none") : "")
      << [&] {
           std::string list;
           for (const auto& e : options.exclude) list += " " + e;
           return list;
         }()
      << ".\n\n"
      << license << "| file | source (split/id) | instance | size |\n|---|---|---|---|\n"
      << cut_rows.str();
  return out;
}

}  // namespace stillslam::sim
