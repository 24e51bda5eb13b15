// Avenues — reading a Java Object Serialization Stream (see java_stream.h).
//
// The grammar is the specification's (Java Object Serialization Specification, 6.4):
//   stream:  magic version contents
//   content: object | blockdata
//   object:  newObject | newClass | newArray | newString | newEnum | newClassDesc |
//            prevObject | nullReference | exception | TC_RESET
// read_content() is one recursive descent over it with a depth counter: nesting in the
// input (an object in a field of an object ...) is the only recursion, and it is capped.
#include "plans/formats/java_stream.h"

#include <cstring>

#include "core/text_encoding.h"

namespace avenues::java {
namespace {

// java.io.ObjectStreamConstants
constexpr uint16_t kMagic = 0xACED;
constexpr uint16_t kVersion = 5;
constexpr uint8_t TC_NULL = 0x70, TC_REFERENCE = 0x71, TC_CLASSDESC = 0x72, TC_OBJECT = 0x73, TC_STRING = 0x74,
                  TC_ARRAY = 0x75, TC_CLASS = 0x76, TC_BLOCKDATA = 0x77, TC_ENDBLOCKDATA = 0x78, TC_RESET = 0x79,
                  TC_BLOCKDATALONG = 0x7A, TC_EXCEPTION = 0x7B, TC_LONGSTRING = 0x7C, TC_PROXYCLASSDESC = 0x7D,
                  TC_ENUM = 0x7E;
constexpr uint32_t kBaseHandle = 0x7E0000;
constexpr uint8_t SC_WRITE_METHOD = 0x01, SC_SERIALIZABLE = 0x02, SC_EXTERNALIZABLE = 0x04, SC_BLOCK_DATA = 0x08;

class Reader {
 public:
  explicit Reader(std::string_view b) : b_(b) {}

  Stream read() {
    if (u16() != kMagic) fail(0, "not a Java serialization stream (no 0xACED magic)");
    if (const uint16_t v = u16(); v != kVersion) fail(2, "stream version " + std::to_string(v) + ", not 5");
    while (pos_ < b_.size()) {
      const uint8_t tc = peek();
      if (tc == TC_RESET) {
        ++pos_;
        handles_.clear();
        continue;
      }
      s_.contents.push_back(content(0));
    }
    return std::move(s_);
  }

 private:
  struct Handle {
    bool is_class;
    uint32_t index;
  };

  [[noreturn]] static void fail(size_t at, const std::string& what) { throw JavaStreamError(at, what); }
  void need(size_t n) const {
    if (b_.size() - pos_ < n)
      fail(pos_, "the stream ends " + std::to_string(n - (b_.size() - pos_)) + " byte(s) short");
  }
  uint8_t peek() const {
    need(1);
    return uint8_t(b_[pos_]);
  }
  uint64_t big_endian(size_t n) {
    need(n);
    uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) v = (v << 8) | uint8_t(b_[pos_ + i]);
    pos_ += n;
    return v;
  }
  uint8_t u8() { return uint8_t(big_endian(1)); }
  uint16_t u16() { return uint16_t(big_endian(2)); }
  uint32_t u32() { return uint32_t(big_endian(4)); }
  int32_t i32() { return int32_t(u32()); }
  uint64_t u64() { return big_endian(8); }

  /// Modified UTF-8 (DataInput.readUTF) of n bytes as UTF-8: C0 80 is NUL, a surrogate
  /// pair (two 3-byte sequences) is one 4-byte sequence.
  std::string utf(size_t n) {
    const size_t start = pos_;
    need(n);
    const std::string_view in = b_.substr(pos_, n);
    pos_ += n;
    std::vector<uint16_t> units;
    for (size_t i = 0; i < in.size();) {
      const uint8_t c = uint8_t(in[i]);
      uint32_t u = 0;
      size_t len = 0;
      if (c < 0x80 && c != 0) u = c, len = 1;
      else if ((c & 0xE0) == 0xC0) u = c & 0x1F, len = 2;
      else if ((c & 0xF0) == 0xE0) u = c & 0x0F, len = 3;
      else fail(start + i, "malformed modified UTF-8 in a string");
      if (i + len > in.size()) fail(start + i, "a string's last character is cut short");
      for (size_t k = 1; k < len; ++k) {
        const uint8_t d = uint8_t(in[i + k]);
        if ((d & 0xC0) != 0x80) fail(start + i + k, "malformed modified UTF-8 in a string");
        u = (u << 6) | (d & 0x3F);
      }
      units.push_back(uint16_t(u));  // at most 16 bits: one, two or three bytes
      i += len;
    }
    return utf8_of_utf16(units);  // a lone surrogate, which Java allows and UTF-8 cannot say: U+FFFD
  }

  uint32_t new_handle(bool is_class, uint32_t index) {
    handles_.push_back({is_class, index});
    return uint32_t(handles_.size() - 1);
  }
  const Handle& handle_at(size_t at) {
    const uint32_t h = u32();
    if (h < kBaseHandle || h - kBaseHandle >= handles_.size())
      fail(at, "reference to handle 0x" + hex(h) + ", which the stream has not assigned");
    return handles_[h - kBaseHandle];
  }
  static std::string hex(uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "%X", v);
    return buf;
  }
  void enter(size_t at, int& depth) {
    if (++depth > Stream::kMaxDepth)
      fail(at, "objects nested deeper than " + std::to_string(Stream::kMaxDepth) + " levels");
  }

  uint32_t add_object(Object o) {
    s_.objects.push_back(std::move(o));
    return uint32_t(s_.objects.size() - 1);
  }
  /// A TC_CLASS or TC_ENUM object: its class descriptor (required, else `missing`), then a
  /// handle of its own.
  uint32_t described_object(Object::Kind kind, size_t at, int depth, const char* missing) {
    Object o;
    o.kind = kind;
    o.offset = at;
    o.cls = class_desc(depth);
    if (o.cls < 0) fail(at, missing);
    const uint32_t i = add_object(std::move(o));
    new_handle(false, i);
    return i;
  }
  static Value ref(uint32_t i) {
    Value v;
    v.kind = Value::Kind::Object;
    v.object = i;
    return v;
  }

  /// A string (TC_STRING, TC_LONGSTRING or a reference to one), for class names of fields
  /// and enum constants.
  std::string string_at(int depth) {
    const size_t at = pos_;
    const Value v = content(depth);
    const Object* o = s_.object(v);
    if (!o || o->kind != Object::Kind::String) fail(at, "a string was expected here");
    return o->text;
  }

  /// classDesc: a new class descriptor, a proxy one, a reference to one, or null (-1).
  int class_desc(int depth) {
    const size_t at = pos_;
    enter(at, depth);
    const uint8_t tc = u8();
    if (tc == TC_NULL) return -1;
    if (tc == TC_REFERENCE) {
      const Handle& h = handle_at(at);
      if (!h.is_class) fail(at, "a class descriptor was expected, the reference names an object");
      return int(h.index);
    }
    ClassDesc c;
    if (tc == TC_CLASSDESC) {
      c.name = utf(u16());
      c.uid = u64();
      const int index = int(s_.classes.size());
      s_.classes.emplace_back();
      new_handle(true, uint32_t(index));
      c.flags = u8();
      const uint16_t n = u16();
      need(n * 3u);  // a field takes at least a type code and a name length
      for (uint16_t i = 0; i < n; ++i) {
        const size_t fat = pos_;
        Field f;
        f.type = char(u8());
        f.name = utf(u16());
        switch (f.type) {
          case 'B': case 'C': case 'D': case 'F': case 'I': case 'J': case 'S': case 'Z':
            break;
          case 'L': case '[':
            f.class_name = string_at(depth);
            break;
          default:
            fail(fat, "field '" + f.name + "' of class " + c.name + " has the unknown type code " +
                          std::to_string(int(uint8_t(f.type))));
        }
        c.fields.push_back(std::move(f));
      }
      if ((c.flags & SC_SERIALIZABLE) && (c.flags & SC_EXTERNALIZABLE))
        fail(at, "class " + c.name + " is flagged both Serializable and Externalizable");
      annotation(depth, nullptr);
      c.super = class_desc(depth);
      s_.classes[size_t(index)] = std::move(c);
      return index;
    }
    if (tc == TC_PROXYCLASSDESC) {
      const int index = int(s_.classes.size());
      s_.classes.emplace_back();
      new_handle(true, uint32_t(index));
      const int32_t n = i32();
      if (n < 0 || size_t(n) > (b_.size() - pos_) / 2) fail(at, "a proxy class with " + std::to_string(n) + " interfaces");
      c.proxy = true;
      c.flags = SC_SERIALIZABLE;
      std::string interfaces;
      for (int32_t i = 0; i < n; ++i) {
        if (i) interfaces += ',';
        interfaces += utf(u16());
      }
      c.name = "Proxy(";
      c.name += interfaces;
      c.name += ')';
      annotation(depth, nullptr);
      c.super = class_desc(depth);
      s_.classes[size_t(index)] = std::move(c);
      return index;
    }
    fail(at, "a class descriptor was expected, found type code 0x" + hex(tc));
  }

  /// Contents up to TC_ENDBLOCKDATA (a class annotation, or what writeObject added);
  /// into out when given, else read and dropped.
  void annotation(int depth, std::vector<Value>* out) {
    for (;;) {
      const uint8_t tc = peek();
      if (tc == TC_ENDBLOCKDATA) {
        ++pos_;
        return;
      }
      const Value v = content(depth);
      if (out) out->push_back(v);
    }
  }

  Value primitive(char type) {
    Value v;
    switch (type) {
      case 'B': v.kind = Value::Kind::Byte, v.integer = int8_t(u8()); break;
      case 'C': v.kind = Value::Kind::Char, v.integer = u16(); break;
      case 'S': v.kind = Value::Kind::Short, v.integer = int16_t(u16()); break;
      case 'Z': v.kind = Value::Kind::Boolean, v.integer = u8() != 0; break;
      case 'I': v.kind = Value::Kind::Int, v.integer = i32(); break;
      case 'J': v.kind = Value::Kind::Long, v.integer = int64_t(u64()); break;
      case 'F': {
        const uint32_t bits = u32();
        float f;
        std::memcpy(&f, &bits, sizeof f);
        v.kind = Value::Kind::Float, v.real = double(f);
        break;
      }
      case 'D': {
        const uint64_t bits = u64();
        double d;
        std::memcpy(&d, &bits, sizeof d);
        v.kind = Value::Kind::Double, v.real = d;
        break;
      }
      default: break;
    }
    return v;
  }
  static size_t primitive_size(char type) {
    switch (type) {
      case 'B': case 'Z': return 1;
      case 'C': case 'S': return 2;
      case 'I': case 'F': return 4;
      case 'J': case 'D': return 8;
      default: return 0;
    }
  }

  /// One content item (object or block data).
  Value content(int depth) {
    const size_t at = pos_;
    enter(at, depth);
    const uint8_t tc = u8();
    switch (tc) {
      case TC_NULL:
        return Value{};
      case TC_REFERENCE: {
        const Handle& h = handle_at(at);
        if (h.is_class) fail(at, "an object was expected, the reference names a class descriptor");
        return ref(h.index);
      }
      case TC_STRING:
      case TC_LONGSTRING: {
        const uint64_t n = tc == TC_STRING ? u16() : u64();
        if (n > b_.size() - pos_) fail(at, "the stream ends within a string of " + std::to_string(n) + " bytes");
        Object o;
        o.kind = Object::Kind::String;
        o.offset = at;
        const uint32_t i = add_object(std::move(o));
        new_handle(false, i);
        std::string text = utf(size_t(n));
        s_.objects[i].text = std::move(text);
        return ref(i);
      }
      case TC_BLOCKDATA:
      case TC_BLOCKDATALONG: {
        const uint64_t n = tc == TC_BLOCKDATA ? u8() : u32();
        need(size_t(n));
        Object o;
        o.kind = Object::Kind::BlockData;
        o.offset = at;
        o.text.assign(b_.substr(pos_, size_t(n)));
        pos_ += size_t(n);
        return ref(add_object(std::move(o)));
      }
      case TC_CLASS:
        return ref(described_object(Object::Kind::Class, at, depth, "a class object without a class descriptor"));
      case TC_ENUM: {
        const uint32_t i = described_object(Object::Kind::Enum, at, depth, "an enum constant without a class descriptor");
        std::string name = string_at(depth);
        s_.objects[i].text = std::move(name);
        return ref(i);
      }
      case TC_ARRAY:
        return array(at, depth);
      case TC_OBJECT:
        return instance(at, depth);
      case TC_CLASSDESC:
      case TC_PROXYCLASSDESC:
        fail(at, "a class descriptor where an object was expected");
      case TC_EXCEPTION:
        fail(at, "the stream records an exception thrown while it was written");
      case TC_RESET:
        fail(at, "TC_RESET inside an object");
      case TC_ENDBLOCKDATA:
        fail(at, "TC_ENDBLOCKDATA where no annotation is open");
      default:
        fail(at, "unknown type code 0x" + hex(tc));
    }
  }

  Value array(size_t at, int depth) {
    Object o;
    o.kind = Object::Kind::Array;
    o.offset = at;
    o.cls = class_desc(depth);
    if (o.cls < 0) fail(at, "an array without a class descriptor");
    const std::string& name = s_.classes[size_t(o.cls)].name;
    if (name.size() < 2 || name[0] != '[') fail(at, "an array whose class '" + name + "' is not an array class");
    const char type = name[1];
    const uint32_t i = add_object(std::move(o));
    new_handle(false, i);
    const int32_t n = i32();
    const size_t size = type == 'L' || type == '[' ? 1 : primitive_size(type);
    if (size == 0) fail(at, "an array of the unknown element type '" + std::string(1, type) + "'");
    if (n < 0 || size_t(n) > (b_.size() - pos_) / size)
      fail(at, "an array of " + std::to_string(n) + " elements, more than the stream holds");
    if (type == 'B' || type == 'Z') {
      s_.objects[i].text.assign(b_.substr(pos_, size_t(n)));
      pos_ += size_t(n);
      return ref(i);
    }
    std::vector<Value> values;
    values.reserve(size_t(n));
    for (int32_t k = 0; k < n; ++k) values.push_back(size == 1 && (type == 'L' || type == '[') ? content(depth) : primitive(type));
    s_.objects[i].values = std::move(values);
    return ref(i);
  }

  Value instance(size_t at, int depth) {
    Object o;
    o.kind = Object::Kind::Instance;
    o.offset = at;
    o.cls = class_desc(depth);
    if (o.cls < 0) fail(at, "an object without a class descriptor");
    const uint32_t i = add_object(std::move(o));
    new_handle(false, i);
    // The chain from the topmost serializable superclass down (at most as many classes as
    // the stream has described, so a cycle of superclasses is caught).
    std::vector<int> chain;
    for (int c = s_.objects[i].cls; c >= 0; c = s_.classes[size_t(c)].super) {
      if (chain.size() > s_.classes.size()) fail(at, "class " + s_.classes[size_t(c)].name + " is its own superclass");
      chain.push_back(c);
    }
    std::vector<Value> values, annotations;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      // By index: reading a field may describe new classes and move s_.classes.
      const size_t ci = size_t(*it);
      const uint8_t flags = s_.classes[ci].flags;
      if (flags & SC_EXTERNALIZABLE) {
        if (!(flags & SC_BLOCK_DATA))
          fail(at, "class " + s_.classes[ci].name + " is externalized in protocol version 1, which cannot be read without it");
        if (!s_.classes[ci].fields.empty()) fail(at, "externalizable class " + s_.classes[ci].name + " lists fields");
        annotation(depth, &annotations);
        continue;
      }
      if (!(flags & SC_SERIALIZABLE))
        fail(at, "class " + s_.classes[ci].name + " is neither Serializable nor Externalizable");
      for (size_t k = 0; k < s_.classes[ci].fields.size(); ++k) {
        const char type = s_.classes[ci].fields[k].type;
        values.push_back(type == 'L' || type == '[' ? content(depth) : primitive(type));
      }
      if (flags & SC_WRITE_METHOD) annotation(depth, &annotations);
    }
    s_.objects[i].values = std::move(values);
    s_.objects[i].annotations = std::move(annotations);
    return ref(i);
  }

  std::string_view b_;
  size_t pos_ = 0;
  std::vector<Handle> handles_;
  Stream s_;
};

const std::string kNoName;

}  // namespace

Stream Stream::parse(std::string_view bytes) { return Reader(bytes).read(); }

const std::string& Stream::class_name(const Object& o) const {
  return o.cls >= 0 && size_t(o.cls) < classes.size() ? classes[size_t(o.cls)].name : kNoName;
}

bool Stream::is_a(const Object& o, std::string_view name) const {
  if (o.kind != Object::Kind::Instance) return false;
  size_t steps = 0;
  for (int c = o.cls; c >= 0 && steps++ <= classes.size(); c = classes[size_t(c)].super)
    if (classes[size_t(c)].name == name) return true;
  return false;
}

const Value* Stream::field(const Object& o, std::string_view name) const {
  if (o.kind != Object::Kind::Instance) return nullptr;
  // Values are stored from the topmost superclass down: find each class's first index.
  std::vector<int> chain;
  for (int c = o.cls; c >= 0 && chain.size() <= classes.size(); c = classes[size_t(c)].super) chain.push_back(c);
  size_t end = o.values.size();
  for (int c : chain) {  // most derived first
    const auto& fields = classes[size_t(c)].fields;
    if (fields.size() > end) break;
    const size_t begin = end - fields.size();
    for (size_t k = 0; k < fields.size(); ++k)
      if (fields[k].name == name) return &o.values[begin + k];
    end = begin;
  }
  return nullptr;
}

std::string Stream::string_field(const Object& o, std::string_view name) const {
  const Value* v = field(o, name);
  const Object* s = v ? object(*v) : nullptr;
  return s && s->kind == Object::Kind::String ? s->text : std::string();
}

Value Stream::unboxed(const Value* v) const {
  if (!v) return Value{};
  if (v->is_number()) return *v;
  const Object* o = object(*v);
  if (!o || o->kind != Object::Kind::Instance || !class_name(*o).starts_with("java.lang.")) return Value{};
  const Value* inner = field(*o, "value");
  return inner && inner->is_number() ? *inner : Value{};
}

std::vector<Value> Stream::annotation_objects(const Object& o) const {
  std::vector<Value> out;
  for (const Value& v : o.annotations) {
    const Object* a = object(v);
    if (a && a->kind == Object::Kind::BlockData) continue;
    out.push_back(v);
  }
  return out;
}

}  // namespace avenues::java
