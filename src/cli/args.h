#pragma once
// A small command-line reader: options are taken out as they are asked for, and finish() rejects
// whatever is left, so a misspelt option is an error rather than silently ignored.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "geometry/vec3.h"

namespace bsp::cli {

// One line of a command's --help: an option as written in the usage line, and what it does.
struct OptionHelp {
  std::string_view option;
  std::string_view meaning;
};
using OptionHelps = std::vector<OptionHelp>;

class Args {
 public:
  explicit Args(std::vector<std::string> args) : args_(std::move(args)) {}

  std::optional<std::string> option(std::string_view name);  // --name VALUE, at most once
  std::vector<std::string> options(std::string_view name);   // --name VALUE, repeatable
  bool flag(std::string_view name);                           // --name
  std::string required(std::string_view name);
  // Typed readers; a malformed value is a UsageError naming the option.
  std::optional<long long> integer(std::string_view name, long long min, long long max);
  std::optional<double> real(std::string_view name);
  // --name X,Y,Z: three finite numbers.
  std::optional<Vec3> point(std::string_view name);
  // Takes the arguments not starting with "--"; call after every option has been taken.
  std::vector<std::string> positional();
  void finish() const;

 private:
  std::vector<std::string> args_;
};

}  // namespace bsp::cli
