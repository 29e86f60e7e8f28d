#include "io/mesh_claims.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <set>
#include <vector>

#include "common/errors.h"

namespace bsp {

namespace {

using u64 = std::uint64_t;

[[noreturn]] void fail(const std::string& path, const std::string& problem) { throw InputError(path + ": " + problem); }

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string bytes(std::size_t n) { return std::to_string(n) + (n == 1 ? " byte" : " bytes"); }

// a * b, or nullopt when it does not fit in 64 bits (no file is that large).
std::optional<u64> times(u64 a, u64 b) {
  u64 r;
  if (__builtin_mul_overflow(a, b, &r)) return std::nullopt;
  return r;
}

// An integer as `stream >> long long` reads a whole token: one optional sign, then digits ("+-5"
// is no integer to the stream, though from_chars would read -5 after a stripped '+').
std::optional<long long> to_integer(std::string_view t) {
  if (!t.empty() && t.front() == '+') {
    t.remove_prefix(1);
    if (!t.empty() && t.front() == '-') return std::nullopt;
  }
  long long v;
  const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
  if (ec != std::errc() || end != t.data() + t.size()) return std::nullopt;
  return v;
}

// Whitespace-separated tokens of a text, and its lines, as the C++ streams CGAL uses see them.
class Text {
 public:
  explicit Text(std::string_view s) : s_(s) {}
  bool at_end() const { return pos_ >= s_.size(); }
  std::size_t left() const { return at_end() ? 0 : s_.size() - pos_; }
  void skip_space() {
    while (!at_end() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  std::string_view token() {
    skip_space();
    const std::size_t start = pos_;
    while (!at_end() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    return s_.substr(start, pos_ - start);
  }
  std::string_view line() {
    const std::size_t start = std::min(pos_, s_.size());
    const std::size_t end = std::min(s_.find('\n', start), s_.size());
    pos_ = std::min(end + 1, s_.size());
    return s_.substr(start, end - start);
  }
  // OFF's comment rule (CGAL's skip_comment_OFF): skip whitespace and lines starting with '#'.
  void skip_off_comments() {
    for (skip_space(); !at_end() && s_[pos_] == '#'; skip_space()) line();
  }
  char peek() const { return at_end() ? '\0' : s_[pos_]; }
  void skip_char() { pos_ += !at_end(); }
  // A run of letters and digits, as CGAL reads OFF keywords.
  std::string_view word() {
    const std::size_t start = pos_;
    while (!at_end() && std::isalnum(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    return s_.substr(start, pos_ - start);
  }
  // An integer as `stream >> int` reads one: whitespace, a sign, digits, stopping at anything else.
  std::optional<long long> integer() {
    skip_space();
    const std::size_t start = pos_;
    if (!at_end() && (s_[pos_] == '+' || s_[pos_] == '-')) ++pos_;
    while (!at_end() && std::isdigit(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    return to_integer(s_.substr(start, pos_ - start));
  }

 private:
  std::string_view s_;
  std::size_t pos_ = 0;
};

// ---- OFF: "[ST][C][N][4][n]OFF" (or SKEL), counts, then one line per vertex and per face.

struct OffHeader {
  bool textures = false, colors = false, normals = false, homogeneous = false, n_dimensional = false, off = true;
};

std::optional<OffHeader> off_keyword(std::string_view k) {
  OffHeader h;
  std::size_t j = 0;
  if (k.substr(j, 2) == "ST") h.textures = true, j += 2;
  for (auto [flag, set] : {std::pair{'C', &h.colors}, {'N', &h.normals}, {'4', &h.homogeneous}, {'n', &h.n_dimensional}})
    if (j < k.size() && k[j] == flag) *set = true, ++j;
  if (k.substr(j) == "SKEL") h.off = false;
  else if (k.substr(j) != "OFF") return std::nullopt;
  return h;
}

// The numbers of a vertex or face line as CGAL reads them: after cutting the line at '#',
// `stream >> double` until one fails, which is libstdc++'s num_get: skip whitespace, then take the
// longest run that fits [sign] digits [. digits] [e|E [sign] digits] (a sign only first or right
// after the exponent letter, one point, one exponent letter and that only after a digit), and fail
// unless strtod reads all of that run to a finite number. So "1-2" is two numbers, and "05evr"
// none: its run "05e" is no number (a fuzzer finding: strtod reads 5 there, so a face line that
// to CGAL had no colour after a coloured one passed the colour check, and CGAL read one past the
// end of the line).
std::vector<double> off_numbers(std::string_view line) {
  line = line.substr(0, line.find('#'));
  std::vector<double> out;
  for (std::size_t pos = 0;;) {
    while (pos < line.size() && std::isspace(static_cast<unsigned char>(line[pos]))) ++pos;
    const std::size_t start = pos;
    const auto sign_at = [&](std::size_t i) { return i < line.size() && (line[i] == '+' || line[i] == '-'); };
    if (sign_at(pos)) ++pos;
    bool digits = false, point = false, exponent = false;
    for (; pos < line.size(); ++pos) {
      const char c = line[pos];
      if (std::isdigit(static_cast<unsigned char>(c))) digits = true;
      else if (c == '.' && !point && !exponent) point = true;
      else if ((c == 'e' || c == 'E') && digits && !exponent) {
        exponent = true;
        if (sign_at(pos + 1)) ++pos;
      } else break;
    }
    const std::string run(line.substr(start, pos - start));
    char* stop = nullptr;
    const double x = std::strtod(run.c_str(), &stop);
    if (run.empty() || *stop != '\0' || !std::isfinite(x)) return out;
    out.push_back(x);
  }
}

// CGAL reads the numbers after a line's coordinates or indices as a colour: one index into its
// 149-entry colour map, or three or four channels, integers 0..255 or fractions 0..1, cast to
// unsigned char. It indexes the map and the line without bounds checks and, once a colour was
// read, reads one from every later line, so anything else is rejected.
void check_off_color(const std::string& path, const std::vector<double>& nums, std::size_t first,
                     const std::string& what, bool& seen) {
  const std::size_t n = nums.size() - std::min(first, nums.size());
  const auto bad = [&] { fail(path, what + " has a colour CGAL cannot read"); };
  if (n == 0) {
    if (seen || first > nums.size()) bad();
    return;
  }
  seen = true;
  if (n == 1 && !(nums[first] >= 0 && nums[first] < 149)) bad();
  if (n == 2 || n > 4) bad();
  if (n == 1) return;
  const bool integers = std::all_of(nums.begin() + first, nums.begin() + first + 3, [](double c) { return c == std::floor(c); });
  for (std::size_t c = first; c < first + 3; ++c)
    if (!(nums[c] >= 0 && nums[c] <= (integers ? 255.0 : 1.0))) bad();
}

// A face line: its first number is how many vertex indices follow (CGAL sizes the face by it),
// each a vertex number CGAL casts to size_t.
void check_off_face(const std::string& path, const std::vector<double>& nums, long long vertices, u64 face,
                    const OffHeader& h, bool& colors_seen) {
  const std::string what = "face " + std::to_string(face);
  if (nums.empty()) fail(path, what + " does not start with its number of vertices");
  const double k = nums[0];
  const std::size_t listed = nums.size() - 1;
  if (!(k >= 0) || k > static_cast<double>(listed))
    fail(path, what + " claims " + number(k) + " vertices but its line lists " + std::to_string(listed));
  const auto size = static_cast<std::size_t>(k);
  for (std::size_t j = 1; j <= size; ++j)
    if (!(nums[j] >= 0 && nums[j] < static_cast<double>(vertices)))
      fail(path, what + " refers to vertex " + number(nums[j]) + " but the file has " + std::to_string(vertices));
  if (h.colors) check_off_color(path, nums, size + 1, what, colors_seen);
}

void check_off_vertex(const std::string& path, const std::vector<double>& nums, u64 vertex, const OffHeader& h,
                      bool& colors_seen) {
  const std::size_t coordinates = 3 + h.homogeneous;
  check_off_color(path, nums, coordinates * (1 + h.normals), "vertex " + std::to_string(vertex), colors_seen);
}

// The header as CGAL's File_header_OFF reads it: the keyword (a run of letters and digits, and
// the character after it), then the counts as ints, the first starting with a digit, or BINARY.
// Returns nullopt when CGAL rejects the header.
std::optional<std::pair<OffHeader, std::pair<long long, long long>>> off_counts(const std::string& path, Text& in) {
  in.skip_off_comments();
  const auto header = off_keyword(in.word());
  if (!header) return std::nullopt;
  if (header->textures) fail(path, "OFF with texture coordinates (ST) is not supported");
  in.skip_char();
  in.skip_off_comments();
  if (std::isalpha(static_cast<unsigned char>(in.peek())) && in.word() == "BINARY")
    fail(path, "binary OFF is not supported (convert it to ASCII OFF, PLY or STL)");
  if (!std::isdigit(static_cast<unsigned char>(in.peek()))) return std::nullopt;
  std::vector<long long> counts;
  for (int i = 0; i < 2 + header->n_dimensional + header->off; ++i) {
    const auto n = in.integer();
    if (!n) return std::nullopt;
    counts.push_back(*n);
  }
  // CGAL doubles the edge count in an int (File_header_OFF: halfedges = 2 * edges) before it reads
  // a vertex: a claim that overflows there is undefined behaviour, and no file of ours is that big.
  const long long edges = header->off ? counts.back() : 0;
  if (edges > INT_MAX / 2 || edges < INT_MIN / 2)
    fail(path, "header claims " + std::to_string(edges) + " edges, more than CGAL can count");
  return std::make_pair(*header, std::make_pair(counts[header->n_dimensional], counts[header->n_dimensional + 1]));
}

void check_off(const std::string& path, std::string_view content) {
  Text in(content);
  const auto parsed = off_counts(path, in);
  if (!parsed) return;
  const auto& [header, counts] = *parsed;
  const auto [vertices, faces] = counts;
  if (vertices < 0 || faces < 0) fail(path, "header claims a negative number of vertices or faces");
  bool vertex_colors = false, face_colors = false;
  for (u64 i = 0; i < static_cast<u64>(vertices) + static_cast<u64>(faces); ++i) {
    in.skip_off_comments();
    if (in.at_end())
      fail(path, "header claims " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                     " faces but the file has only " + bytes(content.size()) + ": " + std::to_string(i) +
                     " records");
    const std::vector<double> nums = off_numbers(in.line());
    if (i >= static_cast<u64>(vertices)) check_off_face(path, nums, vertices, i - vertices, header, face_colors);
    else if (header.colors) check_off_vertex(path, nums, i, header, vertex_colors);
  }
}

// ---- PLY: a text header of elements and their properties, then ASCII or binary records.

enum class PlyFormat { Ascii, Little, Big };

struct PlyProperty {
  int size = 0;        // bytes of a scalar, or of an item of a list
  int count_size = 0;  // bytes of a list's count; 0 for a scalar
  bool count_signed = false;
  bool real = false;  // the scalar or item is float or double
  bool is_signed = false;
};

struct PlyElement {
  std::string name;
  u64 count = 0;
  std::vector<PlyProperty> properties;
  std::set<std::string> typed;  // names whose first property check_ply_typed_property has seen
};

// Bytes of a PLY scalar type, sign in `is_signed`; 0 for a type CGAL does not know (it skips it).
int ply_type_size(std::string_view t, bool& is_signed) {
  is_signed = t == "char" || t == "int8" || t == "short" || t == "int16" || t == "int" || t == "int32";
  if (t == "char" || t == "int8" || t == "uchar" || t == "uint8") return 1;
  if (t == "short" || t == "int16" || t == "ushort" || t == "uint16") return 2;
  if (t == "int" || t == "int32" || t == "uint" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

bool is_real(std::string_view type) { return type.find("float") == 0 || type == "double"; }

// CGAL reads some properties as one type and dereferences a null pointer when the first property of
// that name has another (PLY_element::assign): a vertex's x, y and z as floating point, and a
// halfedge's source and target as uint32 (a fuzzer finding). Those must have the type CGAL reads.
void check_ply_typed_property(const std::string& path, PlyElement& e, std::string_view name,
                              std::string_view type, bool list) {
  const bool vertex = e.name == "vertex" || e.name == "vertices";
  const bool coordinate = vertex && (name == "x" || name == "y" || name == "z");
  const bool index = e.name == "halfedge" && (name == "source" || name == "target");
  if (!(coordinate || index) || !e.typed.insert(std::string(name)).second) return;
  const std::string what = list ? "a list" : std::string(type);
  if (coordinate && (list || !is_real(type)))
    fail(path, "PLY vertex coordinate " + std::string(name) + " is " + what + "; coordinates must be float or double");
  if (index && (list || (type != "uint" && type != "uint32")))
    fail(path, "PLY halfedge " + std::string(name) + " is " + what + "; it must be uint or uint32");
}

// As CGAL's header reader: a property of an unknown type, or a list whose length type is not an
// integer type, is left out (and its data not read).
void add_ply_property(const std::string& path, Text& words, std::vector<PlyElement>& elements) {
  if (elements.empty()) fail(path, "a PLY property comes before any element");
  PlyProperty p;
  bool is_signed = false;
  std::string_view type = words.token();
  const bool list = type == "list";
  if (list) {
    const std::string_view count_type = words.token();
    p.count_size = is_real(count_type) ? 0 : ply_type_size(count_type, p.count_signed);
    type = words.token();
    if (p.count_size == 0) return;
  }
  p.size = ply_type_size(type, is_signed);
  if (p.size == 0) return;
  p.real = is_real(type), p.is_signed = is_signed;
  check_ply_typed_property(path, elements.back(), words.token(), type, list);
  elements.back().properties.push_back(p);
}

void add_ply_element(const std::string& path, Text& words, std::vector<PlyElement>& elements) {
  PlyElement e{std::string(words.token()), 0, {}, {}};
  const std::string_view count = words.token();
  const auto n = to_integer(count);
  if (!n || *n < 0) fail(path, "element " + e.name + " has count '" + std::string(count) + "', not a count");
  e.count = static_cast<u64>(*n);
  elements.push_back(std::move(e));
}

std::optional<PlyFormat> ply_format(std::string_view line) {
  Text words(line);
  words.token();  // CGAL does not look at the tag
  const std::string_view f = words.token();
  if (words.token().empty()) return std::nullopt;  // no version
  if (f == "ascii") return PlyFormat::Ascii;
  if (f == "binary_little_endian") return PlyFormat::Little;
  if (f == "binary_big_endian") return PlyFormat::Big;
  return std::nullopt;
}

// The header's format and elements, leaving `in` where the records start; nullopt when CGAL
// rejects the header itself. As CGAL's PLY_reader::init: "ply" on line 1, the format on line 2,
// then element and property lines up to end_header; other keywords are ignored, an empty line ends
// the header as malformed.
std::optional<std::pair<PlyFormat, std::vector<PlyElement>>> ply_header(const std::string& path, Text& in) {
  if (Text(in.line()).token() != "ply") return std::nullopt;
  const auto format = ply_format(in.line());
  if (!format) return std::nullopt;
  std::vector<PlyElement> elements;
  while (!in.at_end()) {
    Text words(in.line());
    const std::string_view keyword = words.token();
    if (keyword.empty()) return std::nullopt;
    if (keyword == "element") add_ply_element(path, words, elements);
    else if (keyword == "property") add_ply_property(path, words, elements);
    else if (keyword == "end_header") return std::make_pair(*format, std::move(elements));
  }
  // CGAL reads on without end_header, into no data, as many records as the header claims.
  fail(path, "the PLY header has no end_header line");
}

// The fewest bytes one record can take: an ASCII value is at least a digit and a separator, a
// binary one its type's size, a list at least its count. A record without properties still
// counts one byte, so its count stays bounded by the file (CGAL loops over it).
u64 min_record_bytes(const PlyElement& e, PlyFormat format) {
  u64 n = 0;
  for (const auto& p : e.properties) n += format == PlyFormat::Ascii ? 2 : (p.count_size ? p.count_size : p.size);
  return std::max<u64>(n, 1);
}

void check_ply_counts(const std::string& path, const std::vector<PlyElement>& elements, PlyFormat format,
                      std::size_t left) {
  u64 need = 0;
  for (const auto& e : elements) {
    const auto n = times(e.count, min_record_bytes(e, format));
    if (!n || __builtin_add_overflow(need, *n, &need) || need > left + 1)
      fail(path, "header claims " + std::to_string(e.count) + " " + e.name + " records but the file has only " +
                     bytes(left) + " after its header");
  }
}

u64 read_binary_count(std::string_view data, std::size_t at, const PlyProperty& p, bool big, bool& negative) {
  u64 v = 0;
  for (int b = 0; b < p.count_size; ++b) {
    const auto byte = static_cast<unsigned char>(data[at + (big ? b : p.count_size - 1 - b)]);
    v = (v << 8) | byte;
  }
  negative = p.count_signed && (v >> (8 * p.count_size - 1)) != 0;
  return v;
}

[[noreturn]] void ply_data_ends(const std::string& path, const PlyElement& e, u64 record) {
  fail(path, "the data ends inside " + e.name + " " + std::to_string(record) + " (the header claims " +
                 std::to_string(e.count) + ")");
}

// Whether an ASCII token is one whole value as CGAL's PLY_read_number::read_ascii reads it: a real
// through CGAL's iformat (an optional '+', then the run of [0-9.eE+-], which sscanf must start to
// read), an integer through stream >> (a short for the one-byte types), which fails outside the
// type's range. One failed read leaves the stream bad and every later value uninitialised, so a
// list length read after it is garbage (a fuzzer finding: a 4.7 GB allocation for one face).
bool ply_ascii_value(std::string_view t, bool real, int size, bool is_signed) {
  if (real) {
    if (!t.empty() && t.front() == '+') t.remove_prefix(1);
    if (t.empty() || t.find_first_not_of("0123456789.eE+-") != std::string_view::npos) return false;
    const std::string run(t);
    char* stop = nullptr;
    std::strtod(run.c_str(), &stop);
    return stop != run.c_str();
  }
  const auto v = to_integer(t);
  if (!v) return false;
  const int bits = size == 1 ? 16 : 8 * size;
  const long long top = (1LL << (bits - is_signed)) - 1;
  return is_signed ? *v >= -top - 1 && *v <= top : *v >= -top && *v <= top;
}

// A token for an error line: at most 16 characters, anything unprintable as '?'.
std::string shown(std::string_view t) {
  std::string s(t.substr(0, 16));
  for (char& c : s)
    if (!std::isprint(static_cast<unsigned char>(c))) c = '?';
  return t.size() > 16 ? s + "..." : s;
}

// The next ASCII value of record `record` of `e`: it must be there and be one whole value.
void take_ply_ascii_value(const std::string& path, const PlyElement& e, u64 record, Text& text, bool real, int size,
                          bool is_signed) {
  const std::string_view token = text.token();
  if (token.empty()) ply_data_ends(path, e, record);
  if (!ply_ascii_value(token, real, size, is_signed))
    fail(path, e.name + " " + std::to_string(record) + " has '" + shown(token) + "', not " +
                   (real ? std::string("a real") : "a " + std::to_string(size == 1 ? 16 : 8 * size) + "-bit integer"));
}

// One list's length, checked against the bytes left after it. CGAL sizes the list by the length
// before it reads the entries, and a length read past the end of the data is garbage, so the data
// must not end there either.
void check_ply_list(const std::string& path, const PlyElement& e, u64 record, const PlyProperty& p,
                    std::string_view data, std::size_t& at, PlyFormat format) {
  u64 k = 0;
  bool negative = false;
  Text text(data.substr(at));
  if (format == PlyFormat::Ascii) {
    Text probe = text;
    take_ply_ascii_value(path, e, record, text, false, p.count_size, p.count_signed);
    const auto n = to_integer(probe.token());
    negative = *n < 0, k = static_cast<u64>(*n);
    at = data.size() - text.left();
  } else {
    if (data.size() - at < static_cast<std::size_t>(p.count_size)) ply_data_ends(path, e, record);
    k = read_binary_count(data, at, p, format == PlyFormat::Big, negative);
    at += p.count_size;
  }
  const std::size_t left = data.size() - at;
  const auto need = times(k, format == PlyFormat::Ascii ? 2 : p.size);
  // The last ASCII entry needs no separator after it; binary entries have their exact size.
  const std::size_t unseparated = format == PlyFormat::Ascii ? 1 : 0;
  if (negative || !need || *need > left + unseparated)
    fail(path, e.name + " " + std::to_string(record) + " has a list of " +
                   (negative ? "negative length" : std::to_string(k) + " entries") + " but only " + bytes(left) +
                   " remain");
  if (format == PlyFormat::Ascii) {
    for (u64 i = 0; i < k; ++i) take_ply_ascii_value(path, e, record, text, p.real, p.size, p.is_signed);
    at = data.size() - text.left();
  } else {
    at += *need;
  }
}

void skip_ply_scalar(const std::string& path, const PlyElement& e, u64 record, const PlyProperty& p,
                     std::string_view data, std::size_t& at, PlyFormat format) {
  if (format == PlyFormat::Ascii) {
    Text text(data.substr(at));
    take_ply_ascii_value(path, e, record, text, p.real, p.size, p.is_signed);
    at = data.size() - text.left();
  } else {
    if (data.size() - at < static_cast<std::size_t>(p.size)) ply_data_ends(path, e, record);
    at += p.size;
  }
}

// Walks every record the header declares, checking each list's length against the bytes left.
void check_ply_lists(const std::string& path, std::string_view data, const std::vector<PlyElement>& elements,
                     PlyFormat format) {
  std::size_t at = 0;
  for (const auto& e : elements)
    for (u64 r = 0; r < e.count; ++r)
      for (const auto& p : e.properties)
        (p.count_size ? check_ply_list : skip_ply_scalar)(path, e, r, p, data, at, format);
}

void check_ply(const std::string& path, std::string_view content) {
  Text in(content);
  auto header = ply_header(path, in);
  if (!header) return;  // CGAL rejects it
  const auto& [format, elements] = *header;
  const std::string_view data = content.substr(content.size() - in.left());
  check_ply_counts(path, elements, format, data.size());
  check_ply_lists(path, data, elements, format);
}

// ---- STL: binary is an 80-byte header, a uint32 triangle count and 50 bytes per triangle.
// CGAL reads a file not starting with "solid" as binary (and one that does as ASCII first).

void check_stl(const std::string& path, std::string_view content) {
  Text in(content);
  in.skip_space();
  const std::string_view rest = content.substr(content.size() - in.left());
  if (rest.substr(0, 5) == "solid" || content.size() < 84) return;
  u64 triangles = 0;
  for (int b = 3; b >= 0; --b) triangles = (triangles << 8) | static_cast<unsigned char>(content[80 + b]);
  if (84 + 50 * triangles > content.size())
    fail(path, "binary STL header claims " + std::to_string(triangles) + " triangles (" +
                   std::to_string(84 + 50 * triangles) + " bytes) but the file has only " + bytes(content.size()));
}

// ---- OBJ: indices count from 1; negative ones count back from the latest vertex; CGAL reads them
// into an int.

// Checks the integer a face token starts with (CGAL reads "7/2/5" as 7); false when the token
// does not start with one, which ends the face for CGAL too.
bool check_obj_index(const std::string& path, std::string_view token, u64 line, u64 vertices, long long& highest) {
  const std::size_t sign = token[0] == '+' || token[0] == '-';
  const std::size_t end = std::min(token.find_first_not_of("0123456789", sign), token.size());
  if (end == sign) return false;
  const std::string_view number = token.substr(0, end);
  const auto index = to_integer(number);
  const std::string where = "line " + std::to_string(line) + ": face index " + std::string(number);
  if (!index || *index > INT_MAX || *index < -static_cast<long long>(INT_MAX)) fail(path, where + " is too large");
  if (*index == 0) fail(path, where + " (OBJ counts vertices from 1)");
  if (*index < 0 && static_cast<u64>(-*index) > vertices)
    fail(path, where + " reaches back past the first vertex (" + std::to_string(vertices) + " so far)");
  highest = std::max(highest, *index);
  return true;
}

// The statements CGAL's OBJ reader accepts (CGAL/IO/OBJ.h); it rejects a file at any other.
bool cgal_reads_obj_statement(std::string_view keyword) {
  static const std::set<std::string_view> known = {
      "v", "vt", "vn", "f", "vp", "bevel", "lod", "ctech", "c_interp", "usemap", "usemtl", "stech", "d_interp",
      "mtllib", "shadow_obj", "trace_obj", "o", "g", "s", "p", "cstype", "deg", "step", "bmat", "con", "curv",
      "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end", "surf_1", "q0_1", "q1_1", "curv2d_1",
      "surf_2", "q0_2", "q1_2", "curv2d_2", "bsp", "bzp", "cdc", "cdp", "res"};
  return keyword.empty() || keyword.front() == '#' || known.count(keyword) != 0;
}

// Stops at a statement CGAL rejects: the file is malformed before any later index matters.
void check_obj(const std::string& path, std::string_view content) {
  Text in(content);
  u64 vertices = 0, line = 0, highest_line = 0;
  long long highest = 0;
  while (!in.at_end()) {
    Text words(in.line());
    ++line;
    const std::string_view keyword = words.token();
    if (!cgal_reads_obj_statement(keyword)) break;
    vertices += keyword == "v";
    if (keyword != "f") continue;
    const long long before = highest;
    for (std::string_view t = words.token(); !t.empty() && check_obj_index(path, t, line, vertices, highest);)
      t = words.token();
    if (highest != before) highest_line = line;
  }
  if (static_cast<u64>(highest) > vertices)
    fail(path, "line " + std::to_string(highest_line) + ": face index " + std::to_string(highest) +
                   " but the file has only " + std::to_string(vertices) + " vertices");
}

}  // namespace

void check_mesh_claims(const std::string& path, std::string_view content, const std::string& ext) {
  if (ext == ".off") check_off(path, content);
  else if (ext == ".ply") check_ply(path, content);
  else if (ext == ".stl") check_stl(path, content);
}

void check_obj_face_indices(const std::string& path, std::string_view content) { check_obj(path, content); }

}  // namespace bsp
