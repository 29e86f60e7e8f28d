#pragma once
// The IWADs Doom runs and the doom-piece scenes read, by file name in the Doom data directory:
// $BSPBENCH_DOOM_DIR, else /usr/share/games/doom, where Debian's freedoom package installs freedoom1.wad and freedoom2.wad
// (as Doom ports search DOOMWADDIR). Names rather than paths keep keys, identities and commands the
// same on every machine; the map's content hash in each record says which maps were read.
#include <string>

#include "io/wad.h"

namespace bsp {

// $BSPBENCH_DOOM_DIR, or /usr/share/games/doom when it is unset or empty.
std::string doom_data_dir();
std::string doom_iwad_path(const std::string& iwad);

// The IWAD, read once per process and shared by every job that reads it; thread-safe. Throws
// InputError naming the path (and `apt-get install freedoom`) when it is missing or unreadable.
const Wad& doom_wad(const std::string& iwad);

}  // namespace bsp
