// Avenues — what a DXF layer's name says it holds (see dxf_layer_names.h).
#include "plans/formats/dxf_layer_names.h"

#include <cctype>
#include <initializer_list>
#include <string_view>
#include <vector>

#include "core/text_encoding.h"

namespace avenues {
namespace {


/// The lower case of a code point of Latin-1, Latin Extended-A or basic Cyrillic.
unsigned lower_code_point(unsigned cp) {
  if (cp >= 0xC0 && cp <= 0xDE && cp != 0xD7) return cp + 0x20;
  if ((cp >= 0x100 && cp <= 0x137) || (cp >= 0x14A && cp <= 0x177)) return cp | 1u;
  if ((cp >= 0x139 && cp <= 0x148) || (cp >= 0x179 && cp <= 0x17E)) return cp % 2 ? cp + 1 : cp;
  if (cp >= 0x410 && cp <= 0x42F) return cp + 0x20;
  if (cp >= 0x400 && cp <= 0x40F) return cp + 0x50;
  return cp;
}

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool contains(std::string_view s, std::initializer_list<std::string_view> words) {
  for (std::string_view w : words)
    if (s.find(w) != std::string_view::npos) return true;
  return false;
}

/// The name's words: runs of letters and digits (any byte of a UTF-8 sequence is a letter).
std::vector<std::string_view> words_of(std::string_view s) {
  std::vector<std::string_view> out;
  size_t i = 0;
  auto letter = [](unsigned char c) { return c >= 0x80 || std::isalnum(c); };
  while (i < s.size()) {
    while (i < s.size() && !letter(static_cast<unsigned char>(s[i]))) ++i;
    const size_t start = i;
    while (i < s.size() && letter(static_cast<unsigned char>(s[i]))) ++i;
    if (i > start) out.push_back(s.substr(start, i - start));
  }
  return out;
}

bool a_word_starts(const std::vector<std::string_view>& words, std::initializer_list<std::string_view> stems) {
  for (std::string_view w : words)
    for (std::string_view s : stems)
      if (w.substr(0, s.size()) == s) return true;
  return false;
}

bool a_word_is(const std::vector<std::string_view>& words, std::initializer_list<std::string_view> names) {
  for (std::string_view w : words)
    for (std::string_view n : names)
      if (w == n) return true;
  return false;
}

// The words, folded. Stems found anywhere in the name are long or unmistakable (German and
// Dutch join words: Außenwand, Innentüren, binnendeuren); short ones must begin a word
// ("pared" begins paredes), and a few must be the word ("mur" is no wall in "murals",
// "porte" no door in "porteurs" or "supporte").
bool says_door_words(std::string_view n, const std::vector<std::string_view>& w) {
  return contains(n, {"door", "tür", "tuer", "puerta", "deuren", "drzwi", "двер", "dörr", "dorr", "ドア", "扉", "门", "門"}) ||
         a_word_starts(w, {"deur", "kapı", "kapi", "dør", "dveř", "dvere"}) ||
         a_word_is(w, {"porte", "portes", "porta", "portas", "ovi", "ovet"});
}

bool says_window_words(std::string_view n, const std::vector<std::string_view>& w) {
  return contains(n, {"glaz", "window", "fenster", "fenêtre", "fenetre", "ventana", "finestr", "janela", "окн", "pencere",
                      "fönster", "fonster", "vindu", "ikkun", "窗", "窓"}) ||
         a_word_starts(w, {"raam", "ramen", "okn", "okien"});
}

/// A name folded, and its words (views into it: not copied).
struct Folded {
  std::string text;
  std::vector<std::string_view> words;
  explicit Folded(const std::string& name);
  Folded(const Folded&) = delete;
  Folded& operator=(const Folded&) = delete;
  bool door() const { return says_door_words(text, words); }
  bool window() const { return says_window_words(text, words); }
};

}  // namespace

std::string fold_layer_name(const std::string& name) {
  std::string out;
  out.reserve(name.size());
  for (size_t i = 0; i < name.size();) {
    const auto c = static_cast<unsigned char>(name[i]);
    unsigned cp = 0;
    size_t used = 0;
    if (c == '\\' && i + 6 < name.size() && (name[i + 1] == 'U' || name[i + 1] == 'u') && name[i + 2] == '+') {
      int h[4] = {hex_digit(name[i + 3]), hex_digit(name[i + 4]), hex_digit(name[i + 5]), hex_digit(name[i + 6])};
      if (h[0] >= 0 && h[1] >= 0 && h[2] >= 0 && h[3] >= 0) cp = unsigned(h[0] << 12 | h[1] << 8 | h[2] << 4 | h[3]), used = 7;
    } else if ((c & 0xE0) == 0xC0 && i + 1 < name.size() && (static_cast<unsigned char>(name[i + 1]) & 0xC0) == 0x80) {
      cp = unsigned(c & 0x1F) << 6 | (static_cast<unsigned char>(name[i + 1]) & 0x3F), used = 2;
    }
    if (used > 0 && cp >= 0x80) {
      append_utf8(out, lower_code_point(cp));
      i += used;
    } else {
      out += char(std::tolower(c));
      ++i;
    }
  }
  return out;
}

Folded::Folded(const std::string& name) : text(fold_layer_name(name)), words(words_of(text)) {}

namespace {

bool says_no_building(const Folded& f) {
  return contains(f.text, {"virtual", "furn", "dim", "text", "hatch-", "grid", "möbel", "moebel", "mobili", "arredo",
                           "cotation", "bemaß", "bemass", "beschrift", "annot", "demoli", "abbruch", "rückbau", "текст",
                           "размер", "мебел", "标注", "文字", "家具", "轴网"}) ||
         a_word_is(f.words, {"iden", "demo", "abov", "above", "ovhd", "elev", "nplt", "note", "notes", "symb", "tag",
                             "tags", "cote", "cotes", "cotas", "quote", "defpoints"});
}

}  // namespace

bool names_no_building(const std::string& name) { return says_no_building(Folded(name)); }

LayerRole layer_role_by_name(const std::string& name) {
  const Folded f(name);
  const std::string_view n = f.text;
  const std::vector<std::string_view>& w = f.words;
  if (says_no_building(f)) return LayerRole::None;
  const bool door = f.door(), window = f.window();
  if (contains(n, {"menuiser", "carpinter", "infiss", "serrament", "esquadri", "kozijn"}) || (door && window))
    return LayerRole::Doors;
  if (window) return LayerRole::Windows;
  if (door) return LayerRole::Doors;
  if (contains(n, {"wall", "wand", "wänd", "waend", "mauer", "partition", "tragwerk", "structure", "cloison", "tabique",
                   "tramezz", "alvenaria", "muratur", "ścian", "scian", "стен", "перегород", "duvar", "vägg", "vagg",
                   "væg", "vegg", "墙", "牆", "壁",
                   // what walls are made of, and the building's face
                   "drywall", "masonry", "trockenbau", "maçonner", "maconner", "mamposter", "cartongess", "facade",
                   "façade", "fassade", "fachada", "facciata", "gevel"}) ||
      a_word_is(w, {"mur", "murs", "muro", "muros", "muri", "muur", "muren"}) ||
      a_word_starts(w, {"pared", "seinä", "seina", "stěn", "steny"}))
    return LayerRole::Walls;
  // Columns stand in the way as walls do (AIA's A-COLS and S-COLS; their grid is none).
  if (contains(n, {"column", "colonne", "stütze", "stuetze", "säule", "saeule", "poteau", "pilastr", "kolom", "pelare",
                   "słup", "колонн", "柱"}) ||
      a_word_is(w, {"col", "cols"}) || a_word_starts(w, {"columna", "pilar"}))
    return LayerRole::Walls;
  return LayerRole::None;
}

bool names_openings(const std::string& name) {
  const Folded f(name);
  return f.door() || f.window();
}

bool names_a_window(const std::string& name) {
  const Folded f(name);
  return f.window() && !f.door();
}

bool names_a_door(const std::string& name) {
  const Folded f(name);
  return contains(f.text, {"sliding", "pocket", "bifold", "bi-fold"}) || f.text.rfind("tur", 0) == 0 || f.door();
}

bool names_a_storey(const std::string& text) {
  const Folded f(text);
  const std::vector<std::string_view>& w = f.words;
  if (contains(f.text, {"ground floor", "first floor", "second floor", "third floor", "upper floor", "top floor", "1st floor",
                        "2nd floor", "3rd floor", "lower ground", "basement", "erdgeschoss", "obergeschoss", "untergeschoss",
                        "dachgeschoss", "kellergeschoss", "rez-de-chauss", "rez de chauss", "sous-sol", "planta baja",
                        "planta alta", "primer piso", "segundo piso", "piano terra", "primo piano", "secondo piano",
                        "piano primo", "seminterrato", "begane grond", "verdieping"}))
    return true;
  for (size_t i = 0; i < w.size(); ++i) {
    if (w[i] == "eg" || w[i] == "og" || w[i] == "ug" || w[i] == "dg" || w[i] == "étage" || w[i] == "etage") return true;
    const bool numbered = i + 1 < w.size() && std::isdigit(static_cast<unsigned char>(w[i + 1][0]));
    if ((w[i] == "level" || w[i] == "storey" || w[i] == "story" || w[i] == "floor" || w[i] == "niveau" || w[i] == "nivel") && numbered)
      return true;
  }
  return false;
}

}  // namespace avenues
