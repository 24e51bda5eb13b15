// Avenues — VRML97 worlds and classic-encoded X3D (see vrml_scene.h).
#include "plans/vrml_scene.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <set>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "core/affine.h"
#include "core/file_name.h"
#include "core/text_encoding.h"
#include "plans/obj_materials.h"
#include "plans/polygon_triangulation.h"
#include "plans/primitive_shapes.h"

namespace avenues {

namespace {

namespace fs = std::filesystem;

constexpr std::uintmax_t kMaxBytes = std::uintmax_t(1) << 28;  ///< a file, or what a gzipped one inflates to
constexpr int kMaxDepth = 1000;                               ///< nodes within nodes
constexpr int kMaxInlines = 8;                                ///< worlds within worlds
constexpr int kAround = 24;                                   ///< segments round a sphere, cylinder or cone
/// Nodes visited, USEs followed each time: a chain of groups each USEing the one before
/// twice is 2^n visits in a few lines.
constexpr long kMaxVisits = 2'000'000;
/// Nodes made by expanding PROTO instances (a PROTO whose body holds two instances of the
/// one before doubles them at each declaration).
constexpr long kMaxExpanded = 2'000'000;

/// Up to `limit` bytes of `path` (nullopt when it cannot be read), inflated when gzipped (to
/// at most `inflated` bytes: beyond, `too_big` is set).
std::optional<std::string> file_bytes(const std::string& path, std::uintmax_t limit, std::uintmax_t inflated,
                                      bool* too_big = nullptr) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  std::string bytes(size_t(std::min<std::uintmax_t>(fs::file_size(path, ec), limit)), '\0');
  in.read(bytes.data(), std::streamsize(bytes.size()));
  bytes.resize(size_t(in.gcount()));
  if (bytes.size() < 2 || uint8_t(bytes[0]) != 0x1F || uint8_t(bytes[1]) != 0x8B) return bytes;
  z_stream z{};
  if (inflateInit2(&z, 16 + MAX_WBITS) != Z_OK) return std::nullopt;
  std::string out;
  z.next_in = reinterpret_cast<Bytef*>(bytes.data());
  z.avail_in = uInt(std::min<size_t>(bytes.size(), UINT32_MAX));
  char chunk[1 << 16];
  int r = Z_OK;
  while (r == Z_OK && out.size() < inflated) {
    z.next_out = reinterpret_cast<Bytef*>(chunk);
    z.avail_out = sizeof chunk;
    r = inflate(&z, Z_NO_FLUSH);
    out.append(chunk, sizeof chunk - z.avail_out);
    if (r == Z_BUF_ERROR && z.avail_in == 0) break;  // cut short (or only its head was read)
  }
  inflateEnd(&z);
  if (out.size() >= inflated && too_big) *too_big = true;
  if (r != Z_OK && r != Z_STREAM_END && r != Z_BUF_ERROR) return std::nullopt;
  return out;
}

/// Whether the text's first line says VRML97 or classic X3D; `version` gets the line.
bool vrml_header(std::string_view text, std::string* line = nullptr) {
  const size_t end = std::min(text.find('\n'), size_t(80));
  const std::string_view first = text.substr(0, std::min(end, text.size()));
  if (line) *line = std::string(first.substr(0, first.find_last_not_of(" \t\r") + 1));
  return first.starts_with("#VRML V2.0") || first.starts_with("#X3D V3") || first.starts_with("#X3D V4");
}

// ---- The syntax ----

struct Token {
  enum Kind : uint8_t { End, Word, Number, String, LBrace, RBrace, LBracket, RBracket } kind = End;
  std::string_view text;  ///< a word as written; a string's contents, escapes resolved in `str`
  std::string str;
  double number = 0;
  size_t line = 0;
};

class Lexer {
 public:
  Lexer(std::string_view text, const std::string& file) : s_(text), file_(file) {}

  const Token& peek(size_t k = 0) {
    while (ahead_.size() <= k) ahead_.push_back(scan());
    return ahead_[k];
  }
  Token next() {
    peek();
    Token t = std::move(ahead_.front());
    ahead_.pop_front();
    return t;
  }
  [[noreturn]] void fail(size_t line, const std::string& what) const {
    throw std::runtime_error("cannot read model " + file_ + ":" + std::to_string(line) + ": " + what);
  }

 private:
  static bool word_char(char c) {
    return !std::isspace(uint8_t(c)) && c != '{' && c != '}' && c != '[' && c != ']' && c != '"' && c != ',' &&
           c != '#' && uint8_t(c) > 0x20;
  }
  Token scan() {
    for (;;) {  // white space, commas and comments
      while (pos_ < s_.size() && (std::isspace(uint8_t(s_[pos_])) || s_[pos_] == ',' || s_[pos_] == '\0')) {
        if (s_[pos_] == '\n') ++line_;
        ++pos_;
      }
      if (pos_ < s_.size() && s_[pos_] == '#') {
        while (pos_ < s_.size() && s_[pos_] != '\n') ++pos_;
        continue;
      }
      break;
    }
    Token t;
    t.line = line_;
    if (pos_ >= s_.size()) return t;
    const char c = s_[pos_];
    const size_t start = pos_;
    if (c == '{' || c == '}' || c == '[' || c == ']') {
      ++pos_;
      t.kind = c == '{' ? Token::LBrace : c == '}' ? Token::RBrace : c == '[' ? Token::LBracket : Token::RBracket;
      t.text = s_.substr(start, 1);
      return t;
    }
    if (c == '"') {
      t.kind = Token::String;
      for (++pos_; pos_ < s_.size() && s_[pos_] != '"'; ++pos_) {
        if (s_[pos_] == '\\' && pos_ + 1 < s_.size()) ++pos_;
        if (s_[pos_] == '\n') ++line_;
        t.str += s_[pos_];
      }
      if (pos_ >= s_.size()) fail(t.line, "a string begun here is never closed");
      ++pos_;
      return t;
    }
    const bool sign = c == '+' || c == '-';
    const char d = sign && pos_ + 1 < s_.size() ? s_[pos_ + 1] : c;
    if (std::isdigit(uint8_t(d)) || (d == '.' && pos_ + 1 + sign < s_.size() && std::isdigit(uint8_t(s_[pos_ + 1 + sign])))) {
      t.kind = Token::Number;
      size_t at = pos_ + (c == '+');
      const bool negative = c == '-';
      const size_t digits = pos_ + sign;
      if (digits + 1 < s_.size() && s_[digits] == '0' && (s_[digits + 1] == 'x' || s_[digits + 1] == 'X')) {
        uint64_t v = 0;  // SFInt32 and SFImage may be written in hexadecimal
        const auto [end, ec] = std::from_chars(s_.data() + digits + 2, s_.data() + s_.size(), v, 16);
        if (ec != std::errc()) fail(t.line, "'" + std::string(s_.substr(start, 12)) + "' is not a number");
        t.number = negative ? -double(v) : double(v);
        pos_ = size_t(end - s_.data());
      } else {
        const auto [end, ec] = std::from_chars(s_.data() + at, s_.data() + s_.size(), t.number);
        if (ec != std::errc() || !std::isfinite(t.number))
          fail(t.line, "'" + std::string(s_.substr(start, std::min<size_t>(24, s_.size() - start))) + "' is not a number");
        pos_ = size_t(end - s_.data());
      }
      // A number runs into what follows only where a separator is missing ("1.5e": cut short).
      if (pos_ < s_.size() && word_char(s_[pos_]) && !(s_[pos_] == '-' || s_[pos_] == '+'))
        fail(t.line, "'" + std::string(s_.substr(start, std::min<size_t>(24, s_.size() - start))) + "' is not a number");
      t.text = s_.substr(start, pos_ - start);
      return t;
    }
    t.kind = Token::Word;
    while (pos_ < s_.size() && word_char(s_[pos_])) ++pos_;
    if (pos_ == start) fail(t.line, "the byte " + std::to_string(int(uint8_t(c))) + " is no part of VRML's syntax");
    t.text = s_.substr(start, pos_ - start);
    return t;
  }

  std::string_view s_;
  const std::string& file_;
  size_t pos_ = 0, line_ = 1;
  std::deque<Token> ahead_;  ///< peeked: a deque, so that peeking further keeps references to those before
};

struct VNode;
using NodeRef = std::shared_ptr<const VNode>;

/// A field's value, whatever its type: its numbers (TRUE and FALSE as 1 and 0), strings
/// and nodes, in order.
struct Value {
  std::vector<double> numbers;
  std::vector<std::string> strings;
  std::vector<NodeRef> nodes;
  size_t line = 0;
  std::string is;  ///< in a PROTO's body, `field IS name`: the instance's field `name` stands here
};

/// A PROTO declared in the file: its fields' defaults and the first node of its body, the
/// one an instance stands for (VRML97 4.8.3: the others are not drawn), IS left in it.
struct Proto {
  std::map<std::string, Value, std::less<>> defaults;
  NodeRef body;
};

struct VNode {
  std::string type;
  size_t line = 0;
  std::vector<std::pair<std::string, Value>> fields;
  const Value* field(std::string_view name) const {
    for (const auto& [n, v] : fields)
      if (n == name) return &v;
    return nullptr;
  }
  double number(std::string_view name, double otherwise) const {
    const Value* v = field(name);
    return v && !v->numbers.empty() ? v->numbers[0] : otherwise;
  }
  Vec3 vec(std::string_view name, Vec3 otherwise) const {
    const Value* v = field(name);
    return v && v->numbers.size() >= 3 ? Vec3{v->numbers[0], v->numbers[1], v->numbers[2]} : otherwise;
  }
  NodeRef node(std::string_view name) const {
    const Value* v = field(name);
    return v && !v->nodes.empty() ? v->nodes[0] : nullptr;
  }
};

/// A whole file read as nodes, generically (see vrml_scene.h).
class Parser {
 public:
  Parser(std::string_view text, const std::string& file) : lx_(text, file) {}

  std::vector<NodeRef> world(std::set<std::string>& protos) {
    std::vector<NodeRef> roots;
    while (lx_.peek().kind != Token::End) {
      if (statement(protos)) continue;
      if (NodeRef n = node(0)) roots.push_back(std::move(n));
    }
    protos.insert(externs_.begin(), externs_.end());
    return roots;
  }

 private:
  /// PROTO, EXTERNPROTO, ROUTE and X3D's header statements: passed over. True when one was.
  bool statement(std::set<std::string>& protos) {
    const Token& t = lx_.peek();
    if (t.kind != Token::Word) return false;
    const std::string_view w = t.text;
    if (w == "PROTO") {
      proto();
      return true;
    }
    if (w == "EXTERNPROTO") {  // its body is in another file: instances are left out
      const Token kw = lx_.next();
      const Token name = lx_.next();
      if (name.kind != Token::Word) lx_.fail(kw.line, "EXTERNPROTO without a name");
      externs_.insert(std::string(name.text));
      protos_.erase(std::string(name.text));
      skip_balanced(Token::LBracket, Token::RBracket, kw);
      (void)value(1);  // its url(s)
      return true;
    }
    if (w == "ROUTE") {
      for (int k = 0; k < 4; ++k) lx_.next();  // ROUTE a.b TO c.d
      return true;
    }
    static const std::pair<std::string_view, int> kHeader[] = {{"PROFILE", 2}, {"COMPONENT", 2}, {"META", 3}, {"UNIT", 4}};
    for (const auto& [keyword, tokens] : kHeader)
      if (w == keyword) {
        for (int k = 0; k < tokens; ++k) lx_.next();
        return true;
      }
    if (w == "IMPORT" || w == "EXPORT") {  // IMPORT a.b AS c, EXPORT a AS b
      lx_.next(), lx_.next();
      if (lx_.peek().kind == Token::Word && lx_.peek().text == "AS") lx_.next(), lx_.next();
      return true;
    }
    (void)protos;
    return false;
  }

  /// PROTO name [ interface ] { body }: its fields' defaults, and its body's first node.
  void proto() {
    const Token kw = lx_.next();
    const Token name = lx_.next();
    if (name.kind != Token::Word) lx_.fail(kw.line, "PROTO without a name");
    Proto p;
    const Token open = lx_.next();
    if (open.kind != Token::LBracket) lx_.fail(open.line, "PROTO " + std::string(name.text) + " wants '[' here");
    for (;;) {
      const Token& d = lx_.peek();
      if (d.kind == Token::RBracket) break;
      if (d.kind == Token::End) lx_.fail(open.line, "PROTO " + std::string(name.text) + "'s interface begun here is never closed");
      const Token kind = lx_.next(), type = lx_.next(), field = lx_.next();
      if (kind.kind != Token::Word || type.kind != Token::Word || field.kind != Token::Word)
        lx_.fail(kind.line, "PROTO " + std::string(name.text) + ": a declaration (field, exposedField, eventIn or eventOut, a type, a name) was expected");
      const std::string_view k = kind.text;
      if (k == "field" || k == "exposedField" || k == "initializeOnly" || k == "inputOutput")
        p.defaults[std::string(field.text)] = value(1);
      else if (k != "eventIn" && k != "eventOut" && k != "inputOnly" && k != "outputOnly")
        lx_.fail(kind.line, "PROTO " + std::string(name.text) + ": '" + std::string(k) + "' is no kind of declaration");
    }
    lx_.next();  // ]
    // The body: nodes and statements, its names its own (a DEF within it is not seen outside).
    const Token brace = lx_.next();
    if (brace.kind != Token::LBrace) lx_.fail(brace.line, "PROTO " + std::string(name.text) + " wants '{' here");
    auto outer = defs_;
    std::set<std::string> unused;
    for (;;) {
      const Token& t = lx_.peek();
      if (t.kind == Token::RBrace) break;
      if (t.kind == Token::End) lx_.fail(brace.line, "PROTO " + std::string(name.text) + "'s body begun here is never closed");
      if (statement(unused)) continue;
      NodeRef n = node(1);
      if (!p.body) p.body = std::move(n);
    }
    lx_.next();  // }
    defs_ = std::move(outer);
    externs_.erase(std::string(name.text));
    protos_[std::string(name.text)] = std::move(p);
  }

  /// An instance of `p`: its body's first node, each `IS` in it given the instance's value
  /// of that field (or the PROTO's default). Parts with no IS below them are shared, not
  /// copied; `made` keeps a node USEd twice in the body one node in the instance.
  NodeRef instantiate(const NodeRef& n, const Proto& p, const VNode& instance, std::map<const VNode*, NodeRef>& made) {
    if (!n) return nullptr;
    if (const auto it = made.find(n.get()); it != made.end()) return it->second;
    auto copy = std::make_shared<VNode>();
    copy->type = n->type;
    copy->line = n->line;
    bool changed = false;
    for (const auto& [field, v] : n->fields) {
      if (!v.is.empty()) {
        changed = true;
        if (const Value* given = instance.field(v.is)) copy->fields.emplace_back(field, *given);
        else if (const auto d = p.defaults.find(v.is); d != p.defaults.end()) copy->fields.emplace_back(field, d->second);
        continue;  // an event, or a field the PROTO does not declare: nothing stands here
      }
      Value w = v;
      for (NodeRef& c : w.nodes) {
        NodeRef d = instantiate(c, p, instance, made);
        changed = changed || d != c;
        c = std::move(d);
      }
      copy->fields.emplace_back(field, std::move(w));
    }
    if (changed && ++expanded_ > kMaxExpanded)
      lx_.fail(instance.line, "PROTO instances expand to more than " + std::to_string(kMaxExpanded) + " nodes");
    NodeRef out = changed ? NodeRef(std::move(copy)) : n;
    made[n.get()] = out;
    return out;
  }

  void skip_balanced(Token::Kind open, Token::Kind close, const Token& what) {
    const Token first = lx_.next();
    if (first.kind != open)
      lx_.fail(first.line, std::string(what.text) + " wants '" + (open == Token::LBrace ? "{" : "[") + "' here");
    for (int depth = 1; depth > 0;) {
      const Token t = lx_.next();
      if (t.kind == Token::End) lx_.fail(first.line, std::string(what.text) + "'s block begun here is never closed");
      depth += t.kind == open ? 1 : t.kind == close ? -1 : 0;
    }
  }

  bool starts_node() {
    const Token& t = lx_.peek();
    if (t.kind != Token::Word) return false;
    if (t.text == "DEF" || t.text == "USE") return true;
    return lx_.peek(1).kind == Token::LBrace;
  }

  NodeRef node(int depth) {
    if (depth > kMaxDepth) lx_.fail(lx_.peek().line, "nodes nested more than " + std::to_string(kMaxDepth) + " deep");
    const Token t = lx_.next();
    if (t.kind != Token::Word) lx_.fail(t.line, "a node was expected, not '" + std::string(t.text) + "'");
    if (t.text == "NULL") return nullptr;
    if (t.text == "DEF" || t.text == "USE") {
      const Token name = lx_.next();
      if (name.kind != Token::Word) lx_.fail(t.line, std::string(t.text) + " without a name");
      if (t.text == "USE") {
        const auto it = defs_.find(std::string(name.text));
        if (it == defs_.end()) lx_.fail(t.line, "USE " + std::string(name.text) + ": no node before it is DEF " + std::string(name.text));
        return it->second;
      }
      NodeRef n = node(depth);
      defs_[std::string(name.text)] = n;
      return n;
    }
    const Token open = lx_.next();
    if (open.kind != Token::LBrace) lx_.fail(t.line, "'" + std::string(t.text) + "' is no node (no '{' after it)");
    auto n = std::make_shared<VNode>();
    n->type = std::string(t.text);
    n->line = t.line;
    std::set<std::string> unused;
    for (;;) {
      const Token& f = lx_.peek();
      if (f.kind == Token::RBrace) break;
      if (f.kind == Token::End) lx_.fail(t.line, "node " + n->type + " begun here is never closed");
      if (statement(unused)) continue;
      if (f.kind != Token::Word) lx_.fail(f.line, "a field of " + n->type + " was expected, not '" + std::string(f.text) + "'");
      std::string name(lx_.next().text);
      n->fields.emplace_back(std::move(name), value(depth + 1));
    }
    lx_.next();  // }
    if (const auto p = protos_.find(n->type); p != protos_.end()) {
      std::map<const VNode*, NodeRef> made;
      return instantiate(p->second.body, p->second, *n, made);
    }
    return n;
  }

  Value value(int depth) {
    Value v;
    v.line = lx_.peek().line;
    auto atom = [&](const Token& t) {
      if (t.kind == Token::Number) return v.numbers.push_back(t.number), true;
      if (t.kind == Token::String) return v.strings.push_back(t.str), true;
      if (t.kind == Token::Word && (t.text == "TRUE" || t.text == "FALSE")) return v.numbers.push_back(t.text == "TRUE"), true;
      return false;
    };
    const Token& t = lx_.peek();
    if (t.kind == Token::LBracket) {
      const Token open = lx_.next();
      for (;;) {
        const Token& e = lx_.peek();
        if (e.kind == Token::RBracket) break;
        if (e.kind == Token::End) lx_.fail(open.line, "a list begun here is never closed");
        if (atom(e)) {
          lx_.next();
        } else if (starts_node()) {
          if (NodeRef n = node(depth)) v.nodes.push_back(std::move(n));
        } else if (e.kind == Token::Word) {
          std::set<std::string> unused;
          if (!statement(unused)) lx_.next();  // NULL, or a word no list holds: passed over
        } else {
          lx_.fail(e.line, "'" + std::string(e.text) + "' in a list");
        }
      }
      lx_.next();  // ]
      return v;
    }
    if (t.kind == Token::Word && t.text == "IS") {  // in a PROTO's body: the instance's field
      lx_.next();
      const Token name = lx_.next();
      if (name.kind != Token::Word) lx_.fail(name.line, "IS without a field's name");
      v.is = std::string(name.text);
      return v;
    }
    if (starts_node()) {
      if (NodeRef n = node(depth)) v.nodes.push_back(std::move(n));
      return v;
    }
    if (t.kind == Token::Word && t.text == "NULL") {
      lx_.next();
      return v;
    }
    while (atom(lx_.peek())) lx_.next();
    return v;  // nothing: the next word is the next field (a Script's declarations)
  }

  Lexer lx_;
  std::map<std::string, NodeRef, std::less<>> defs_;
  std::map<std::string, Proto, std::less<>> protos_;
  std::set<std::string> externs_;  ///< EXTERNPROTOs, whose instances are left out
  long expanded_ = 0;
};

// ---- The world ----

/// The shapes of the worlds, placed in VRML's space, then turned into Avenues'.
class World {
 public:
  World(const std::string& path, const ImportOptions& options) : path_(path), options_(options) {}

  ImportedScene read() {
    const auto t0 = std::chrono::steady_clock::now();
    out_.path = path_;
    out_.format = "VRML97 (Avenues' reader)";
    out_.nodes.push_back({});
    out_.nodes[0].name = "root";
    // VRML's y up, in metres, unless told otherwise: its (x, y, z) is Avenues' (x, −z, y).
    const char up = options_.axes.up.value_or('y');
    const double k = options_.axes.metres_per_unit.value_or(1);
    Affine3 turn = Affine3::scaling({k, k, k});  // z up: as it is
    if (up == 'y') turn.m = {{{k, 0, 0, 0}, {0, 0, -k, 0}, {0, k, 0, 0}}};  // (x, −z, y), exactly
    else if (up == 'x') turn.m = {{{0, 0, -k, 0}, {0, k, 0, 0}, {k, 0, 0, 0}}};  // (−z, y, x)
    read_world(path_, turn, 0);
    for (const auto& [what, n] : left_out_) warn(std::to_string(n) + " " + what + " left out");
    size_t triangles = 0;
    for (const ImportedNode& n : out_.nodes) triangles += n.triangles.size();
    if (triangles == 0)
      throw std::runtime_error("cannot read model " + path_ + ": it draws no triangle Avenues can use" +
                               (out_.warnings.empty() ? std::string() : " (" + out_.warnings.back() + ")"));
    out_.import_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return std::move(out_);
  }

 private:
  void warn(const std::string& what) { out_.warnings.push_back(path_ + ": " + what); }

  void read_world(const std::string& file, const Affine3& place, int inlines) {
    bool too_big = false;
    const std::optional<std::string> bytes = file_bytes(file, kMaxBytes, kMaxBytes, &too_big);
    if (!bytes) throw std::runtime_error("cannot read model " + file + ": it cannot be read (or its gzip is broken)");
    if (too_big) throw std::runtime_error("cannot read model " + file + ": it inflates to more than 256 MiB");
    const std::string text = utf8_of_text(*bytes);
    std::string first;
    if (!vrml_header(text, &first)) {
      if (first.starts_with("#VRML V1.0"))
        throw std::runtime_error("cannot read model " + file + ":1: VRML 1.0 is not read (VRML97, '#VRML V2.0', is)");
      throw std::runtime_error("cannot read model " + file + ":1: not VRML97 or classic X3D: its first line is '" +
                               first.substr(0, 40) + "', not '#VRML V2.0 utf8'");
    }
    Parser parser(text, file);
    const std::vector<NodeRef> roots = parser.world(protos_);
    std::error_code ec;
    const fs::path canonical = fs::weakly_canonical(file, ec);
    files_.push_back(ec ? file : canonical.string());  // as Inlines are compared
    for (const NodeRef& n : roots) visit(n, place, inlines, 0);
    files_.pop_back();
  }

  void visit(const NodeRef& n, const Affine3& place, int inlines, int depth) {
    if (!n || depth > kMaxDepth) return;
    if (++visits_ > kMaxVisits)
      throw std::runtime_error("cannot read model " + path_ + ": its nodes, each USE counted again, number more than " +
                               std::to_string(kMaxVisits));
    const std::string& t = n->type;
    auto children = [&](std::string_view field, const Affine3& p) {
      if (const Value* v = n->field(field))
        for (const NodeRef& c : v->nodes) visit(c, p, inlines, depth + 1);
    };
    if (t == "Transform") {
      const Vec3 c = n->vec("center", {0, 0, 0});
      const Value* r = n->field("rotation");
      const Value* so = n->field("scaleOrientation");
      const auto turn = [](const Value* v, double sign) {
        return v && v->numbers.size() >= 4 ? Affine3::rotation({v->numbers[0], v->numbers[1], v->numbers[2]}, sign * v->numbers[3])
                                           : Affine3{};
      };
      const Affine3 local = Affine3::translation(n->vec("translation", {0, 0, 0})) * Affine3::translation(c) * turn(r, 1) *
                            turn(so, 1) * Affine3::scaling(n->vec("scale", {1, 1, 1})) * turn(so, -1) *
                            Affine3::translation(-1.0 * c);
      children("children", place * local);
    } else if (t == "Switch") {
      const int which = int(n->number("whichChoice", -1));
      const Value* v = n->field("choice") ? n->field("choice") : n->field("children");
      if (v && which >= 0 && size_t(which) < v->nodes.size()) visit(v->nodes[size_t(which)], place, inlines, depth + 1);
    } else if (t == "LOD") {
      const Value* v = n->field("level") ? n->field("level") : n->field("children");
      if (v && !v->nodes.empty()) visit(v->nodes[0], place, inlines, depth + 1);
    } else if (t == "Inline") {
      inline_world(*n, place, inlines);
    } else if (t == "Shape") {
      shape(*n, place);
    } else if (t == "Viewpoint") {
      viewpoint(*n, place);
    } else if (protos_.count(t)) {
      ++left_out_["instance(s) of EXTERNPROTO " + t + " (its body is in another file, not read)"];
    } else if (n->field("children")) {  // Group, Anchor, Billboard (as placed), Collision, X3D's CAD groups...
      children("children", place);
    }
  }

  /// The first Viewpoint met, which a VRML browser starts from: at `position`, looking
  /// along −z turned by `orientation`; its fieldOfView, VRML's smaller angle, taken as
  /// the height of a 16:9 picture's.
  void viewpoint(const VNode& n, const Affine3& place) {
    if (out_.viewpoint) return;
    const Vec3 p = n.vec("position", {0, 0, 10});
    const Value* o = n.field("orientation");
    const Affine3 turn = o && o->numbers.size() >= 4
                             ? Affine3::rotation({o->numbers[0], o->numbers[1], o->numbers[2]}, o->numbers[3])
                             : Affine3{};
    const double fov = std::clamp(n.number("fieldOfView", std::numbers::pi / 4), 0.01, 3.0);
    out_.viewpoint = Viewpoint{place.apply(p), place.apply(p + turn.apply({0, 0, -1})), fov_deg_of_vertical(fov)};
  }

  void inline_world(const VNode& n, const Affine3& place, int inlines) {
    const Value* url = n.field("url");
    if (!url || url->strings.empty()) return;
    if (inlines >= kMaxInlines) {
      ++left_out_["Inline(s) more than " + std::to_string(kMaxInlines) + " deep"];
      return;
    }
    for (const std::string& u : url->strings) {
      if (u.find("://") != std::string::npos) continue;  // on the web: not fetched
      std::error_code ec;
      const std::string at = fs::weakly_canonical(fs::path(files_.back()).parent_path() / u, ec).string();
      if (ec || !fs::is_regular_file(at, ec)) continue;
      if (std::find(files_.begin(), files_.end(), at) != files_.end()) {
        warn("Inline '" + u + "' (line " + std::to_string(n.line) + ") names a world that holds it: left out");
        return;
      }
      try {
        read_world(at, place, inlines + 1);
      } catch (const std::runtime_error& e) {
        warn(std::string(e.what()) + ": the Inline at line " + std::to_string(n.line) + " left out");
      }
      return;
    }
    warn("Inline (line " + std::to_string(n.line) + "): none of its urls (" + url->strings.front() +
         ") names a file beside it: left out");
  }

  /// The colour of a Shape's appearance: its texture's mean, else its diffuseColor.
  /// The Shape's colour and whether the file gave one; `textured` set when it is an
  /// ImageTexture's (which stands over a Color node's, as a VRML browser shows an RGB
  /// texture over vertex colours).
  std::array<double, 3> colour_of(const VNode& shape, bool& coloured, bool& textured) {
    coloured = textured = false;
    const NodeRef app = shape.node("appearance");
    if (!app) return {1, 1, 1};
    if (const NodeRef tex = app->node("texture"); tex && tex->type == "ImageTexture")
      if (const Value* url = tex->field("url"); url && !url->strings.empty()) {
        const std::string at = (fs::path(files_.back()).parent_path() / url->strings.front()).string();
        bool first = false;
        const MaterialFiles::Image& image = images_.image(at, &first);
        if (first && (!image.at_hand || !image.problem.empty()))
          warn((image.at_hand ? image.problem : "texture " + at + " is not at hand") + ": its material's diffuseColor stands");
        if (image.colour) return coloured = textured = true, *image.colour;
      }
    const NodeRef mat = app->node("material");
    if (!mat) return {1, 1, 1};
    coloured = true;
    const Vec3 d = mat->vec("diffuseColor", {0.8, 0.8, 0.8});
    auto clamp = [](double v) { return std::clamp(v, 0.0, 1.0); };
    return {clamp(d.x), clamp(d.y), clamp(d.z)};
  }

  void shape(const VNode& s, const Affine3& place) {
    const NodeRef g = s.node("geometry");
    if (!g) return;
    std::vector<Vec3> v;
    std::vector<std::array<int, 3>> tris;
    std::vector<std::array<double, 3>> tri_colour;  // an IndexedFaceSet's own colours, per triangle
    const std::string& t = g->type;
    if (t == "IndexedFaceSet") face_set(*g, v, tris, tri_colour);
    else if (t == "ElevationGrid") elevation_grid(*g, v, tris, tri_colour);
    else if (t.ends_with("TriangleSet") || t.ends_with("QuadSet") || t.ends_with("StripSet") || t.ends_with("FanSet"))
      triangle_set(*g, v, tris, tri_colour);
    else if (t == "Box") box_shape(g->vec("size", {2, 2, 2}), {v, tris});
    else if (t == "Sphere") sphere_shape(g->number("radius", 1), kAround, kAround / 2, {v, tris});
    else if (t == "Cylinder")
      round_shape(g->number("radius", 1), g->number("radius", 1), g->number("height", 2), kAround, g->number("side", 1) != 0,
                  g->number("top", 1) != 0, g->number("bottom", 1) != 0, {v, tris});
    else if (t == "Cone")
      round_shape(g->number("bottomRadius", 1), 0, g->number("height", 2), kAround, g->number("side", 1) != 0, false,
                  g->number("bottom", 1) != 0, {v, tris});
    else if (t == "Extrusion") {
      const Extrusion e = extrusion_of(*g);
      if (e.spine.size() * e.cross_section.size() > (size_t(1) << 24)) {
        warn("Extrusion (line " + std::to_string(g->line) + "): " + std::to_string(e.spine.size()) + " spine points × " +
             std::to_string(e.cross_section.size()) + " cross-section points, over 16 million corners: left out");
        return;
      }
      extrusion_shape(e, {v, tris});
    }
    else {
      ++left_out_[t + " geometry (not drawn by this reader)"];
      return;
    }
    if (tris.empty()) return;
    ImportedNode n;
    n.name = t + " (line " + std::to_string(g->line) + ")";
    n.parent = 0;
    for (const Vec3& p : v) n.vertices.push_back(place.apply(p));
    n.triangles = std::move(tris);
    if (place.det() < 0)
      for (auto& tri : n.triangles) std::swap(tri[1], tri[2]);
    bool coloured = false, textured = false;
    n.colour = colour_of(s, coloured, textured);
    n.coloured = coloured;
    if (!tri_colour.empty() && !textured) {
      // The geometry's Color node, which stands for the Material's diffuseColor: a material
      // for each colour it uses.
      std::map<std::array<double, 3>, int> material_of;
      for (const auto& c : tri_colour) {
        auto [it, added] = material_of.try_emplace(c, int(out_.materials.size()));
        if (added) out_.materials.push_back({n.name + ", colour " + std::to_string(material_of.size()), c, true});
        n.triangle_material.push_back(it->second);
      }
      n.colour = tri_colour.front();
      n.coloured = true;
    } else if (coloured) {
      out_.materials.push_back({n.name, n.colour, true});
      n.triangle_material.assign(n.triangles.size(), int(out_.materials.size()) - 1);
    }
    out_.nodes.push_back(std::move(n));
  }

  /// Each face's colour from the geometry's Color node (VRML97 6.23): by colorIndex or in
  /// order, one a face (colorPerVertex FALSE) or one a corner (TRUE: the face's corners'
  /// mean). Empty without a Color node; a face whose index names no colour takes white.
  static std::vector<std::array<double, 3>> face_colours(const VNode& g, const std::vector<std::vector<int>>& faces,
                                                         const std::vector<std::vector<int>>& corner_index) {
    const NodeRef color = g.node("color");
    const Value* list = color ? color->field("color") : nullptr;
    if (!list || list->numbers.size() < 3) return {};
    const size_t colours = list->numbers.size() / 3;
    auto colour = [&](long i) -> std::array<double, 3> {
      if (i < 0 || size_t(i) >= colours) return {1, 1, 1};
      auto c = [&](size_t k) { return std::clamp(list->numbers[size_t(i) * 3 + k], 0.0, 1.0); };
      return {c(0), c(1), c(2)};
    };
    const Value* index = g.field("colorIndex");
    const bool per_vertex = g.number("colorPerVertex", 1) != 0;
    std::vector<std::array<double, 3>> out;
    for (size_t f = 0; f < faces.size(); ++f) {
      if (!per_vertex) {
        const long i = index && !index->numbers.empty() ? (f < index->numbers.size() ? long(index->numbers[f]) : -1) : long(f);
        out.push_back(colour(i));
        continue;
      }
      std::array<double, 3> sum{0, 0, 0};
      for (size_t k = 0; k < faces[f].size(); ++k) {
        const long i = index && !index->numbers.empty() ? long(corner_index[f][k]) : long(faces[f][k]);
        const auto c = colour(i);
        for (size_t j = 0; j < 3; ++j) sum[j] += c[j] / double(faces[f].size());
      }
      out.push_back(sum);
    }
    return out;
  }

  void face_set(const VNode& g, std::vector<Vec3>& v, std::vector<std::array<int, 3>>& tris,
                std::vector<std::array<double, 3>>& tri_colour) {
    const NodeRef coord = g.node("coord");
    const Value* point = coord ? coord->field("point") : nullptr;
    const Value* index = g.field("coordIndex");
    if (!point || !index) return;
    for (size_t i = 0; i + 2 < point->numbers.size(); i += 3) v.push_back({point->numbers[i], point->numbers[i + 1], point->numbers[i + 2]});
    const size_t points = v.size();
    const bool ccw = g.number("ccw", 1) != 0;
    size_t bad = 0;
    std::vector<int> face;
    // Every face as written (its number counts for colorIndex, drawn or not), its corners'
    // colour indices where colorIndex runs beside coordIndex, and its triangles' face.
    std::vector<std::vector<int>> faces, corner_index;
    std::vector<size_t> face_of;
    const Value* ci = g.field("colorIndex");
    size_t at = 0;  // the position in coordIndex of the face's first corner
    auto close = [&](size_t end) {
      if (face.empty()) return;
      bool ok = face.size() >= 3;
      for (int i : face) ok = ok && i >= 0 && size_t(i) < points;
      const size_t before = tris.size();
      if (!ok) {
        bad += 1;
      } else if (polygon_is_convex(v, face)) {
        for (size_t k = 1; k + 1 < face.size(); ++k) tris.push_back({face[0], face[k], face[k + 1]});
      } else {
        for (const auto& tri : triangulate_polygon(v, face)) tris.push_back(tri);
      }
      std::vector<int> corners;
      for (size_t k = at; k < end; ++k)
        corners.push_back(ci && k < ci->numbers.size() && ci->numbers[k] < double(INT32_MAX) ? int(ci->numbers[k]) : -1);
      face_of.insert(face_of.end(), tris.size() - before, faces.size());
      faces.push_back(face);
      corner_index.push_back(std::move(corners));
      face.clear();
    };
    for (size_t k = 0; k < index->numbers.size(); ++k) {
      const double i = index->numbers[k];
      if (i < 0) close(k), at = k + 1;
      else face.push_back(i < double(INT32_MAX) ? int(i) : -1);
    }
    close(index->numbers.size());
    if (const auto colours = face_colours(g, faces, corner_index); !colours.empty())
      for (size_t f : face_of) tri_colour.push_back(colours[f]);
    if (!ccw)
      for (auto& tri : tris) std::swap(tri[1], tri[2]);
    if (bad > 0)
      warn("IndexedFaceSet (line " + std::to_string(g.line) + "): " + std::to_string(bad) +
           " face(s) of fewer than three corners or naming no coordinate dropped");
  }

  /// An Extrusion's fields, VRML's defaults where a field is not given.
  static Extrusion extrusion_of(const VNode& g) {
    Extrusion e;
    if (const Value* f = g.field("crossSection")) {
      e.cross_section.clear();
      for (size_t i = 0; i + 1 < f->numbers.size(); i += 2) e.cross_section.push_back({f->numbers[i], f->numbers[i + 1]});
    }
    if (const Value* f = g.field("spine")) {
      e.spine.clear();
      for (size_t i = 0; i + 2 < f->numbers.size(); i += 3) e.spine.push_back({f->numbers[i], f->numbers[i + 1], f->numbers[i + 2]});
    }
    if (const Value* f = g.field("scale")) {
      e.scale.clear();
      for (size_t i = 0; i + 1 < f->numbers.size(); i += 2) e.scale.push_back({f->numbers[i], f->numbers[i + 1]});
    }
    if (const Value* f = g.field("orientation")) {
      e.orientation.clear();
      for (size_t i = 0; i + 3 < f->numbers.size(); i += 4)
        e.orientation.push_back({f->numbers[i], f->numbers[i + 1], f->numbers[i + 2], f->numbers[i + 3]});
    }
    e.begin_cap = g.number("beginCap", 1) != 0;
    e.end_cap = g.number("endCap", 1) != 0;
    return e;
  }

  /// X3D's triangle and quad sets (ISO/IEC 19775-1, Rendering and CADGeometry): triangles,
  /// quads, strips and fans of their coordinates, in order or by `index` (strips and fans
  /// of an index split at −1; of coordinates in order, by stripCount or fanCount). A strip's
  /// every other triangle is turned back, so that all of them turn as its first does.
  static void triangle_set(const VNode& g, std::vector<Vec3>& v, std::vector<std::array<int, 3>>& tris,
                           std::vector<std::array<double, 3>>& tri_colour) {
    const NodeRef coord = g.node("coord");
    const Value* point = coord ? coord->field("point") : nullptr;
    if (!point) return;
    for (size_t i = 0; i + 2 < point->numbers.size(); i += 3) v.push_back({point->numbers[i], point->numbers[i + 1], point->numbers[i + 2]});
    const long points = long(v.size());
    const std::string& t = g.type;
    const bool indexed = t.starts_with("Indexed");
    std::vector<long> order;  // the corners in order: the index, or the coordinates
    if (indexed) {
      if (const Value* index = g.field("index"))
        for (double i : index->numbers) order.push_back(i < 0 ? -1 : i < double(INT32_MAX) ? long(i) : points);
    } else {
      for (long i = 0; i < points; ++i) order.push_back(i);
    }
    // Runs of corners: split at −1 (indexed strips and fans) or by their counts.
    std::vector<std::vector<long>> runs(1);
    const Value* counts = g.field(t.ends_with("StripSet") ? "stripCount" : "fanCount");
    if (!indexed && counts && (t.ends_with("StripSet") || t.ends_with("FanSet"))) {
      runs.clear();
      size_t at = 0;
      for (double c : counts->numbers) {
        std::vector<long> run;
        for (long k = 0; k < long(c) && at < order.size(); ++k) run.push_back(order[at++]);
        runs.push_back(std::move(run));
      }
    } else {
      for (long i : order) {
        if (i < 0) runs.emplace_back();
        else runs.back().push_back(i);
      }
    }
    // Faces (triangles, or quads for the quad sets) as the node's kind makes them.
    std::vector<std::vector<int>> faces;
    const bool strip = t.ends_with("StripSet"), fan = t.ends_with("FanSet");
    const size_t per = t.ends_with("QuadSet") ? 4 : 3;
    for (const std::vector<long>& run : runs) {
      auto ok = [&](long i) { return i >= 0 && i < points; };
      if (strip || fan) {
        for (size_t k = 2; k < run.size(); ++k) {
          long a = fan ? run[0] : run[k - 2], b = run[k - 1], c = run[k];
          if (strip && k % 2 == 1) std::swap(a, b);
          if (ok(a) && ok(b) && ok(c)) faces.push_back({int(a), int(b), int(c)});
        }
      } else {
        for (size_t k = 0; k + per <= run.size(); k += per) {
          std::vector<int> f;
          for (size_t j = 0; j < per; ++j)
            if (ok(run[k + j])) f.push_back(int(run[k + j]));
          if (f.size() == per) faces.push_back(std::move(f));
        }
      }
    }
    const bool ccw = g.number("ccw", 1) != 0;
    std::vector<size_t> face_of;
    for (size_t f = 0; f < faces.size(); ++f) {
      const std::vector<int>& q = faces[f];
      for (size_t k = 1; k + 1 < q.size(); ++k) {
        tris.push_back(ccw ? std::array<int, 3>{q[0], q[k], q[k + 1]} : std::array<int, 3>{q[0], q[k + 1], q[k]});
        face_of.push_back(f);
      }
    }
    if (const auto colours = face_colours(g, faces, faces); !colours.empty())
      for (size_t f : face_of) tri_colour.push_back(colours[f]);
  }

  static void elevation_grid(const VNode& g, std::vector<Vec3>& v, std::vector<std::array<int, 3>>& tris,
                             std::vector<std::array<double, 3>>& tri_colour) {
    const long nx = long(g.number("xDimension", 0)), nz = long(g.number("zDimension", 0));
    const double dx = g.number("xSpacing", 1), dz = g.number("zSpacing", 1);
    const Value* h = g.field("height");
    if (nx < 2 || nz < 2 || !h || h->numbers.size() < size_t(nx * nz) || nx * nz > (1L << 24)) return;
    for (long j = 0; j < nz; ++j)
      for (long i = 0; i < nx; ++i) v.push_back({double(i) * dx, h->numbers[size_t(j * nx + i)], double(j) * dz});
    const bool ccw = g.number("ccw", 1) != 0;
    // Its squares as faces, for their colours (a colour a square, or a point: face_colours).
    std::vector<std::vector<int>> squares;
    for (long j = 0; j + 1 < nz; ++j)
      for (long i = 0; i + 1 < nx; ++i) {
        const int a = int(j * nx + i), b = int((j + 1) * nx + i), c = int((j + 1) * nx + i + 1), d = int(j * nx + i + 1);
        // (b − a) × (c − a) points up (+y) for ccw, as VRML's grid faces.
        tris.push_back(ccw ? std::array<int, 3>{a, b, c} : std::array<int, 3>{a, c, b});
        tris.push_back(ccw ? std::array<int, 3>{a, c, d} : std::array<int, 3>{a, d, c});
        squares.push_back({a, b, c, d});
      }
    for (const auto& c : face_colours(g, squares, squares)) tri_colour.push_back(c), tri_colour.push_back(c);
  }

  std::string path_;
  ImportOptions options_;
  ImportedScene out_;
  std::vector<std::string> files_;  ///< the worlds being read, outermost first
  std::set<std::string> protos_;
  MaterialFiles images_{read_material_file};  ///< textures' mean colours, each decoded once
  std::map<std::string, long> left_out_;
  long visits_ = 0;
};

}  // namespace

bool is_vrml(const std::string& path) {
  const std::optional<std::string> head = file_bytes(path, 1 << 16, 256);
  return head && vrml_header(utf8_of_text(*head));
}

ImportedScene read_vrml(const std::string& path, const ImportOptions& options) { return World(path, options).read(); }

}  // namespace avenues
