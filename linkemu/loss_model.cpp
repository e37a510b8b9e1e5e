// Bernoulli and Gilbert–Elliott loss.
#include "linkemu/loss_model.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace a3::linkemu {

LossModel::LossModel(common::Rng rng, const GilbertElliottConfig& config)
    : rng_(std::move(rng)), config_(config) {
  if (config.enabled && !(config.mean_burst_messages >= 1.0)) {
    throw std::invalid_argument("Gilbert-Elliott mean_burst_messages must be >= 1, got " +
                                std::to_string(config.mean_burst_messages));
  }
  if (config.enabled && !(config.loss_in_bad > 0.0 && config.loss_in_bad <= 1.0)) {
    throw std::invalid_argument("Gilbert-Elliott loss_in_bad must be in (0, 1], got " +
                                std::to_string(config.loss_in_bad));
  }
}

bool LossModel::lose(double p) {
  if (!config_.enabled) return rng_.bernoulli(p);
  // Stationary share of Bad = p_gb / (p_gb + r) must be p / loss_in_bad.
  const double r = 1.0 / config_.mean_burst_messages;
  const double bad_share = std::min(1.0, p / config_.loss_in_bad);
  const double p_gb = bad_share >= 1.0 ? 1.0 : std::min(1.0, r * bad_share / (1.0 - bad_share));
  bad_ = bad_ ? !rng_.bernoulli(r) : rng_.bernoulli(p_gb);
  return bad_ && rng_.bernoulli(config_.loss_in_bad);
}

}  // namespace a3::linkemu
