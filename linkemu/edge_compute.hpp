// The edge-compute term: how long the edge takes for a request under the current edge
// load. The edge is a processor-sharing server at utilisation ρ = edge_load; a request
// that needs work_ms on an idle edge takes work_ms / (1 - ρ) on average (M/G/1-PS mean
// sojourn time for a job of that size), with ρ capped at max_load so the delay stays finite.
#pragma once

namespace a3::linkemu {

struct EdgeComputeModel {
  double max_load = 0.95;  // ρ cap: at most a 20× slowdown by default
  // Throws std::invalid_argument when work_ms is not a finite number >= 0.
  double delay_ms(double work_ms, double edge_load) const;
};

}  // namespace a3::linkemu
