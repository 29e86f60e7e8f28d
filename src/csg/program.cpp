#include "csg/program.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "common/errors.h"

namespace bsp::csg {

const Value* Node::arg(std::string_view key) const {
  for (const auto& [name, value] : args)
    if (name == key) return &value;
  return nullptr;
}

namespace {

// Characters to tokens, tracking the line for messages. Comments (// and /* */) are skipped, as
// OpenSCAD's own lexer does, so hand-written CSG files parse too.
class Lexer {
 public:
  Lexer(std::string_view text, const std::string& path) : s_(text), path_(&path) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(*path_ + ":" + std::to_string(line_) + ": " + problem);
  }
  std::uint32_t line() const { return line_; }
  bool at_end() { skip_space(); return i_ >= s_.size(); }
  char peek() { skip_space(); return i_ < s_.size() ? s_[i_] : '\0'; }
  bool accept(char c) {
    if (peek() != c) return false;
    ++i_;
    return true;
  }
  void expect(char c, std::string_view where) {
    if (!accept(c)) fail(std::string("expected '") + c + "' " + std::string(where) + ", found " + found());
  }
  // Letters, digits, '_' and a leading '$' (special variables).
  std::string identifier() {
    skip_space();
    const std::size_t start = i_;
    if (i_ < s_.size() && (s_[i_] == '$' || s_[i_] == '_' || std::isalpha(static_cast<unsigned char>(s_[i_])))) ++i_;
    while (i_ < s_.size() && (s_[i_] == '_' || std::isalnum(static_cast<unsigned char>(s_[i_])))) ++i_;
    if (start == i_) fail("expected a name, found " + found());
    return std::string(s_.substr(start, i_ - start));
  }
  bool at_identifier() {
    const char c = peek();
    return c == '$' || c == '_' || std::isalpha(static_cast<unsigned char>(c));
  }
  // A decimal number with an optional sign and exponent; "inf" and "nan" after a sign are OpenSCAD's
  // spelling of non-finite values, which no geometry argument may take (the evaluator refuses them).
  double number() {
    skip_space();
    const std::size_t start = i_;
    if (i_ < s_.size() && (s_[i_] == '-' || s_[i_] == '+')) ++i_;
    while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '.' ||
                              ((s_[i_] == '-' || s_[i_] == '+') && (s_[i_ - 1] == 'e' || s_[i_ - 1] == 'E'))))
      ++i_;
    const std::string_view token = s_.substr(start, i_ - start);
    const std::string_view body = token.substr(token.empty() || (token[0] != '-' && token[0] != '+') ? 0 : 1);
    const double sign = !token.empty() && token[0] == '-' ? -1.0 : 1.0;
    if (body == "inf") return sign * std::numeric_limits<double>::infinity();
    if (body == "nan") return std::numeric_limits<double>::quiet_NaN();
    double value = 0;
    const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
    if (body.empty() || ec != std::errc() || end != body.data() + body.size())
      fail("malformed number '" + std::string(token) + "'");
    return sign * value;
  }
  std::string string_literal() {
    expect('"', "to open a string");
    std::string out;
    while (i_ < s_.size() && s_[i_] != '"') {
      char c = s_[i_++];
      if (c == '\n') ++line_;
      if (c == '\\' && i_ < s_.size()) {
        c = s_[i_++];
        if (c == 'n') c = '\n';
        else if (c == 't') c = '\t';
      }
      out.push_back(c);
    }
    if (i_ >= s_.size()) fail("unterminated string");
    ++i_;
    return out;
  }
  std::string found() {
    if (at_end()) return "the end of the file";
    return "'" + std::string(1, s_[i_]) + "'";
  }

 private:
  void skip_space() {
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == '\n') {
        ++line_;
        ++i_;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        ++i_;
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '/') {
        while (i_ < s_.size() && s_[i_] != '\n') ++i_;
      } else if (c == '/' && i_ + 1 < s_.size() && s_[i_ + 1] == '*') {
        const std::size_t end = s_.find("*/", i_ + 2);
        if (end == std::string_view::npos) fail("unterminated comment");
        for (std::size_t k = i_; k < end; ++k) line_ += s_[k] == '\n';
        i_ = end + 2;
      } else {
        return;
      }
    }
  }

  std::string_view s_;
  const std::string* path_;  // a pointer, so a lexer can be saved and restored
  std::size_t i_ = 0;
  std::uint32_t line_ = 1;
};

// One value; vectors nest through an explicit stack of open vectors.
Value parse_value(Lexer& lex) {
  std::vector<Value> open;
  for (;;) {
    Value v;
    if (lex.accept('[')) {
      if (static_cast<int>(open.size()) >= kMaxValueDepth)
        lex.fail("vectors nested deeper than " + std::to_string(kMaxValueDepth));
      v.type = Value::Type::Vector;
      if (!lex.accept(']')) {
        open.push_back(std::move(v));
        continue;
      }
    } else if (lex.peek() == '"') {
      v.type = Value::Type::String;
      v.text = lex.string_literal();
    } else if (lex.at_identifier()) {
      const std::string word = lex.identifier();
      if (word == "true" || word == "false") {
        v.type = Value::Type::Bool;
        v.boolean = word == "true";
      } else if (word == "inf" || word == "nan") {
        v.type = Value::Type::Number;
        v.number = word == "inf" ? std::numeric_limits<double>::infinity() : std::numeric_limits<double>::quiet_NaN();
      } else if (word != "undef") {
        lex.fail("expected a literal value, found '" + word + "' (the CSG format holds no expressions)");
      }
    } else {
      v.type = Value::Type::Number;
      v.number = lex.number();
    }
    // Close every vector this value completes.
    for (;;) {
      if (open.empty()) return v;
      open.back().items.push_back(std::move(v));
      if (lex.accept(',')) break;
      lex.expect(']', "to close a vector");
      v = std::move(open.back());
      open.pop_back();
    }
  }
}

Modifier parse_modifier(Lexer& lex) {
  if (lex.accept('%')) return Modifier::Background;
  if (lex.accept('#')) return Modifier::Highlight;
  if (lex.accept('!')) return Modifier::Root;
  if (lex.accept('*')) return Modifier::Disable;
  return Modifier::None;
}

void parse_args(Lexer& lex, Node& node) {
  lex.expect('(', "after the module name '" + node.name + "'");
  if (lex.accept(')')) return;
  do {
    std::string key;
    if (lex.at_identifier()) {
      // A name followed by '=' is a named argument; otherwise the word is a value (true, undef).
      Lexer saved = lex;
      std::string word = lex.identifier();
      if (lex.accept('=')) key = std::move(word);
      else lex = saved;
    }
    node.args.emplace_back(std::move(key), parse_value(lex));
  } while (lex.accept(','));
  lex.expect(')', "to close the arguments of '" + node.name + "'");
}

}  // namespace

Program parse_program(std::string_view text, std::string path) {
  Program program;
  program.path = std::move(path);
  Lexer lex(text, program.path);
  std::vector<std::uint32_t> open;  // nodes whose '{' block is being read
  for (;;) {
    if (lex.at_end()) {
      if (!open.empty()) lex.fail("'" + program.nodes[open.back()].name + "' block not closed");
      return program;
    }
    if (lex.accept('}')) {
      if (open.empty()) lex.fail("'}' closes no block");
      open.pop_back();
      continue;
    }
    if (lex.accept(';')) continue;  // an empty statement
    Node node;
    // Modifiers combine as OpenSCAD's flags do: disabled over background over root over highlight.
    for (Modifier m; (m = parse_modifier(lex)) != Modifier::None;) node.modifier = std::max(node.modifier, m);
    node.line = lex.line();
    node.name = lex.identifier();
    parse_args(lex, node);
    const auto index = static_cast<std::uint32_t>(program.nodes.size());
    (open.empty() ? program.roots : program.nodes[open.back()].children).push_back(index);
    program.nodes.push_back(std::move(node));
    if (lex.accept('{')) open.push_back(index);
    else lex.expect(';', "or '{' after '" + program.nodes[index].name + "(...)'");
  }
}

Program read_program(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path + ": cannot read the file");
  return parse_program(text.str(), path);
}

}  // namespace bsp::csg
