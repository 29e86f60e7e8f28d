#pragma once
// Runs one command so that nothing escapes it: every exception becomes one line
// "bspbench COMMAND: ..." on `err` and an exit code (main.cpp lists them). Header-only, so the tests
// can drive it with bodies that throw.
#include <algorithm>
#include <exception>
#include <new>
#include <ostream>
#include <string>
#include <string_view>

#include "common/errors.h"

namespace bsp::cli {

inline constexpr int kExitUsage = 2;     // bad arguments or bad input (UsageError, InputError)
inline constexpr int kExitInternal = 3;  // a plugin's exception, or anything else: a bug or the machine (out of memory, Embree)

// `usage` is printed after a UsageError; `body` returns the command's exit code.
template <class Body>
int run_guarded(std::string_view command, std::string_view usage, Body&& body, std::ostream& err) {
  // One line whatever the message holds (a plugin's text, dlerror()): its line breaks become spaces.
  const auto line = [&](std::string_view what) {
    std::string text(what);
    std::replace(text.begin(), text.end(), '\n', ' ');
    err << "bspbench " << command << ": " << text << "\n";
  };
  try {
    return body();
  } catch (const UsageError& e) {
    line(e.what());
    err << "usage: bspbench " << command << " " << usage << "\n";
    return kExitUsage;
  } catch (const InputError& e) {
    line(e.what());
    return kExitUsage;
  } catch (const PluginError& e) {
    line(e.what());
  } catch (const std::bad_alloc&) {
    line("internal error: out of memory");
  } catch (const std::exception& e) {
    line(std::string("internal error: ") + e.what());
  } catch (...) {
    line("internal error: an exception of unknown type");
  }
  return kExitInternal;
}

}  // namespace bsp::cli
