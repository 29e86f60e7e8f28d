#include "io/wad.h"

#include <cstdint>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "common/errors.h"
#include "io/atomic_file.h"

namespace bsp {

namespace {

constexpr std::size_t kHeaderBytes = 12;
constexpr std::size_t kEntryBytes = 16;
constexpr std::size_t kNameBytes = 8;

std::int32_t read_le32(const std::string& bytes, std::size_t at) {
  std::uint32_t v = 0;
  for (int b = 3; b >= 0; --b) v = (v << 8) | static_cast<std::uint8_t>(bytes[at + b]);
  return static_cast<std::int32_t>(v);
}

void append_le32(std::string& out, std::uint32_t v) {
  for (int b = 0; b < 4; ++b) out.push_back(static_cast<char>((v >> (8 * b)) & 0xff));
}

std::string lump_name(const std::string& bytes, std::size_t at) {
  std::string name = bytes.substr(at, kNameBytes);
  return name.substr(0, name.find('\0'));
}

// The number `what` of `where`, checked not to be negative.
std::size_t non_negative(std::int32_t value, const std::string& file, const std::string& where,
                         const std::string& what) {
  if (value < 0) throw InputError(file + ": " + where + ": negative " + what + " " + std::to_string(value));
  return static_cast<std::size_t>(value);
}

Lump read_entry(const std::string& bytes, std::size_t entry, std::size_t at, const std::string& file) {
  const std::string name = lump_name(bytes, at + 8);
  const std::string where = "directory entry " + std::to_string(entry) + " (lump " + name + ")";
  const std::size_t offset = non_negative(read_le32(bytes, at), file, where, "offset");
  const std::size_t size = non_negative(read_le32(bytes, at + 4), file, where, "size");
  if (offset > bytes.size() || size > bytes.size() - offset)
    throw InputError(file + ": " + where + ": " + std::to_string(size) + " bytes at offset " + std::to_string(offset) +
                     " reach past the end of the file (" + std::to_string(bytes.size()) + " bytes)");
  const auto* first = reinterpret_cast<const std::uint8_t*>(bytes.data()) + offset;
  return {name, std::vector<std::uint8_t>(first, first + size)};
}

}  // namespace

Wad parse_wad(const std::string& bytes, const std::string& file) {
  if (bytes.size() < kHeaderBytes)
    throw InputError(file + ": " + std::to_string(bytes.size()) + " bytes is shorter than the 12-byte WAD header");
  const std::string magic = bytes.substr(0, 4);
  if (magic != "IWAD" && magic != "PWAD") throw InputError(file + ": not a WAD file (magic is not IWAD or PWAD)");
  const std::size_t count = non_negative(read_le32(bytes, 4), file, "header", "lump count");
  const std::size_t directory = non_negative(read_le32(bytes, 8), file, "header", "directory offset");
  if (directory > bytes.size() || count > (bytes.size() - directory) / kEntryBytes)
    throw InputError(file + ": directory of " + std::to_string(count) + " entries at offset " +
                     std::to_string(directory) + " reaches past the end of the file (" + std::to_string(bytes.size()) +
                     " bytes)");
  Wad wad{magic == "IWAD", {}};
  wad.lumps.reserve(count);
  for (std::size_t i = 0; i < count; ++i) wad.lumps.push_back(read_entry(bytes, i, directory + i * kEntryBytes, file));
  return wad;
}

Wad read_wad(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open");
  std::ostringstream content;
  content << in.rdbuf();
  if (in.bad()) throw InputError(path + ": read failed");
  return parse_wad(content.str(), path);
}

std::string wad_bytes(const Wad& wad) {
  std::string data;
  std::string directory;
  for (const Lump& lump : wad.lumps) {
    if (lump.name.size() > kNameBytes) throw std::invalid_argument("lump name longer than 8 characters: " + lump.name);
    append_le32(directory, static_cast<std::uint32_t>(kHeaderBytes + data.size()));
    append_le32(directory, static_cast<std::uint32_t>(lump.data.size()));
    directory += lump.name + std::string(kNameBytes - lump.name.size(), '\0');
    data.append(lump.data.begin(), lump.data.end());
  }
  if (kHeaderBytes + data.size() > INT32_MAX) throw std::length_error("WAD larger than its 32-bit offsets can address");
  std::string out = wad.iwad ? "IWAD" : "PWAD";
  append_le32(out, static_cast<std::uint32_t>(wad.lumps.size()));
  append_le32(out, static_cast<std::uint32_t>(kHeaderBytes + data.size()));
  return out + data + directory;
}

void write_wad(const std::string& path, const Wad& wad) { write_file_atomically(path, wad_bytes(wad)); }

}  // namespace bsp
