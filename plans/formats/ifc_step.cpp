// Avenues — IfcSpace LongNames from the STEP text (see ifc_step.h).
#include "plans/formats/ifc_step.h"

#include <cctype>
#include <cstdint>
#include <optional>
#include <unordered_set>
#include <vector>

#include "core/text_encoding.h"

namespace avenues {
namespace {

// IfcRoot(GlobalId, OwnerHistory, Name, ...); IfcSpatialStructureElement(..., ObjectPlacement,
// Representation, LongName, ...) in IFC2X3 and IFC4 alike.
constexpr size_t kNameAttribute = 2;
constexpr size_t kLongNameAttribute = 7;
constexpr size_t kGlobalIdLength = 22;


/// `digits` hexadecimal digits at s[at...], as a number; nullopt if any is not one.
std::optional<uint32_t> hex(std::string_view s, size_t at, size_t digits) {
  if (at + digits > s.size()) return std::nullopt;
  uint32_t v = 0;
  for (size_t k = 0; k < digits; ++k) {
    const char c = s[at + k];
    const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'A' && c <= 'F' ? c - 'A' + 10 : c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
    if (d < 0) return std::nullopt;
    v = v * 16 + uint32_t(d);
  }
  return v;
}

/// Past a string that starts at s[i] == '\'' (its closing quote); s.size() if unclosed.
size_t skip_string(std::string_view s, size_t i) {
  for (++i; i < s.size(); ++i) {
    if (s[i] != '\'') continue;
    if (i + 1 < s.size() && s[i + 1] == '\'') {
      ++i;
      continue;
    }
    return i + 1;
  }
  return s.size();
}

/// Past a comment that starts at s[i] == '/', s[i + 1] == '*'.
size_t skip_comment(std::string_view s, size_t i) {
  const size_t end = s.find("*/", i + 2);
  return end == std::string_view::npos ? s.size() : end + 2;
}

/// Past the string or comment that starts at s[i], if one does; else i. The record
/// scanners below step over both as units: a ';' or '#' inside them is text.
size_t skip_string_or_comment(std::string_view s, size_t i) {
  if (s[i] == '\'') return skip_string(s, i);
  if (s[i] == '/' && i + 1 < s.size() && s[i + 1] == '*') return skip_comment(s, i);
  return i;
}

/// Past white space and comments.
void skip_space(std::string_view s, size_t& i) {
  for (;;) {
    while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
    if (i + 1 < s.size() && s[i] == '/' && s[i + 1] == '*') i = skip_comment(s, i);
    else return;
  }
}

/// One record "#id = KEYWORD(attr, attr, ...)" (its id read from up to 18 digits; offset
/// and size left for the caller); nullopt for a malformed one.
std::optional<StepRecord> record_of(std::string_view r) {
  size_t i = 0;
  skip_space(r, i);
  if (i >= r.size() || r[i] != '#') return std::nullopt;
  ++i;
  StepRecord out;
  const size_t digits = i;
  for (; i < r.size() && std::isdigit(static_cast<unsigned char>(r[i])); ++i)
    if (i - digits < 18) out.id = out.id * 10 + unsigned(r[i] - '0');
  if (i == digits) return std::nullopt;
  skip_space(r, i);
  if (i >= r.size() || r[i] != '=') return std::nullopt;
  ++i;
  skip_space(r, i);
  while (i < r.size() && (std::isalnum(static_cast<unsigned char>(r[i])) || r[i] == '_'))
    out.keyword += char(std::toupper(static_cast<unsigned char>(r[i++])));
  if (out.keyword.empty()) return std::nullopt;
  skip_space(r, i);
  if (i >= r.size() || r[i] != '(') return std::nullopt;
  int depth = 1;
  size_t from = ++i;
  while (i < r.size()) {
    const char c = r[i];
    if (c == '\'') {
      i = skip_string(r, i);
      continue;
    }
    if (c == '/' && i + 1 < r.size() && r[i + 1] == '*') {
      i = skip_comment(r, i);
      continue;
    }
    if (c == '(') ++depth;
    if (c == ')' && --depth == 0) {
      out.attributes.push_back(r.substr(from, i - from));
      return out;
    }
    if (c == ',' && depth == 1) {
      out.attributes.push_back(r.substr(from, i - from));
      from = i + 1;
    }
    ++i;
  }
  return std::nullopt;  // unclosed
}

/// The body of an attribute that is one string ('...'), else nullopt ($, a reference, ...).
std::optional<std::string_view> string_body(std::string_view a) {
  a = step_trimmed(a);
  if (a.size() < 2 || a.front() != '\'' || a.back() != '\'' || skip_string(a, 0) != a.size()) return std::nullopt;
  return a.substr(1, a.size() - 2);
}

}  // namespace

std::string decode_step_string(std::string_view s, bool& ok) {
  ok = true;
  std::string out;
  for (size_t i = 0; i < s.size();) {
    const char c = s[i];
    if (c == '\'') {  // only doubled inside a string
      if (i + 1 >= s.size() || s[i + 1] != '\'') return ok = false, std::string();
      out += '\'', i += 2;
      continue;
    }
    if (c != '\\') {
      out += c, ++i;
      continue;
    }
    const std::string_view rest = s.substr(i);
    if (rest.starts_with("\\\\")) {
      out += '\\', i += 2;
    } else if (rest.starts_with("\\S\\") && rest.size() >= 4) {  // ISO 8859 upper half
      if (!append_utf8(out, uint32_t(static_cast<unsigned char>(rest[3]) & 0x7F) + 0x80)) return ok = false, std::string();
      i += 4;
    } else if (rest.starts_with("\\P") && rest.size() >= 4 && rest[3] == '\\') {  // code page: ISO 8859-1 assumed
      i += 4;
    } else if (rest.starts_with("\\X\\")) {
      const auto v = hex(rest, 3, 2);
      if (!v || !append_utf8(out, *v)) return ok = false, std::string();
      i += 5;
    } else if (rest.starts_with("\\X2\\") || rest.starts_with("\\X4\\")) {
      const size_t digits = rest[2] == '2' ? 4 : 8;
      size_t k = 4;
      uint32_t high = 0;  // a UTF-16 high surrogate waiting for its low half
      for (;;) {
        if (rest.substr(k).starts_with("\\X0\\")) break;
        const auto v = hex(rest, k, digits);
        if (!v) return ok = false, std::string();
        k += digits;
        if (digits == 4 && *v >= 0xD800 && *v <= 0xDBFF && !high) {
          high = *v;
          continue;
        }
        uint32_t cp = *v;
        if (high) {
          if (cp < 0xDC00 || cp > 0xDFFF) return ok = false, std::string();
          cp = 0x10000 + ((high - 0xD800) << 10) + (cp - 0xDC00);
          high = 0;
        }
        if (!append_utf8(out, cp)) return ok = false, std::string();
      }
      if (high) return ok = false, std::string();
      i += k + 4;
    } else {
      return ok = false, std::string();
    }
  }
  return out;
}

std::optional<StepProblem> step_data_problem(std::string_view text) {
  std::unordered_set<unsigned long long> defined;
  std::vector<std::pair<unsigned long long, size_t>> referenced;  // id, offset
  auto number_at = [&](size_t& i) {
    unsigned long long n = 0;
    const size_t from = i;
    while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i])) && i - from < 18)
      n = n * 10 + unsigned(text[i++] - '0');
    return i > from ? std::optional<unsigned long long>(n) : std::nullopt;
  };
  bool in_data = false, saw_data = false;
  size_t start = 0, record_refs = 0;  // record_refs: references before this record
  for (size_t i = 0; i < text.size();) {
    if (const size_t past = skip_string_or_comment(text, i); past != i) {
      i = past;
      continue;
    }
    const char c = text[i];
    if (c == '#') {  // a reference (the record's own id is taken off below)
      const size_t at = i++;
      if (const auto n = number_at(i)) referenced.push_back({*n, at});
      continue;
    }
    if (c != ';') {
      ++i;
      continue;
    }
    const size_t base = start;  // the record's offset in the text
    const std::string_view piece = text.substr(start, i - start);
    size_t k = 0;
    skip_space(piece, k);
    const size_t at = base + k;
    start = ++i;
    std::string_view word = piece.substr(k);
    while (!word.empty() && std::isspace(static_cast<unsigned char>(word.back()))) word.remove_suffix(1);
    // Every record that starts with '#' is an instance, wherever it stands (Assimp reads
    // instances past a broken section line); the others are section and header lines.
    if (word.empty() || word[0] != '#') {
      referenced.resize(record_refs);
      if (in_data && word != "ENDSEC") return StepProblem{at, "not a STEP record (#id=ENTITY(...);)"};
      if (word == "DATA") in_data = saw_data = true;
      if (word == "ENDSEC") in_data = false;
      continue;
    }
    // "#id = KEYWORD(...)" or a complex instance "#id = (...)".
    size_t j = k;
    size_t digits = base + j + 1;
    const auto id = number_at(digits);
    j = digits - base;
    skip_space(piece, j);
    if (!id || j >= piece.size() || piece[j] != '=') return StepProblem{at, "not a STEP record (#id=ENTITY(...);)"};
    ++j;
    skip_space(piece, j);
    if (j < piece.size() && piece[j] != '(') {
      const std::optional<StepRecord> r = record_of(piece);
      if (!r) return StepProblem{at, "record " + step_reference_text(*id) + " is not a STEP record (#id=ENTITY(...);)"};
    }
    if (!defined.insert(*id).second) return StepProblem{at, "record " + step_reference_text(*id) + " is defined twice"};
    // Its own id was counted as a reference: drop it.
    for (size_t r = referenced.size(); r-- > 0;)
      if (referenced[r].second == at) {
        referenced.erase(referenced.begin() + std::ptrdiff_t(r));
        break;
      }
    record_refs = referenced.size();
  }
  if (!saw_data) return StepProblem{0, "it has no DATA section"};
  for (const auto& [id, offset] : referenced)
    if (!defined.count(id)) return StepProblem{offset, step_reference_text(id) + " refers to no record"};
  return std::nullopt;
}

void for_each_step_record(std::string_view text, const std::function<void(const StepRecord&)>& f) {
  // Records end at a ';' outside strings and comments.
  size_t start = 0;
  for (size_t i = 0; i < text.size();) {
    if (const size_t past = skip_string_or_comment(text, i); past != i) {
      i = past;
      continue;
    }
    if (text[i] != ';') {
      ++i;
      continue;
    }
    std::string_view piece = text.substr(start, i - start);
    size_t from = 0;
    skip_space(piece, from);
    const size_t offset = start + from;
    piece.remove_prefix(from);
    start = ++i;
    std::optional<StepRecord> r = record_of(piece);
    if (!r) continue;
    r->offset = offset;
    r->size = piece.size();
    f(*r);
  }
}

std::string_view step_trimmed(std::string_view v) {
  while (!v.empty() && std::isspace(static_cast<unsigned char>(v.front()))) v.remove_prefix(1);
  while (!v.empty() && std::isspace(static_cast<unsigned char>(v.back()))) v.remove_suffix(1);
  return v;
}

std::optional<std::vector<std::string_view>> step_list(std::string_view a) {
  a = step_trimmed(a);
  if (a.size() < 2 || a.front() != '(' || a.back() != ')') return std::nullopt;
  std::vector<std::string_view> items;
  int depth = 0;
  size_t from = 1;
  for (size_t i = 1; i + 1 < a.size();) {
    if (const size_t past = skip_string_or_comment(a, i); past != i) {
      i = past;
      continue;
    }
    const char c = a[i];
    if (c == '(') ++depth;
    if (c == ')' && --depth < 0) return std::nullopt;  // the first '(' closed before the end
    if (c == ',' && depth == 0) {
      items.push_back(step_trimmed(a.substr(from, i - from)));
      from = i + 1;
    }
    ++i;
  }
  if (depth != 0) return std::nullopt;
  const std::string_view last = step_trimmed(a.substr(from, a.size() - 1 - from));
  if (!last.empty() || !items.empty()) items.push_back(last);
  for (std::string_view item : items)
    if (item.empty()) return std::nullopt;  // "(a,,b)"
  return items;
}

std::string step_reference_text(unsigned long long id) {
  std::string s(1, '#');  // built in steps (GCC 12 warns falsely of an overlap in "#" + std::to_string(n))
  s += std::to_string(id);
  return s;
}

std::optional<unsigned long long> step_reference(std::string_view a) {
  a = step_trimmed(a);
  if (a.size() < 2 || a.size() > 19 || a[0] != '#') return std::nullopt;
  unsigned long long n = 0;
  for (size_t k = 1; k < a.size(); ++k) {
    if (!std::isdigit(static_cast<unsigned char>(a[k]))) return std::nullopt;
    n = n * 10 + unsigned(a[k] - '0');
  }
  return n;
}

std::map<std::string, IfcRootNames> ifc_root_names(std::string_view text) {
  std::map<std::string, IfcRootNames> out;
  auto decoded = [](const std::vector<std::string_view>& attrs, size_t k) -> std::optional<std::string> {
    if (k >= attrs.size()) return std::nullopt;
    const auto body = string_body(attrs[k]);
    if (!body) return std::nullopt;
    bool ok = false;
    std::string s = decode_step_string(*body, ok);
    if (!ok) return std::nullopt;
    return s;
  };
  for_each_step_record(text, [&](const StepRecord& r) {
    const std::optional<std::string> guid = decoded(r.attributes, 0);
    if (!guid || guid->size() != kGlobalIdLength) return;  // not an IfcRoot
    IfcRootNames names;
    names.name = decoded(r.attributes, kNameAttribute).value_or("");
    if (r.keyword == "IFCSPACE" || r.keyword == "IFCBUILDINGSTOREY" || r.keyword == "IFCBUILDING" ||
        r.keyword == "IFCSITE")
      names.long_name = decoded(r.attributes, kLongNameAttribute).value_or("");
    if (!names.name.empty() || !names.long_name.empty()) out[*guid] = std::move(names);
  });
  return out;
}

}  // namespace avenues
