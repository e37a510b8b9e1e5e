#!/usr/bin/env bash
# Flies the demonstration flight (bench_dynamics_flight) and plots it with gnuplot.
# Usage: bench/dynamics/plot_flight.sh [BUILD_DIR] [OUT_PNG]
#   BUILD_DIR  default: build/ in the repository; OUT_PNG default: docs/figures/dynamics_flight.png
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
repo=$(cd "$here/../.." && pwd)
build=${1:-$repo/build}
png=${2:-$repo/docs/figures/dynamics_flight.png}
csv=$(mktemp --suffix=.csv)
trap 'rm -f "$csv"' EXIT
"$build/bench/bench_dynamics_flight" --csv "$csv"
mkdir -p "$(dirname "$png")"
gnuplot -e "csv='$csv'; png='$png'" "$here/plot_flight.gp"
echo "plot: $png ($(( $(stat -c %s "$png") / 1024 )) KB)"
