// Where ../shared (the α³-Bench public episodes, DroneCAN vectors) is for a command: the
// environment's A3_SHARED_DIR; else ../shared from the working directory, when it exists; else,
// for an installed a3rig (<prefix>/bin/a3rig with <prefix>/share/a3rig), <prefix>/share/a3rig/shared
// (whether or not it exists: an installed a3rig never looks into the tree it was built from);
// else ../shared beside the repository of the running a3rig (<repo>/build/a3rig); else ../shared
// beside the source tree it was built from.
#pragma once

#include <filesystem>

namespace a3::rigs {

std::filesystem::path default_shared_dir();

}  // namespace a3::rigs
