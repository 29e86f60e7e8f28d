#pragma once
// The programs csg runs and `bspbench csg` take, by name:
//   NAME:k=K   a generated program (generators/csg_programs.h: drilled-plate, sphere-union) of size K;
//   openscad:NAME   an example model OpenSCAD ships (/usr/share/openscad/examples), exported to CSG
//               by Debian's openscad into a scratch folder with its data files;
//   PATH.csg   a program file.
// Each becomes a file on disk, since OpenSCAD, the peer that renders the very same program, reads one.
#include <cstdint>
#include <filesystem>
#include <string>

#include "csg/lower.h"
#include "csg/program.h"

namespace bsp::experiments {

struct ProgramSource {
  std::string name;    // "drilled-plate", "openscad:example001" or the path
  std::uint64_t k = 0;  // a generated program's size; 0 otherwise
  bool generated() const { return k > 0; }
  std::string label() const;  // as given: NAME:k=K, openscad:NAME or the path
};

// Throws UsageError for a generated program without k (or with a k beyond its range) and for an
// unknown generator; a path is taken as it is.
ProgramSource parse_program_source(const std::string& text);

inline const std::filesystem::path kOpenScadExamples = "/usr/share/openscad/examples";

struct LoadedProgram {
  std::filesystem::path file;  // the program's file: the path, or one written under `scratch`
  csg::Program program;
  csg::Postfix postfix;
};

// Writes a generated program (from `seed`) or exports an OpenSCAD example under `scratch`, then parses
// and lowers it. Throws InputError naming the file (an unreadable or refused program) and
// InputError "openscad:NAME: ..." when openscad is missing or fails to export.
LoadedProgram load_program(const ProgramSource& source, std::uint64_t seed, const std::filesystem::path& scratch);

// A fresh folder for one job's files under the system's temporary folder; the caller removes it.
std::filesystem::path scratch_folder(const std::string& key);

// A path as one word of a POSIX shell command: in single quotes, each quote in it as '\''.
std::string shell_quoted(const std::filesystem::path& p);

}  // namespace bsp::experiments
