#include "cli/args.h"

#include <charconv>
#include <cmath>

#include "common/errors.h"

namespace bsp::cli {

std::optional<std::string> Args::option(std::string_view name) {
  auto values = options(name);
  if (values.size() > 1) throw UsageError("option " + std::string(name) + " given more than once");
  if (values.empty()) return std::nullopt;
  return values.front();
}

std::vector<std::string> Args::options(std::string_view name) {
  std::vector<std::string> values;
  for (std::size_t i = 0; i < args_.size();) {
    if (args_[i] != name) {
      ++i;
      continue;
    }
    if (i + 1 >= args_.size()) throw UsageError("option " + std::string(name) + " needs a value");
    values.push_back(args_[i + 1]);
    args_.erase(args_.begin() + static_cast<long>(i), args_.begin() + static_cast<long>(i) + 2);
  }
  return values;
}

bool Args::flag(std::string_view name) {
  bool found = false;
  for (std::size_t i = 0; i < args_.size();) {
    if (args_[i] == name) {
      found = true;
      args_.erase(args_.begin() + static_cast<long>(i));
    } else {
      ++i;
    }
  }
  return found;
}

std::string Args::required(std::string_view name) {
  auto v = option(name);
  if (!v) throw UsageError("missing option " + std::string(name));
  return *v;
}

std::optional<long long> Args::integer(std::string_view name, long long min, long long max) {
  auto text = option(name);
  if (!text) return std::nullopt;
  long long value = 0;
  auto [ptr, ec] = std::from_chars(text->data(), text->data() + text->size(), value);
  if (ec != std::errc() || ptr != text->data() + text->size() || value < min || value > max)
    throw UsageError("option " + std::string(name) + " wants an integer in [" + std::to_string(min) + ", " +
                     std::to_string(max) + "], not '" + *text + "'");
  return value;
}

std::optional<double> Args::real(std::string_view name) {
  auto text = option(name);
  if (!text) return std::nullopt;
  double value = 0;
  auto [ptr, ec] = std::from_chars(text->data(), text->data() + text->size(), value);
  if (ec != std::errc() || ptr != text->data() + text->size() || !std::isfinite(value))
    throw UsageError("option " + std::string(name) + " wants a finite number, not '" + *text + "'");
  return value;
}

std::vector<std::string> Args::positional() {
  std::vector<std::string> taken, rest;
  for (auto& a : args_) (a.rfind("--", 0) == 0 ? rest : taken).push_back(std::move(a));
  args_ = std::move(rest);
  return taken;
}

void Args::finish() const {
  if (!args_.empty()) throw UsageError("unexpected argument '" + args_.front() + "'");
}

std::optional<Vec3> Args::point(std::string_view name) {
  const std::optional<std::string> text = option(name);
  if (!text) return std::nullopt;
  double c[3] = {0, 0, 0};
  const char* p = text->data();
  const char* end = text->data() + text->size();
  for (int i = 0; i < 3; ++i) {
    auto [next, ec] = std::from_chars(p, end, c[i]);
    const bool separator_ok = i < 2 ? (next != end && *next == ',') : next == end;
    if (ec != std::errc() || !separator_ok || !std::isfinite(c[i]))
      throw UsageError("option " + std::string(name) + " wants X,Y,Z (three finite numbers), not '" + *text + "'");
    p = next + 1;
  }
  return Vec3{c[0], c[1], c[2]};
}

}  // namespace bsp::cli
