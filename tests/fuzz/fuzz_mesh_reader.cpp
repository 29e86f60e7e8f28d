// The mesh readers on arbitrary bytes: the first byte picks the format (OBJ, OFF, PLY, STL), the
// rest is the file. read_mesh must return a scene or throw InputError; any other exception, a
// sanitizer report, a leak or an allocation past libFuzzer's -rss_limit_mb is a bug.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>

#include "common/errors.h"
#include "io/mesh_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  static const char* const kExtensions[] = {".obj", ".off", ".ply", ".stl"};
  // In memory (/dev/shm): writing every input to a disk-backed /tmp made file I/O most of the time.
  const std::string path = "/dev/shm/bspbench_fuzz_mesh_" + std::to_string(::getpid()) + kExtensions[data[0] % 4];
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  try {
    bsp::read_mesh(path);
  } catch (const bsp::InputError&) {
  }
  std::remove(path.c_str());
  return 0;
}
