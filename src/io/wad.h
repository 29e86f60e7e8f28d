#pragma once
// WAD files, the container of Doom's data [DoomSpecs]: a 12-byte
// header ("IWAD" or "PWAD", lump count, directory offset, little-endian int32), the lumps' bytes,
// and a directory of 16-byte entries (offset, size, name of up to 8 characters NUL-padded).
// A Wad is the directory in order with each lump's bytes copied out, so lumps can be replaced
// and the file written again with every other lump's bytes unchanged.
#include <cstdint>
#include <string>
#include <vector>

namespace bsp {

struct Lump {
  std::string name;  // up to 8 characters, without the NUL padding
  std::vector<std::uint8_t> data;
};

struct Wad {
  bool iwad = false;  // "IWAD" rather than "PWAD"
  std::vector<Lump> lumps;
};

// Throws InputError "PATH: problem" for an unreadable file, one shorter than the header, a bad
// magic, a directory or a lump (named by its entry number and name) reaching past the end of the
// file, or a negative count, size or offset.
Wad read_wad(const std::string& path);

// read_wad on bytes already in memory; `file_for_errors` names them in messages.
Wad parse_wad(const std::string& bytes, const std::string& file_for_errors);

// The file's bytes: header, the lumps' data in directory order, then the directory. Names longer
// than 8 characters are a bug (std::invalid_argument): no WAD can hold them.
std::string wad_bytes(const Wad& wad);

// wad_bytes written atomically (write_file_atomically).
void write_wad(const std::string& path, const Wad& wad);

}  // namespace bsp
