#include "io/doom_iwads.h"

#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>

#include "common/errors.h"

namespace bsp {

std::string doom_data_dir() {
  const char* dir = std::getenv("BSPBENCH_DOOM_DIR");
  return dir && *dir ? dir : "/usr/share/games/doom";
}

std::string doom_iwad_path(const std::string& iwad) { return (std::filesystem::path(doom_data_dir()) / iwad).string(); }

const Wad& doom_wad(const std::string& iwad) {
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<const Wad>> read;
  const std::string path = doom_iwad_path(iwad);
  const std::lock_guard lock(mutex);
  auto& wad = read[path];
  if (!wad) {
    if (!std::filesystem::exists(path))
      throw InputError(path + ": no such IWAD (apt-get install freedoom, or set BSPBENCH_DOOM_DIR to its directory)");
    wad = std::make_unique<const Wad>(read_wad(path));
  }
  return *wad;
}

}  // namespace bsp
