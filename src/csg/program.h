#pragma once
// OpenSCAD's CSG format, parsed: what `openscad -o model.csg model.scad` writes, a tree of module
// instantiations `[modifier] name(arguments) { children }` or `name(arguments);` with literal
// arguments (numbers, booleans, strings, undef, nested vectors) [OpenSCAD 2021.01 manual, "CSG
// export"]. Parsing is iterative (an explicit stack of open blocks), so nesting depth costs heap,
// not call stack; values are nested at most kMaxValueDepth deep.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace bsp::csg {

// A literal argument value. Vectors hold their elements in `items`.
struct Value {
  enum class Type : std::uint8_t { Undef, Bool, Number, String, Vector };
  Type type = Type::Undef;
  bool boolean = false;
  double number = 0;
  std::string text;
  std::vector<Value> items;
};

// OpenSCAD's modifier characters: '#' highlight (rendered), '!' root (only this subtree is
// rendered), '%' background (shown, not rendered), '*' disable (dropped). Several on one node
// combine: the later in this order wins (a disabled node is dropped whatever else it is marked).
enum class Modifier : std::uint8_t { None, Highlight, Root, Background, Disable };

struct Node {
  std::string name;
  std::vector<std::pair<std::string, Value>> args;  // positional arguments have an empty name
  std::vector<std::uint32_t> children;               // indices into Program::nodes
  std::uint32_t line = 0;                            // 1-based line of the name
  Modifier modifier = Modifier::None;

  // The named argument, or nullptr.
  const Value* arg(std::string_view key) const;
};

struct Program {
  std::string path;                  // as given; error messages name it
  std::vector<Node> nodes;
  std::vector<std::uint32_t> roots;  // the top-level statements, in order
};

inline constexpr int kMaxValueDepth = 64;

// Throws InputError "PATH:LINE: problem" for text that is not the CSG format.
Program parse_program(std::string_view text, std::string path);
// Reads and parses a file; throws InputError "PATH: problem" when it cannot be read.
Program read_program(const std::string& path);

}  // namespace bsp::csg
