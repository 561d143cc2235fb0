// `stillslam vocab`: train a bag-of-words vocabulary on images (ORB features
// from the project's extractor), print what a vocabulary file holds, and
// query a small image database with it.
//
//   stillslam vocab train --images DIR_OR_LIST_OR_IMAGE... --out FILE [--k 10 --levels 5 --features 1000]
//   stillslam vocab info FILE
//   stillslam vocab query --vocab FILE --database DIR... --image IMG... [--top 5]
#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "commands.h"
#include "stillslam/core/error.h"
#include "stillslam/core/json_text.h"
#include "stillslam/core/stopwatch.h"
#include "stillslam/features/orb_extractor.h"
#include "stillslam/io/image_files.h"
#include "stillslam/io/input_file.h"
#include "stillslam/place/keyframe_database.h"
#include "stillslam/place/vocabulary.h"

namespace stillslam::apps {
namespace {

namespace fs = std::filesystem;

// A folder's images; for dataset folders the colour/left (and right) images
// in the usual subfolders (TUM rgb/, EuRoC mav0/cam0,cam1/data, KITTI image_N).
std::vector<fs::path> images_in_folder(const fs::path& dir) {
  auto files = image_files_in(dir);
  if (!files.empty()) return files;
  for (const char* sub : {"rgb", "mav0/cam0/data", "mav0/cam1/data", "cam0/data", "cam1/data", "image_0", "image_1",
                          "image_2", "image_3"}) {
    if (!fs::is_directory(dir / sub)) continue;
    auto more = image_files_in(dir / sub);
    files.insert(files.end(), more.begin(), more.end());
  }
  if (files.empty())
    throw Error("no images (.png, .jpg, ...) in '" + dir.string() +
                "' or its rgb/, mav0/cam0/data, mav0/cam1/data, image_N/ subfolders");
  return files;
}

// A text list: one image path per line (relative to the list's folder), or
// TUM-style "timestamp path" lines; '#' starts a comment.
std::vector<fs::path> images_in_list(const fs::path& list) {
  std::ifstream in = open_input_file(list, "image list");
  std::vector<fs::path> files;
  std::string line;
  while (std::getline(in, line)) {
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream tokens(line);
    std::string token, last;
    while (tokens >> token) last = token;
    if (last.empty()) continue;
    fs::path p(last);
    if (p.is_relative()) p = list.parent_path() / p;
    files.push_back(p);
  }
  if (files.empty()) throw Error("image list '" + list.string() + "' names no images");
  return files;
}

// Every input is a folder, an image list (.txt) or an image; `every` keeps
// every n-th image of each input (consecutive video frames are redundant).
std::vector<fs::path> collect_images(const std::vector<std::string>& inputs, int every) {
  std::vector<fs::path> all;
  for (const auto& input : inputs) {
    const fs::path p(input);
    std::vector<fs::path> files;
    if (fs::is_directory(p))
      files = images_in_folder(p);
    else if (!fs::exists(p))
      throw Error("--images '" + input + "' does not exist");
    else if (is_image_file(p))
      files = {p};
    else
      files = images_in_list(p);
    for (std::size_t i = 0; i < files.size(); i += static_cast<std::size_t>(std::max(every, 1)))
      all.push_back(files[i]);
  }
  return all;
}

cv::Mat read_gray(const fs::path& p) {
  cv::Mat gray = cv::imread(p.string(), cv::IMREAD_GRAYSCALE);
  if (gray.empty()) throw Error("cannot read image '" + p.string() + "' (missing or not an image)");
  return gray;
}

struct TrainArgs {
  std::vector<std::string> images;
  std::string out;
  VocabularyOptions vocabulary;
  std::string weighting = "tf-idf";
  int features = 1000;
  int every = 1;
};

WordWeighting parse_weighting(const std::string& s) {
  for (auto w : {WordWeighting::kTfIdf, WordWeighting::kTf, WordWeighting::kIdf, WordWeighting::kBinary})
    if (s == to_string(w)) return w;
  throw Error("--weighting '" + s + "': use tf-idf, tf, idf or binary");
}

void run_train(TrainArgs args) {
  args.vocabulary.weighting = parse_weighting(args.weighting);
  const auto files = collect_images(args.images, args.every);
  OrbOptions orb;
  orb.n_features = args.features;
  const OrbExtractor extractor(orb);
  Stopwatch extract_clock;
  std::vector<cv::Mat> descriptors;
  std::size_t total = 0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    descriptors.push_back(extractor.extract(read_gray(files[i])).descriptors);
    total += static_cast<std::size_t>(descriptors.back().rows);
    if ((i + 1) % 100 == 0 || i + 1 == files.size())
      spdlog::info("ORB features: {}/{} images, {} descriptors", i + 1, files.size(), total);
  }
  const double extract_s = extract_clock.elapsed_ms() / 1e3;
  Stopwatch train_clock;
  const Vocabulary voc = Vocabulary::train(descriptors, args.vocabulary);
  const double train_s = train_clock.elapsed_ms() / 1e3;
  voc.save(args.out);
  nlohmann::json j = {{"file", args.out},
                      {"images", files.size()},
                      {"descriptors", total},
                      {"k", voc.k()},
                      {"levels", voc.depth()},
                      {"weighting", to_string(voc.weighting())},
                      {"seed", args.vocabulary.seed},
                      {"words", voc.size()},
                      {"nodes", voc.node_count()},
                      {"bytes", fs::file_size(args.out)},
                      {"extract_seconds", extract_s},
                      {"train_seconds", train_s}};
  std::cout << json_text(j, 2) << "\n";
}

void run_info(const std::string& file) {
  Stopwatch clock;
  const Vocabulary voc = Vocabulary::load(file);
  const double load_ms = clock.elapsed_ms();
  std::map<int, std::size_t> words_at_depth;
  std::size_t zero_weight = 0;
  for (WordId w = 0; w < voc.size(); ++w) {
    ++words_at_depth[voc.node_depth(voc.word_node(w))];
    zero_weight += voc.word_weight(w) == 0 ? 1 : 0;
  }
  nlohmann::json depth = nlohmann::json::object();
  for (const auto& [d, n] : words_at_depth) depth[std::to_string(d)] = n;
  nlohmann::json j = {{"file", file},
                      {"k", voc.k()},
                      {"levels", voc.depth()},
                      {"weighting", to_string(voc.weighting())},
                      {"words", voc.size()},
                      {"nodes", voc.node_count()},
                      {"words_by_depth", depth},
                      {"zero_weight_words", zero_weight},
                      {"training_images", voc.training_images()},
                      {"training_descriptors", voc.training_descriptors()},
                      {"bytes", fs::file_size(file)},
                      {"load_ms", load_ms}};
  std::cout << json_text(j, 2) << "\n";
}

struct QueryArgs {
  std::string vocab;
  std::vector<std::string> database, images;
  int top = 5;
  int features = 1000;
};

void run_query(const QueryArgs& args) {
  const Vocabulary voc = Vocabulary::load(args.vocab);
  OrbOptions orb;
  orb.n_features = args.features;
  const OrbExtractor extractor(orb);
  const auto db_files = collect_images(args.database, 1);
  KeyframeDatabase db;
  for (std::size_t i = 0; i < db_files.size(); ++i)
    db.add(i, voc.transform(extractor.extract(read_gray(db_files[i])).descriptors));
  PlaceQueryOptions options;
  options.max_results = static_cast<std::size_t>(std::max(args.top, 0));
  for (const auto& q : collect_images(args.images, 1)) {
    const BowVector bow = voc.transform(extractor.extract(read_gray(q)).descriptors);
    nlohmann::json matches = nlohmann::json::array();
    for (const auto& c : db.query(bow, options))
      matches.push_back({{"image", db_files[c.id].string()}, {"score", c.score}, {"common_words", c.common_words}});
    std::cout << json_text(nlohmann::json{{"query", q.string()}, {"words", bow.size()}, {"matches", matches}}) << "\n";
  }
}

}  // namespace

void add_vocab_command(CLI::App& app) {
  auto* vocab = app.add_subcommand("vocab", "Bag-of-words vocabulary: train, inspect, query");
  vocab->require_subcommand(1);

  auto train = std::make_shared<TrainArgs>();
  auto* t = vocab->add_subcommand("train", "Train a vocabulary on ORB features of images");
  t->add_option("--images", train->images, "Image folders, image lists (.txt) or images")->required();
  t->add_option("--out", train->out, "Output vocabulary file")->required();
  t->add_option("--k", train->vocabulary.branching, "Branching factor")->capture_default_str();
  t->add_option("--levels", train->vocabulary.levels, "Tree depth L (at most k^L words)")->capture_default_str();
  t->add_option("--features", train->features, "ORB features per image")->capture_default_str();
  t->add_option("--every", train->every, "Use every n-th image of each input")->capture_default_str();
  t->add_option("--seed", train->vocabulary.seed, "k-means++ seed")->capture_default_str();
  t->add_option("--iterations", train->vocabulary.max_iterations, "k-majority iterations per node")
      ->capture_default_str();
  t->add_option("--weighting", train->weighting, "tf-idf, tf, idf or binary")->capture_default_str();
  t->callback([train] { run_train(*train); });

  auto info_file = std::make_shared<std::string>();
  auto* i = vocab->add_subcommand("info", "Print a vocabulary's parameters and size as JSON");
  i->add_option("file", *info_file, "Vocabulary file")->required();
  i->callback([info_file] { run_info(*info_file); });

  auto query = std::make_shared<QueryArgs>();
  auto* q = vocab->add_subcommand("query", "Rank database images by BoW similarity to query images (JSON lines)");
  q->add_option("--vocab", query->vocab, "Vocabulary file")->required();
  q->add_option("--database", query->database, "Database image folders, lists or images")->required();
  q->add_option("--image", query->images, "Query images, folders or lists")->required();
  q->add_option("--top", query->top, "Best matches per query (0: all)")->capture_default_str();
  q->add_option("--features", query->features, "ORB features per image")->capture_default_str();
  q->callback([query] { run_query(*query); });
}

}  // namespace stillslam::apps
