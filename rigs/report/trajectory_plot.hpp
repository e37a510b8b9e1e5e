// The trajectory plot's gnuplot script, apart from drawing it (write_trajectory_plot in
// episode_writer.hpp runs gnuplot on it), so that what the map shows can be checked without
// gnuplot. The map shows the flown track over the world: the geofence (always in view), no-fly
// zones (filled, labelled with id, floor and ceiling), objectives and home, the other
// aircraft's planned tracks (waypoints with their times), and the recorded safety events
// (no-fly-zone intrusions, separation breaches, crashes, gate refusals, failsafes, ...) where
// they happened, one legend entry per kind.
#pragma once

#include <filesystem>
#include <string>

#include "rigs/run/episode_recorder.hpp"
#include "rigs/scenario/scenario.hpp"

namespace a3::rigs {

// The script reads the track from DIR/trajectory.tsv and draws into DIR/trajectory.png, or
// into png_out when given (gnuplot -e "png_out='...'"). Zones, peers and events are inline
// data blocks ($peer_N, $events_KIND), one row per waypoint or event.
std::string trajectory_plot_script(const std::filesystem::path& dir, const Scenario& scenario,
                                   const RecordedEpisode& rec);

}  // namespace a3::rigs
