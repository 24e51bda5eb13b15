// Avenues — a Java Object Serialization Stream (java.io.ObjectOutputStream's bytes) as a
// generic tree of values.
//
// Sweet Home 3D homes saved before version 5.3 hold only a serialized Java `Home` entry.
// Such a stream describes its own classes (names, fields and their types), so it can be
// read without Java: this is a small, strict reader of the protocol as the Java Object
// Serialization Specification (chapter 6, java.io.ObjectStreamConstants) defines it:
//   magic 0xACED, version 5; TC_OBJECT, TC_CLASS, TC_ARRAY, TC_STRING, TC_LONGSTRING,
//   TC_ENUM, TC_CLASSDESC, TC_PROXYCLASSDESC, TC_REFERENCE (handles from 0x7E0000),
//   TC_NULL, TC_BLOCKDATA, TC_BLOCKDATALONG, TC_ENDBLOCKDATA, TC_RESET; class
//   annotations; superclass chains; modified UTF-8.
// A class with SC_WRITE_METHOD is read as its default fields followed by its annotation
// (objects and block data up to TC_ENDBLOCKDATA): that is how java.util.ArrayList, HashMap,
// HashSet, TreeMap, LinkedList, Vector, java.net.URL and Sweet Home's own classes write
// themselves (defaultWriteObject or writeFields first, then their extra data). So a list's
// elements are its instance's annotation objects, a map's keys and values alternate there.
// An SC_EXTERNALIZABLE class must also be SC_BLOCK_DATA (protocol 2, the default since
// Java 1.2): its data is an annotation. Protocol-1 externals and TC_EXCEPTION are refused.
//
// Hostile input: nesting is capped (kMaxDepth), every length is checked against the bytes
// left before anything is allocated, so memory stays proportional to the input; every
// error is a JavaStreamError naming the byte offset.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace avenues::java {

/// A malformed stream: what() is "byte N: what is wrong".
class JavaStreamError : public std::runtime_error {
 public:
  JavaStreamError(size_t offset, const std::string& what)
      : std::runtime_error("byte " + std::to_string(offset) + ": " + what), offset_(offset) {}
  size_t offset() const { return offset_; }

 private:
  size_t offset_;
};

/// A field's or an element's value: a primitive, null, or an object of the stream.
struct Value {
  enum class Kind : uint8_t { Null, Boolean, Byte, Char, Short, Int, Long, Float, Double, Object };
  Kind kind = Kind::Null;
  int64_t integer = 0;  ///< Boolean, Byte, Char, Short, Int, Long
  double real = 0;      ///< Float (widened exactly), Double
  uint32_t object = 0;  ///< Object: index into Stream::objects
  bool is_null() const { return kind == Kind::Null; }
  bool is_object() const { return kind == Kind::Object; }
  bool is_number() const { return kind != Kind::Null && kind != Kind::Object; }
  /// A primitive as a double (integers converted).
  double number() const { return kind == Kind::Float || kind == Kind::Double ? real : double(integer); }
};

struct Field {
  char type = 0;           ///< B C D F I J S Z, or L (object) and [ (array)
  std::string name;
  std::string class_name;  ///< for L and [: the field's type as a JVM signature
};

struct ClassDesc {
  std::string name;  ///< "com.eteks.sweethome3d.model.Wall", "[F", ...
  uint64_t uid = 0;  ///< serialVersionUID
  uint8_t flags = 0; ///< SC_* bits
  std::vector<Field> fields;
  int super = -1;    ///< index into Stream::classes; -1 when the superclass is not serializable
  bool proxy = false;
};

struct Object {
  enum class Kind : uint8_t { Instance, String, Array, Enum, Class, BlockData };
  Kind kind = Kind::Instance;
  int cls = -1;       ///< index into Stream::classes (Instance, Array, Enum, Class)
  size_t offset = 0;  ///< where it starts in the stream
  /// String: its text (UTF-8); Enum: the constant's name; BlockData: the bytes;
  /// an array of byte or boolean: its elements as bytes.
  std::string text;
  /// Instance: its field values, class by class from the topmost serializable superclass
  /// down, each class's fields in the order its descriptor lists them. Array: its
  /// elements (not for byte or boolean arrays, which are in text).
  std::vector<Value> values;
  /// Instance: what writeObject or writeExternal wrote after the fields, all classes in
  /// order: objects, and block data as BlockData objects.
  std::vector<Value> annotations;
};

/// A whole stream: the objects it holds (in the order they begin), their classes, and the
/// top-level contents (usually one object).
class Stream {
 public:
  static constexpr int kMaxDepth = 400;  ///< objects nested deeper than this are refused

  /// Parses bytes (a complete stream). Throws JavaStreamError.
  static Stream parse(std::string_view bytes);

  std::vector<ClassDesc> classes;
  std::vector<Object> objects;
  std::vector<Value> contents;

  /// The object a value refers to; nullptr for null and primitives.
  const Object* object(const Value& v) const { return v.is_object() ? &objects[v.object] : nullptr; }
  /// The class name of an instance, array, enum or class object ("" for strings, block data).
  const std::string& class_name(const Object& o) const;
  /// Whether an instance's class or one of its superclasses is named `name`.
  bool is_a(const Object& o, std::string_view name) const;
  /// An instance's field, looked up from its own class up its superclasses (so a field a
  /// subclass declares hides its superclass's); nullptr when no class declares it.
  const Value* field(const Object& o, std::string_view name) const;
  /// A field holding a string: its text, or "" when absent or null.
  std::string string_field(const Object& o, std::string_view name) const;
  /// Follows a boxed number (java.lang.Float, Integer, ...: its "value" field) or returns a
  /// primitive as it is; Null for null, for absent and for anything else.
  Value unboxed(const Value* v) const;
  /// The objects (not block data) of an instance's annotation: a list's or set's elements,
  /// a map's keys and values alternately.
  std::vector<Value> annotation_objects(const Object& o) const;
};

}  // namespace avenues::java
