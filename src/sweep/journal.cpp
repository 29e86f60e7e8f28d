#include "sweep/journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "common/errors.h"

namespace bsp::sweep {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw InputError(path + ": " + what + " (" + std::strerror(errno) + ")");
}

}  // namespace

Journal::Journal(std::string path) : path_(std::move(path)) {
  const auto dir = std::filesystem::path(path_).parent_path();
  std::error_code ec;
  if (!dir.empty()) std::filesystem::create_directories(dir, ec);
  if (ec) throw InputError(path_ + ": cannot create directory " + dir.string() + " (" + ec.message() + ")");
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd_ < 0) fail(path_, "cannot open the journal");
  load();
}

Journal::~Journal() {
  if (fd_ >= 0) ::close(fd_);
}

void Journal::load() {
  std::ifstream in(path_, std::ios::binary);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto complete = text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1;
  if (complete < text.size()) {
    ++torn_;
    if (::ftruncate(fd_, static_cast<off_t>(complete)) != 0) fail(path_, "cannot drop the torn last line");
  }
  std::size_t line_no = 0;
  for (std::size_t begin = 0; begin < complete;) {
    const auto end = text.find('\n', begin);
    ++line_no;
    const std::string_view line(text.data() + begin, end - begin);
    begin = end + 1;
    if (line.empty()) continue;
    auto record = nlohmann::json::parse(line, nullptr, false);
    if (record.is_discarded() || !record.is_object() || !record.contains("key") || !record["key"].is_string())
      throw InputError(path_ + ": line " + std::to_string(line_no) +
                       " is not a journal record; delete the journal to start the sweep afresh");
    records_.push_back(std::move(record));
  }
}

void Journal::append(const nlohmann::json& record) {
  const std::string line = record.dump() + "\n";
  for (std::size_t written = 0; written < line.size();) {
    const auto n = ::write(fd_, line.data() + written, line.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(path_, "cannot append to the journal");
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd_) != 0) fail(path_, "cannot sync the journal");
}

}  // namespace bsp::sweep
