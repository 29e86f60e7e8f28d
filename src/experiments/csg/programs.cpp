#include "experiments/csg/programs.h"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include "common/errors.h"
#include "csg_programs.h"

namespace bsp::experiments {

namespace {

std::filesystem::path write_generated(const ProgramSource& s, std::uint64_t seed, const std::filesystem::path& scratch) {
  const auto file = scratch / (s.name + "-k" + std::to_string(s.k) + "-s" + std::to_string(seed) + ".csg");
  std::ofstream out(file, std::ios::binary);
  out << find_csg_program(s.name).text(s.k, seed);
  if (!out.flush()) throw InputError(file.string() + ": cannot write the program");
  return file;
}

// The example's folder is copied whole: its imports are relative to it.
std::filesystem::path export_example(const std::string& name, const std::filesystem::path& scratch) {
  const std::string label = "openscad:" + name;
  if (!std::filesystem::exists(kOpenScadExamples)) throw InputError(label + ": OpenSCAD's examples are not installed (.ci/setup installs openscad)");
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kOpenScadExamples)) {
    if (entry.path().extension() != ".scad" || entry.path().stem() != name) continue;
    const auto dir = scratch / "model";
    std::filesystem::copy(entry.path().parent_path(), dir, std::filesystem::copy_options::recursive);
    const auto file = dir / (name + ".csg");
    const std::string cmd = "cd " + shell_quoted(dir) + " && openscad -o " + shell_quoted(file) + " " + shell_quoted(dir / entry.path().filename()) +
                            " > " + shell_quoted(dir / "export.log") + " 2>&1";
    if (std::system(cmd.c_str()) != 0 || !std::filesystem::exists(file))
      throw InputError(label + ": openscad could not export it to CSG (is Debian's openscad installed?)");
    return file;
  }
  throw InputError(label + ": no such example in " + kOpenScadExamples.string());
}

}  // namespace

std::string ProgramSource::label() const { return generated() ? name + ":k=" + std::to_string(k) : name; }

ProgramSource parse_program_source(const std::string& text) {
  if (text.rfind("openscad:", 0) == 0 || text.ends_with(".csg")) return {text, 0};
  const std::size_t colon = text.find(':');
  const CsgProgramInfo& info = find_csg_program(text.substr(0, colon));
  const std::string rest = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (rest.rfind("k=", 0) != 0) throw UsageError("program '" + text + "' needs its size: " + std::string(info.name) + ":k=K");
  char* end = nullptr;
  const unsigned long long k = std::strtoull(rest.c_str() + 2, &end, 10);
  if (*end != '\0' || k < 1 || k > info.max_k)
    throw UsageError("program '" + text + "': k must be an integer in [1, " + std::to_string(info.max_k) + "]");
  return {std::string(info.name), k};
}

LoadedProgram load_program(const ProgramSource& source, std::uint64_t seed, const std::filesystem::path& scratch) {
  LoadedProgram out;
  if (source.generated()) out.file = write_generated(source, seed, scratch);
  else if (source.name.rfind("openscad:", 0) == 0) out.file = export_example(source.name.substr(9), scratch);
  else out.file = source.name;
  out.program = csg::read_program(out.file.string());
  out.postfix = csg::lower(out.program);
  return out;
}

std::string shell_quoted(const std::filesystem::path& p) {
  std::string out = "'";
  for (const char c : p.string()) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::filesystem::path scratch_folder(const std::string& key) {
  const auto dir = std::filesystem::temp_directory_path() / ("bspbench-csg-" + std::to_string(::getpid()) + "-" + key);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace bsp::experiments
