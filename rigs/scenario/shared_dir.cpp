#include "rigs/scenario/shared_dir.hpp"

#include <cstdlib>
#include <system_error>

namespace a3::rigs {

std::filesystem::path default_shared_dir() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("A3_SHARED_DIR"); env != nullptr && *env != '\0') return env;
  const fs::path here = "../shared";
  std::error_code ec;
  if (fs::is_directory(here, ec)) return here;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    // Installed (<prefix>/bin/a3rig beside <prefix>/share/a3rig): never the build machine's paths.
    const fs::path installed_data = exe.parent_path().parent_path() / "share" / "a3rig";
    if (exe.parent_path().filename() == "bin" && fs::is_directory(installed_data, ec)) return installed_data / "shared";
    const fs::path beside_repo = exe.parent_path().parent_path().parent_path() / "shared";
    if (fs::is_directory(beside_repo, ec)) return beside_repo;
  }
#ifdef A3_SHARED_DIR_DEFAULT
  if (fs::is_directory(A3_SHARED_DIR_DEFAULT, ec)) return A3_SHARED_DIR_DEFAULT;
#endif
  return here;  // absent: the commands that need it say so, naming this path
}

}  // namespace a3::rigs
