// Message loss of one direction at the current loss rate: independent (Bernoulli), or in
// bursts (Gilbert–Elliott: a Good state that loses nothing and a Bad state that loses with
// probability loss_in_bad, left after mean_burst_messages on average; the Good→Bad
// probability is set from the current loss rate so the long-run rate stays that rate).
#pragma once

#include "common/rng.hpp"

namespace a3::linkemu {

struct GilbertElliottConfig {
  bool enabled = false;
  double mean_burst_messages = 4.0;  // mean stay in Bad, messages (>= 1)
  double loss_in_bad = 0.5;          // loss probability in Bad, (0, 1]
};

class LossModel {
 public:
  // Throws std::invalid_argument on a bad Gilbert–Elliott configuration.
  LossModel(common::Rng rng, const GilbertElliottConfig& config);
  // Decides the fate of the next message; loss_probability in [0, 1]. Rates above
  // loss_in_bad / (1 + 1/mean_burst) cannot be reached in bursts and are capped there.
  bool lose(double loss_probability);
  bool in_bad_state() const { return bad_; }

 private:
  common::Rng rng_;
  GilbertElliottConfig config_;
  bool bad_ = false;
};

}  // namespace a3::linkemu
