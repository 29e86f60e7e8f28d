#pragma once
// Output files appear whole or not at all: content goes to a temporary file beside the target,
// which is renamed over it only after a successful write and close.
#include <string>

namespace bsp {

// Throws InputError naming the path when the file cannot be written.
void write_file_atomically(const std::string& path, const std::string& content);

}  // namespace bsp
