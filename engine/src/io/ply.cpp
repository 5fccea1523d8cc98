// Strict PLY reader: ASCII, binary little endian and binary big endian, version 1.0.
//
// Header: "ply", "format ...", then "element <name> <count>" each followed by its
// "property <type> <name>" / "property list <count type> <item type> <name>" lines,
// "comment" and "obj_info" lines anywhere, and "end_header". Types: char uchar short
// ushort int uint float double and their sized names (int8 ... float64).
// Kept: element "vertex" with x y z (required), nx ny nz (all three or none), and a
// texcoord pair (the first of u v, s t, texture_u texture_v, texture_s texture_t);
// element "face" with the list "vertex_indices" (or "vertex_index") of integers, from
// 0. Everything else (colors, other elements) is read, checked against its type and
// dropped, except faces in another form: an element "tristrips" is an error. Element
// counts are checked against the bytes after the header before anything is
// allocated, lists against the bytes left; values must fit their type, kept floats
// must be finite; a face needs 3 distinct existing vertices; nothing may follow the
// last element. Errors name the element and entry ("vertex[12]"), with the line
// (ASCII) or byte offset (binary).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "finflex/error.hpp"
#include "io/builder.hpp"
#include "io/formats.hpp"
#include "io/text.hpp"

namespace finflex::io {
namespace {

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct PlyTypeInfo {
  PlyType type;
  const char* name;
  const char* sized_name;
  std::size_t size;
  bool is_float;
  double min;  // integer types: the range
  double max;
};

constexpr PlyTypeInfo kTypes[] = {
    {PlyType::kInt8, "char", "int8", 1, false, -128.0, 127.0},
    {PlyType::kUint8, "uchar", "uint8", 1, false, 0.0, 255.0},
    {PlyType::kInt16, "short", "int16", 2, false, -32768.0, 32767.0},
    {PlyType::kUint16, "ushort", "uint16", 2, false, 0.0, 65535.0},
    {PlyType::kInt32, "int", "int32", 4, false, -2147483648.0, 2147483647.0},
    {PlyType::kUint32, "uint", "uint32", 4, false, 0.0, 4294967295.0},
    {PlyType::kFloat32, "float", "float32", 4, true, 0.0, 0.0},
    {PlyType::kFloat64, "double", "float64", 8, true, 0.0, 0.0},
};

const PlyTypeInfo& info(PlyType type) { return kTypes[static_cast<int>(type)]; }

enum class Encoding { kAscii, kLittleEndian, kBigEndian };

// What a vertex property is used for.
enum class Role { kNone, kX, kY, kZ, kNx, kNy, kNz, kU, kV, kFaceIndices };

struct Property {
  std::string name;
  std::size_t line = 0;  // of its header line
  PlyType type = PlyType::kFloat32;
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
  Role role = Role::kNone;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::size_t line = 0;
  std::vector<Property> properties;
};

// ---------------------------------------------------------------------------------
// Header

struct Header {
  Encoding encoding = Encoding::kAscii;
  std::vector<Element> elements;
  std::size_t data_offset = 0;  // first byte after the "end_header" line
  std::size_t data_line = 0;    // number of the first line after it
};

bool find_type(std::string_view name, PlyType& type) {
  for (const PlyTypeInfo& t : kTypes) {
    if (name == t.name || name == t.sized_name) {
      type = t.type;
      return true;
    }
  }
  return false;
}

PlyType read_type(std::string_view name, const std::string& where) {
  PlyType type = PlyType::kFloat32;
  if (!find_type(name, type)) throw_at(ErrorCode::kFormat, where, "unknown type " + shown(name));
  return type;
}

void read_property(const std::vector<std::string_view>& words, const TextLine& line,
                   Element& element) {
  const std::string where = line_field(line.number);
  Property property;
  property.line = line.number;
  if (words.size() == 5 && words[1] == "list") {
    property.is_list = true;
    property.count_type = read_type(words[2], where);
    if (info(property.count_type).is_float) {
      throw_at(ErrorCode::kFormat, where, "a list's count type must be an integer type");
    }
    property.type = read_type(words[3], where);
    property.name = words[4];
  } else if (words.size() == 3 && words[1] != "list") {
    property.type = read_type(words[1], where);
    property.name = words[2];
  } else {
    throw_at(ErrorCode::kFormat, where,
             "expected 'property <type> <name>' or 'property list <count type> <item type> "
             "<name>'");
  }
  element.properties.push_back(property);
}

// Throws for a second element of a name, or a second property of a name in an
// element. Linear in the header's size.
void check_unique_names(const Header& header) {
  std::unordered_set<std::string_view> elements;
  for (const Element& element : header.elements) {
    if (!elements.insert(element.name).second) {
      throw_at(ErrorCode::kFormat, line_field(element.line),
               "a second element " + shown(element.name));
    }
    std::unordered_set<std::string_view> properties;
    for (const Property& property : element.properties) {
      if (!properties.insert(property.name).second) {
        throw_at(
            ErrorCode::kFormat, line_field(property.line),
            "element " + shown(element.name) + " has a second property " + shown(property.name));
      }
    }
  }
}

Header read_header(std::string_view bytes) {
  LineReader lines(bytes);
  TextLine line;
  std::vector<std::string_view> words;
  if (!lines.next(line) || line.text != "ply") {
    throw Error(ErrorCode::kFormat, "path", "not a PLY file: the first line is not 'ply'");
  }
  Header header;
  bool has_format = false;
  for (;;) {
    if (!lines.next(line)) {
      throw_at(ErrorCode::kFormat, line_field(line.number), "the header has no 'end_header' line");
    }
    const std::string where = line_field(line.number);
    split_words(line.text, words);
    if (words.empty() || words[0] == "comment" || words[0] == "obj_info") continue;
    if (words[0] == "end_header" && words.size() == 1) break;
    if (words[0] == "format") {
      if (has_format || words.size() != 3 || words[2] != "1.0") {
        throw_at(ErrorCode::kFormat, where,
                 "expected one 'format ascii|binary_little_endian|binary_big_endian 1.0' line");
      }
      has_format = true;
      if (words[1] == "ascii") {
        header.encoding = Encoding::kAscii;
      } else if (words[1] == "binary_little_endian") {
        header.encoding = Encoding::kLittleEndian;
      } else if (words[1] == "binary_big_endian") {
        header.encoding = Encoding::kBigEndian;
      } else {
        throw_at(ErrorCode::kFormat, where, "unknown format " + shown(words[1]));
      }
    } else if (words[0] == "element") {
      if (words.size() != 3)
        throw_at(ErrorCode::kFormat, where, "expected 'element <name> <count>'");
      const std::int64_t count = read_int(words[2], where, "element count");
      if (count < 0) {
        throw_at(ErrorCode::kFormat, where,
                 "element count " + std::to_string(count) + " is negative");
      }
      header.elements.push_back(
          Element{std::string(words[1]), static_cast<std::uint64_t>(count), line.number, {}});
    } else if (words[0] == "property") {
      if (header.elements.empty())
        throw_at(ErrorCode::kFormat, where, "a property before any element");
      read_property(words, line, header.elements.back());
    } else {
      throw_at(ErrorCode::kFormat, where, "unknown header line " + shown(line.text));
    }
  }
  if (!has_format) throw Error(ErrorCode::kFormat, "path", "the PLY header has no 'format' line");
  check_unique_names(header);
  header.data_offset = bytes.size() - lines.remaining();
  header.data_line = lines.line_number() + 1;
  return header;
}

// ---------------------------------------------------------------------------------
// Roles of the properties we keep

Property* find_property(Element& element, std::string_view name) {
  for (Property& p : element.properties) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

void assign_vertex_roles(Element& vertex) {
  const std::string where = line_field(vertex.line);
  const auto scalar = [&](std::string_view name, Role role) {
    Property* p = find_property(vertex, name);
    if (p == nullptr) return false;
    if (p->is_list)
      throw_at(ErrorCode::kFormat, where, "vertex property " + shown(name) + " is a list");
    p->role = role;
    return true;
  };
  for (const char* axis : {"x", "y", "z"}) {
    if (find_property(vertex, axis) == nullptr) {
      throw_at(ErrorCode::kFormat, where,
               std::string("element 'vertex' has no property '") + axis + "'");
    }
  }
  scalar("x", Role::kX);
  scalar("y", Role::kY);
  scalar("z", Role::kZ);
  const int normals = int{find_property(vertex, "nx") != nullptr} +
                      int{find_property(vertex, "ny") != nullptr} +
                      int{find_property(vertex, "nz") != nullptr};
  if (normals != 0 && normals != 3) {
    throw_at(ErrorCode::kFormat, where, "element 'vertex' has some of nx ny nz, not all three");
  }
  if (normals == 3) {
    scalar("nx", Role::kNx);
    scalar("ny", Role::kNy);
    scalar("nz", Role::kNz);
  }
  static const char* const kPairs[][2] = {
      {"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (const auto& pair : kPairs) {
    if (find_property(vertex, pair[0]) != nullptr && find_property(vertex, pair[1]) != nullptr) {
      scalar(pair[0], Role::kU);
      scalar(pair[1], Role::kV);
      break;
    }
  }
}

void assign_face_roles(Element& face) {
  Property* p = find_property(face, "vertex_indices");
  if (p == nullptr) p = find_property(face, "vertex_index");
  const std::string where = line_field(face.line);
  if (p == nullptr || !p->is_list || info(p->type).is_float) {
    throw_at(ErrorCode::kFormat, where,
             "element 'face' needs a list of integers 'vertex_indices' (or 'vertex_index')");
  }
  p->role = Role::kFaceIndices;
}

// ---------------------------------------------------------------------------------
// Data

// Names a value for errors: "vertex[12].y", "face[3].vertex_indices[2]".
struct ValueName {
  const Element* element = nullptr;
  std::uint64_t entry = 0;
  const Property* property = nullptr;
  std::int64_t item = -1;  // list item, -1 for the list's count or a scalar

  std::string field() const {
    std::string name =
        printable(element->name) + "[" + std::to_string(entry) + "]." + printable(property->name);
    if (item >= 0) name += "[" + std::to_string(item) + "]";
    return name;
  }
};

// Reads the values after the header, in either encoding, with bounds checks.
class DataReader {
 public:
  DataReader(std::string_view bytes, const Header& header)
      : bytes_(bytes),
        position_(header.data_offset),
        line_(header.data_line),
        encoding_(header.encoding) {}

  // A value of `type`: integers exactly, floats as double (non-finite ones as NaN or
  // infinity when binary, NaN when ASCII; the caller decides whether they may be).
  double scalar(PlyType type, const ValueName& name);
  // A value of integer `type`.
  std::int64_t integer(PlyType type, const ValueName& name);
  // Bytes left.
  std::size_t remaining() const { return bytes_.size() - position_; }
  bool is_ascii() const { return encoding_ == Encoding::kAscii; }
  // Throws unless only blanks (ASCII) or nothing (binary) is left.
  void expect_end();
  // Throws `code` with field name.field() and the message "<field> (<place>): <text>".
  [[noreturn]] void fail(ErrorCode code, const ValueName& name, const std::string& text) const;
  // Where the reader is (the line of the last value, or the byte offset of the next),
  // and its text ("line 12", "byte 345").
  std::size_t mark() const { return is_ascii() ? line_ : position_; }
  std::string place(std::size_t mark) const {
    return is_ascii() ? line_field(mark) : "byte " + std::to_string(mark);
  }

 private:
  std::string place() const { return place(mark()); }
  std::string_view token(const ValueName& name);
  std::uint64_t bits(std::size_t size, const ValueName& name);

  std::string_view bytes_;
  std::size_t position_;
  std::size_t line_;
  Encoding encoding_;
};

void DataReader::fail(ErrorCode code, const ValueName& name, const std::string& text) const {
  const std::string field = name.field();
  throw Error(code, field, field + " (" + place() + "): " + text);
}

std::string_view DataReader::token(const ValueName& name) {
  while (position_ < bytes_.size() && (is_blank(bytes_[position_]) || bytes_[position_] == '\n')) {
    if (bytes_[position_] == '\n') ++line_;
    ++position_;
  }
  const std::size_t begin = position_;
  while (position_ < bytes_.size() && !is_blank(bytes_[position_]) && bytes_[position_] != '\n') {
    ++position_;
  }
  if (position_ == begin) fail(ErrorCode::kFormat, name, "the data ends before this value");
  return bytes_.substr(begin, position_ - begin);
}

// The next `size` bytes as an unsigned number in file byte order.
std::uint64_t DataReader::bits(std::size_t size, const ValueName& name) {
  if (remaining() < size) fail(ErrorCode::kFormat, name, "the data ends before this value");
  std::uint64_t value = 0;
  for (std::size_t i = 0; i < size; ++i) {
    const std::uint64_t byte = static_cast<unsigned char>(bytes_[position_ + i]);
    const std::size_t shift = encoding_ == Encoding::kBigEndian ? size - 1 - i : i;
    value |= byte << (8 * shift);
  }
  position_ += size;
  return value;
}

std::int64_t DataReader::integer(PlyType type, const ValueName& name) {
  const PlyTypeInfo& t = info(type);
  if (is_ascii()) {
    const std::string_view text = token(name);
    std::int64_t value = 0;
    const NumberError error = parse_int(text, value);
    if (error == NumberError::kUnreadable) {
      fail(ErrorCode::kFormat, name, shown(text) + " is not an integer");
    }
    const auto v = static_cast<double>(value);
    if (error != NumberError::kNone || v < t.min || v > t.max) {
      fail(ErrorCode::kFormat, name, shown(text) + " is outside the range of " + t.name);
    }
    return value;
  }
  const std::uint64_t raw = bits(t.size, name);
  switch (type) {
    case PlyType::kInt8:
      return static_cast<std::int8_t>(static_cast<std::uint8_t>(raw));
    case PlyType::kInt16:
      return static_cast<std::int16_t>(static_cast<std::uint16_t>(raw));
    case PlyType::kInt32:
      return static_cast<std::int32_t>(static_cast<std::uint32_t>(raw));
    default:
      return static_cast<std::int64_t>(raw);  // unsigned types
  }
}

double DataReader::scalar(PlyType type, const ValueName& name) {
  if (!info(type).is_float) return static_cast<double>(integer(type, name));
  if (is_ascii()) {
    const std::string_view text = token(name);
    double value = 0.0;
    float narrow = 0.0f;
    const NumberError error =
        type == PlyType::kFloat32 ? parse_float(text, narrow) : parse_double(text, value);
    if (error == NumberError::kNotFinite) return std::numeric_limits<double>::quiet_NaN();
    if (error == NumberError::kUnreadable) {
      fail(ErrorCode::kFormat, name, shown(text) + " is not a number");
    }
    if (error == NumberError::kOutOfRange) {
      fail(ErrorCode::kInvalidMesh, name,
           shown(text) + " is outside the range of " + info(type).name);
    }
    return type == PlyType::kFloat32 ? double{narrow} : value;
  }
  if (type == PlyType::kFloat32) {
    const auto raw = static_cast<std::uint32_t>(bits(4, name));
    float value = 0.0f;
    std::memcpy(&value, &raw, sizeof value);
    return double{value};
  }
  const std::uint64_t raw = bits(8, name);
  double value = 0.0;
  std::memcpy(&value, &raw, sizeof value);
  return value;
}

void DataReader::expect_end() {
  std::size_t end = position_;
  if (is_ascii()) {
    while (end < bytes_.size() && (is_blank(bytes_[end]) || bytes_[end] == '\n')) ++end;
  }
  if (end == bytes_.size()) return;
  throw Error(ErrorCode::kFormat, "path",
              std::to_string(bytes_.size() - position_) + " bytes follow the last element (" +
                  place() + ")");
}

// ---------------------------------------------------------------------------------
// Elements

// The smallest number of bytes an entry of `element` takes: binary, its scalars and
// list counts; ASCII, a character per value.
std::uint64_t min_entry_bytes(const Element& element, bool ascii) {
  std::uint64_t bytes = 0;
  for (const Property& p : element.properties) {
    bytes += ascii ? 1 : info(p.is_list ? p.count_type : p.type).size;
  }
  return bytes;
}

class PlyReader {
 public:
  explicit PlyReader(std::string_view bytes) : header_(read_header(bytes)), data_(bytes, header_) {}
  Mesh read();

 private:
  void check_counts() const;
  void read_entry(const Element& element, std::uint64_t entry);
  std::uint64_t read_list_count(const Property& p, const ValueName& name);
  void add_faces();

  Header header_;
  DataReader data_;
  const Element* vertex_ = nullptr;
  const Element* face_ = nullptr;
  MeshBuilder builder_;
  // Faces, kept until every vertex is read (the face element may come first).
  std::vector<std::int64_t> corners_;
  std::vector<std::size_t> face_sizes_;
  std::vector<std::size_t> face_marks_;  // where each face's list starts (DataReader::mark)
  std::vector<std::uint32_t> polygon_;
};

void PlyReader::check_counts() const {
  const bool ascii = data_.is_ascii();
  std::uint64_t left = data_.remaining();
  for (const Element& element : header_.elements) {
    if (element.count == 0) continue;
    const std::string where = line_field(element.line);
    const std::uint64_t entry_bytes = min_entry_bytes(element, ascii);
    if (entry_bytes == 0) {
      throw_at(ErrorCode::kFormat, where,
               "element " + shown(element.name) + " has " + std::to_string(element.count) +
                   " entries but no properties");
    }
    if (element.count > left / entry_bytes) {
      throw_at(ErrorCode::kFormat, where,
               "element " + shown(element.name) + " declares " + std::to_string(element.count) +
                   " entries of at least " + std::to_string(entry_bytes) + " bytes, but only " +
                   std::to_string(left) +
                   " bytes of data are left for it (truncated file or "
                   "wrong count)");
    }
    left -= element.count * entry_bytes;
  }
}

std::uint64_t PlyReader::read_list_count(const Property& p, const ValueName& name) {
  const std::int64_t count = data_.integer(p.count_type, name);
  if (count < 0)
    data_.fail(ErrorCode::kFormat, name, "list count " + std::to_string(count) + " is negative");
  // Each item takes at least a byte: a count beyond the data left is refused before
  // anything is allocated for it.
  const std::uint64_t item_bytes = data_.is_ascii() ? 1 : info(p.type).size;
  if (static_cast<std::uint64_t>(count) > data_.remaining() / item_bytes) {
    data_.fail(ErrorCode::kFormat, name,
               "list count " + std::to_string(count) + " exceeds the " +
                   std::to_string(data_.remaining()) + " bytes left");
  }
  return static_cast<std::uint64_t>(count);
}

void PlyReader::read_entry(const Element& element, std::uint64_t entry) {
  ValueName name{&element, entry, nullptr, -1};
  glm::vec3 position(0.0f), normal(0.0f);
  glm::vec2 texcoord(0.0f);
  bool has_normal = false, has_texcoord = false;
  for (const Property& p : element.properties) {
    name.property = &p;
    name.item = -1;
    if (p.is_list) {
      const std::uint64_t count = read_list_count(p, name);
      if (p.role == Role::kFaceIndices) face_marks_.push_back(data_.mark());
      if (p.role == Role::kFaceIndices && count < 3) {
        data_.fail(ErrorCode::kFormat, name,
                   "face has " + std::to_string(count) + " corners, at least 3 needed");
      }
      for (std::uint64_t k = 0; k < count; ++k) {
        name.item = static_cast<std::int64_t>(k);
        if (p.role == Role::kFaceIndices) {
          corners_.push_back(data_.integer(p.type, name));
        } else {
          data_.scalar(p.type, name);  // checked, not kept
        }
      }
      if (p.role == Role::kFaceIndices) face_sizes_.push_back(static_cast<std::size_t>(count));
      continue;
    }
    const double value = data_.scalar(p.type, name);
    if (p.role == Role::kNone) continue;
    float narrow = 0.0f;
    const NumberError error = narrow_to_float(value, narrow);
    if (error == NumberError::kNotFinite) {
      data_.fail(ErrorCode::kInvalidMesh, name,
                 std::isnan(value) ? "is NaN"
                 : value > 0       ? "is +inf"
                                   : "is -inf");
    }
    if (error == NumberError::kOutOfRange) {
      data_.fail(ErrorCode::kInvalidMesh, name,
                 std::to_string(value) + " is outside the float range");
    }
    switch (p.role) {
      case Role::kX:
        position.x = narrow;
        break;
      case Role::kY:
        position.y = narrow;
        break;
      case Role::kZ:
        position.z = narrow;
        break;
      case Role::kNx:
        normal.x = narrow;
        has_normal = true;
        break;
      case Role::kNy:
        normal.y = narrow;
        break;
      case Role::kNz:
        normal.z = narrow;
        break;
      case Role::kU:
        texcoord.x = narrow;
        has_texcoord = true;
        break;
      case Role::kV:
        texcoord.y = narrow;
        break;
      default:
        break;
    }
  }
  if (&element == vertex_) {
    const std::uint32_t v = builder_.add_vertex(position);
    if (has_normal) builder_.add_normal(v, normal);
    if (has_texcoord) builder_.add_texcoord(v, texcoord);
  }
}

// The faces read, now that every vertex is known.
void PlyReader::add_faces() {
  const std::size_t vertex_count = builder_.vertex_count();
  const Property* indices = nullptr;
  for (const Property& p : face_->properties) {
    if (p.role == Role::kFaceIndices) indices = &p;
  }
  std::size_t first = 0;
  for (std::size_t f = 0; f < face_sizes_.size(); ++f) {
    const std::size_t size = face_sizes_[f];
    const auto fail = [&](std::int64_t item, const std::string& text) {
      const std::string field = ValueName{face_, f, indices, item}.field();
      throw Error(ErrorCode::kInvalidMesh, field,
                  field + " (" + data_.place(face_marks_[f]) + "): " + text);
    };
    polygon_.clear();
    for (std::size_t k = 0; k < size; ++k) {
      const std::int64_t index = corners_[first + k];
      if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_count) {
        fail(static_cast<std::int64_t>(k), "vertex index " + std::to_string(index) +
                                               " is out of range (" + std::to_string(vertex_count) +
                                               " vertices)");
      }
      polygon_.push_back(static_cast<std::uint32_t>(index));
    }
    if (const auto repeat = find_repeated_corner(polygon_)) {
      fail(-1, "the face uses vertex " + std::to_string(polygon_[repeat->first]) + " at corners " +
                   std::to_string(repeat->first + 1) + " and " +
                   std::to_string(repeat->second + 1) + " (a polygon's corners must be distinct)");
    }
    builder_.add_polygon(polygon_);
    first += size;
  }
}

Mesh PlyReader::read() {
  for (Element& element : header_.elements) {
    if (element.name == "vertex") {
      assign_vertex_roles(element);
      vertex_ = &element;
    } else if (element.name == "face") {
      assign_face_roles(element);
      face_ = &element;
    } else if (element.name == "tristrips" && element.count > 0) {
      // Faces in another form: dropping them would lose part of the surface.
      throw_at(ErrorCode::kFormat, line_field(element.line),
               "element 'tristrips' (triangle strips) is not supported, only 'face'");
    }
  }
  if (vertex_ == nullptr || vertex_->count == 0) {
    throw Error(ErrorCode::kFormat, "positions", "positions: the PLY header declares no vertices");
  }
  check_counts();
  for (const Element& element : header_.elements) {
    for (std::uint64_t entry = 0; entry < element.count; ++entry) read_entry(element, entry);
  }
  data_.expect_end();
  if (face_ != nullptr) add_faces();
  return builder_.finish();
}

}  // namespace

Mesh read_ply(std::string_view bytes) { return PlyReader(bytes).read(); }

}  // namespace finflex::io
