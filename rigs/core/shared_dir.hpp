// Where ../shared (the α³-Bench public episodes, DroneCAN vectors) is for a command: the
// environment's A3_SHARED_DIR; else ../shared from the working directory, when it exists; else
// ../shared beside the repository of the running a3rig (<repo>/build/a3rig); else ../shared
// beside the source tree it was built from.
#pragma once

#include <filesystem>

namespace a3::rigs {

std::filesystem::path default_shared_dir();

}  // namespace a3::rigs
