#pragma once
// Timestamp association between a ground-truth and an estimated trajectory.
#include <cstddef>
#include <string>
#include <vector>

namespace stillslam {

enum class AssociationMethod {
  // TUM associate.py: all candidate pairs with |dt| < max_dt, taken greedily
  // by increasing |dt|, each stamp used at most once, result sorted by time.
  // Like associate.py (which keys a dict by stamp), a stamp that repeats in
  // one trajectory keeps only its last pose.
  Greedy,
  // evo sync: every stamp of the shorter trajectory takes its nearest stamp of
  // the longer one if |dt| <= max_dt (stamps of the longer one may repeat).
  Nearest,
};

AssociationMethod parse_association_method(const std::string& name);  // "tum"/"greedy", "nearest"
std::string to_string(AssociationMethod method);

struct AssociationOptions {
  AssociationMethod method = AssociationMethod::Greedy;
  // Seconds; <= 0 picks the method's default (0.02 greedy as TUM, 0.01 nearest as evo).
  double max_dt = 0;
  double offset = 0;  // added to the estimate's stamps before matching (seconds)

  double effective_max_dt() const;
  // OptionError for a NaN, negative or infinite max_dt or a non-finite offset
  // (either would silently give the default or no pairs).
  void check() const;
};

struct IndexPair {
  std::size_t gt = 0;
  std::size_t est = 0;
};

// Index pairs into `gt_stamps` and `est_stamps`, sorted by ground-truth time.
std::vector<IndexPair> associate(const std::vector<double>& gt_stamps, const std::vector<double>& est_stamps,
                                 const AssociationOptions& options);

}  // namespace stillslam
