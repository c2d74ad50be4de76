// Anderson acceleration of a fixed-point iteration x <- G(x) (Walker & Ni 2011, "type II"):
// owns the last `depth` differences of the iterates' images and residuals. Used for the Uzawa
// updates of the augmented Lagrangian (contact_pair_augmentation.cpp), whose plain iteration
// contracts like k / (k + eps) per update for a contact mode of stiffness k: with a penalty well
// below the surface's stiffness that is 0.9-0.99, hundreds of updates. Near a fixed active set
// the map is affine, and Anderson then does what GMRES does on it.
#pragma once

#include <Eigen/Dense>
#include <deque>

namespace cc::contact {

class AndersonAcceleration {
 public:
  explicit AndersonAcceleration(int depth) : depth_(depth) {}

  // The next iterate from the current one `x` and its image `image` = G(x): the combination of
  // the last images whose residuals G(x) - x combine to the least weighted norm (weights
  // `weights` >= 0, one per entry: the integration weights). Depth 0, the first call, a change
  // of size, and a residual larger than the last one's (the map left its affine regime: an
  // active set changed) all give the plain image and restart the history from it.
  Eigen::VectorXd next(const Eigen::VectorXd& x, const Eigen::VectorXd& image,
                       const Eigen::VectorXd& weights);
  void reset();
  int historySize() const { return static_cast<int>(residualChanges_.size()); }

 private:
  int depth_;
  bool started_ = false;
  Eigen::VectorXd lastImage_, lastResidual_;
  std::deque<Eigen::VectorXd> imageChanges_, residualChanges_;  // newest at the back
};

}  // namespace cc::contact
