// PLY 1.0 in ascii, binary_little_endian and binary_big_endian. The `vertex` element must have
// scalar x, y, z (any numeric type); the `face` element a list named vertex_indices (or
// vertex_index) with integer count and index types. Every other property and element, lists
// included, is read past by its declared type. The header's counts must match the data
// exactly: a short body, extra data after the last element, or an ascii line with the wrong
// number of values is an error. Ascii bodies hold one element per line.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "engine/io/mesh_readers.h"
#include "engine/io/reader_checks.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "engine/util/parallel_for.h"

namespace strata {
namespace meshio {
namespace {

enum class Type { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

bool typeFromName(std::string_view n, Type& type) {
  struct Entry {
    const char* name;
    Type type;
  };
  static const Entry kTypes[] = {
      {"char", Type::Int8},      {"int8", Type::Int8},       {"uchar", Type::UInt8},
      {"uint8", Type::UInt8},    {"short", Type::Int16},     {"int16", Type::Int16},
      {"ushort", Type::UInt16},  {"uint16", Type::UInt16},   {"int", Type::Int32},
      {"int32", Type::Int32},    {"uint", Type::UInt32},     {"uint32", Type::UInt32},
      {"float", Type::Float32},  {"float32", Type::Float32}, {"double", Type::Float64},
      {"float64", Type::Float64}};
  for (const Entry& e : kTypes) {
    if (n == e.name) {
      type = e.type;
      return true;
    }
  }
  return false;
}

size_t sizeOf(Type t) {
  switch (t) {
    case Type::Int8:
    case Type::UInt8:
      return 1;
    case Type::Int16:
    case Type::UInt16:
      return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32:
      return 4;
    case Type::Float64:
      return 8;
  }
  return 1;
}

bool isInteger(Type t) {
  return t != Type::Float32 && t != Type::Float64;
}

struct Property {
  std::string name;
  bool isList = false;
  Type type = Type::Float32;     // of the value, or of each list item
  Type countType = Type::UInt8;  // lists only
};

struct Element {
  std::string name;
  uint64_t count = 0;
  size_t headerLine = 0;
  std::vector<Property> properties;
};

enum class Format { Ascii, LittleEndian, BigEndian };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  size_t bodyStart = 0;  // byte offset just past end_header's line
  size_t lines = 0;      // header lines, so ascii bodies number on from here
};

// The header's lines up to end_header, one method per keyword.
class HeaderParser {
 public:
  HeaderParser(const std::string& name, const std::string& bytes) : name_(name), lines_(bytes) {}

  Header parse() {
    std::string_view line;
    if (!lines_.next(line) || line != "ply")
      failAtLine(name_, 1, "not a PLY file (expected 'ply')");
    for (bool more = true; more;) more = readLine();
    if (!haveFormat_) failAtLine(name_, 2, "missing format line");
    for (const Element& e : header_.elements) {
      if (e.count > 0 && e.properties.empty()) {
        failAtLine(name_, e.headerLine, "element '" + e.name + "' has no properties");
      }
    }
    return std::move(header_);
  }

 private:
  // One header line; false once it was end_header.
  bool readLine() {
    std::string_view line;
    if (!lines_.next(line)) {
      failAtLine(name_, lines_.lineNumber() + 1,
                 "unexpected end of file in the header (no end_header)");
    }
    const size_t lineNo = lines_.lineNumber();
    splitTokens(line, tokens_, /*hashComments=*/false);
    if (tokens_.empty()) return true;
    const std::string_view keyword = tokens_[0];
    if (keyword == "comment" || keyword == "obj_info") return true;
    if (keyword == "end_header") {
      header_.bodyStart = lines_.byteOffset();
      header_.lines = lineNo;
      return false;
    }
    if (keyword == "format") {
      readFormat(lineNo);
    } else if (keyword == "element") {
      readElement(lineNo);
    } else if (keyword == "property") {
      readProperty(lineNo);
    } else {
      failAtLine(name_, lineNo, "unknown header keyword " + quoted(keyword));
    }
    return true;
  }

  // format ascii|binary_little_endian|binary_big_endian 1.0
  void readFormat(size_t lineNo) {
    if (tokens_.size() != 3) failAtLine(name_, lineNo, "format line needs a format and a version");
    if (tokens_[1] == "ascii") {
      header_.format = Format::Ascii;
    } else if (tokens_[1] == "binary_little_endian") {
      header_.format = Format::LittleEndian;
    } else if (tokens_[1] == "binary_big_endian") {
      header_.format = Format::BigEndian;
    } else {
      failAtLine(name_, lineNo, "unknown format " + quoted(tokens_[1]));
    }
    if (tokens_[2] != "1.0" && tokens_[2] != "1") {
      failAtLine(name_, lineNo, "unsupported PLY version " + quoted(tokens_[2]));
    }
    haveFormat_ = true;
  }

  // element <name> <count>. The mesh's elements (vertex, face) may be declared only once.
  void readElement(size_t lineNo) {
    long long count = 0;
    if (tokens_.size() != 3 || !parseInteger(tokens_[2], count) || count < 0) {
      failAtLine(name_, lineNo, "element line needs a name and a non-negative count");
    }
    Element e;
    e.name = std::string(tokens_[1]);
    e.count = static_cast<uint64_t>(count);
    e.headerLine = lineNo;
    if (e.name == "vertex" || e.name == "face") {
      for (const Element& earlier : header_.elements) {
        if (earlier.name != e.name) continue;
        failAtLine(name_, lineNo,
                   "element '" + e.name + "' is declared twice (first at line " +
                       std::to_string(earlier.headerLine) +
                       "): which one holds the mesh is ambiguous");
      }
    }
    header_.elements.push_back(std::move(e));
  }

  // property <type> <name>, or property list <count type> <item type> <name>
  void readProperty(size_t lineNo) {
    if (header_.elements.empty()) failAtLine(name_, lineNo, "property before any element");
    Property p;
    if (tokens_.size() == 5 && tokens_[1] == "list") {
      p.isList = true;
      if (!typeFromName(tokens_[2], p.countType) || !isInteger(p.countType)) {
        failAtLine(name_, lineNo,
                   "list count type must be an integer type, found " + quoted(tokens_[2]));
      }
      if (!typeFromName(tokens_[3], p.type)) {
        failAtLine(name_, lineNo, "unknown property type " + quoted(tokens_[3]));
      }
      p.name = std::string(tokens_[4]);
    } else if (tokens_.size() == 3) {
      if (!typeFromName(tokens_[1], p.type)) {
        failAtLine(name_, lineNo, "unknown property type " + quoted(tokens_[1]));
      }
      p.name = std::string(tokens_[2]);
    } else {
      failAtLine(name_, lineNo, "malformed property line");
    }
    header_.elements.back().properties.push_back(std::move(p));
  }

  const std::string& name_;
  LineReader lines_;
  std::vector<std::string_view> tokens_;  // of the current line
  Header header_;
  bool haveFormat_ = false;
};

// Where the geometry lives in the element list.
struct Layout {
  const Element* vertex = nullptr;
  int x = -1, y = -1, z = -1;
  const Element* face = nullptr;
  int indices = -1;
};

Layout findLayout(const std::string& name, const Header& header) {
  Layout layout;
  for (const Element& e : header.elements) {
    if (e.name == "vertex") layout.vertex = &e;
    if (e.name == "face") layout.face = &e;
  }
  if (!layout.vertex) failAtLine(name, header.lines, "no 'vertex' element in the header");
  for (int i = 0; i < static_cast<int>(layout.vertex->properties.size()); ++i) {
    const Property& p = layout.vertex->properties[i];
    int* slot = p.name == "x"   ? &layout.x
                : p.name == "y" ? &layout.y
                : p.name == "z" ? &layout.z
                                : nullptr;
    if (!slot) continue;
    if (p.isList)
      failAtLine(name, layout.vertex->headerLine, "vertex property " + p.name + " is a list");
    *slot = i;
  }
  if (layout.x < 0 || layout.y < 0 || layout.z < 0) {
    failAtLine(name, layout.vertex->headerLine, "element vertex lacks an x, y or z property");
  }
  if (layout.vertex->count >= std::numeric_limits<uint32_t>::max()) {
    failAtLine(name, layout.vertex->headerLine, "too many vertices");
  }
  if (!layout.face)
    failAtLine(name, header.lines, "no 'face' element: the file contains no triangles");
  for (int i = 0; i < static_cast<int>(layout.face->properties.size()); ++i) {
    const Property& p = layout.face->properties[i];
    if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
    if (!p.isList || !isInteger(p.type)) {
      failAtLine(name, layout.face->headerLine, p.name + " must be a list of integers");
    }
    layout.indices = i;
  }
  if (layout.indices < 0) {
    failAtLine(name, layout.face->headerLine,
               "element face has no vertex_indices (or vertex_index) list property");
  }
  return layout;
}

bool hostIsLittleEndian() {
  const uint16_t probe = 1;
  unsigned char first;
  std::memcpy(&first, &probe, 1);
  return first == 1;
}

// One value of `type` at `raw` (stored little- or big-endian), as double: exactly for every
// integer type. The one decoding of the whole read and the read in pieces.
double decode(const char* raw, Type type, bool bigEndian) {
  unsigned char b[8];
  const size_t n = sizeOf(type);
  std::memcpy(b, raw, n);
  if (bigEndian == hostIsLittleEndian())
    for (size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
  const auto get = [&](auto v) {
    std::memcpy(&v, b, sizeof(v));
    return double(v);
  };
  switch (type) {
    case Type::Int8:
      return get(int8_t());
    case Type::UInt8:
      return get(uint8_t());
    case Type::Int16:
      return get(int16_t());
    case Type::UInt16:
      return get(uint16_t());
    case Type::Int32:
      return get(int32_t());
    case Type::UInt32:
      return get(uint32_t());
    case Type::Float32:
      return get(float());
    case Type::Float64:
      return get(double());
  }
  return 0.0;
}

// ---- Binary ----

class BinaryCursor {
 public:
  BinaryCursor(const std::string& name, const std::string& bytes, size_t pos, bool bigEndian)
      : name_(name), bytes_(bytes), pos_(pos), bigEndian_(bigEndian) {}

  size_t pos() const { return pos_; }
  size_t remaining() const { return bytes_.size() - pos_; }

  void need(size_t n, const Element& e, uint64_t index) const {
    if (remaining() < n) {
      failAtByte(name_, bytes_.size(),
                 "unexpected end of file in element '" + e.name + "' " + std::to_string(index) +
                     " of " + std::to_string(e.count) +
                     " (truncated, or the header's counts are wrong)");
    }
  }

  // Reads one value of `type` (bounds already checked) as double, exactly for all integers.
  double read(Type type) {
    const double value = decode(bytes_.data() + pos_, type, bigEndian_);
    pos_ += sizeOf(type);
    return value;
  }

  void skip(size_t n) { pos_ += n; }

 private:
  const std::string& name_;
  const std::string& bytes_;
  size_t pos_;
  bool bigEndian_;
};

void parseBinaryBody(const std::string& name, const std::string& bytes, const Header& header,
                     const Layout& layout, TriangleMesh& mesh) {
  BinaryCursor in(name, bytes, header.bodyStart, header.format == Format::BigEndian);
  for (const Element& e : header.elements) {
    // Each instance needs at least its scalars and list counts: catch absurd counts early.
    size_t minBytes = 0;
    for (const Property& p : e.properties) minBytes += sizeOf(p.isList ? p.countType : p.type);
    if (minBytes > 0 && e.count > in.remaining() / minBytes) {
      failAtByte(name, in.pos(),
                 "the header says " + std::to_string(e.count) + " '" + e.name +
                     "' elements, which need at least " + std::to_string(e.count * minBytes) +
                     " bytes, but only " + std::to_string(in.remaining()) +
                     " remain (truncated, or the header's counts are wrong)");
    }
    const bool isVertex = &e == layout.vertex;
    const bool isFace = &e == layout.face;
    if (isVertex) mesh.positions.reserve(e.count);
    std::vector<uint32_t> polygon;
    for (uint64_t i = 0; i < e.count; ++i) {
      glm::dvec3 p(0.0);
      for (int pi = 0; pi < static_cast<int>(e.properties.size()); ++pi) {
        const Property& prop = e.properties[pi];
        if (!prop.isList) {
          in.need(sizeOf(prop.type), e, i);
          const size_t at = in.pos();
          if (isVertex && (pi == layout.x || pi == layout.y || pi == layout.z)) {
            const double v = in.read(prop.type);
            requireFiniteAtByte(name, at, v);
            p[pi == layout.x ? 0 : pi == layout.y ? 1 : 2] = v;
          } else {
            in.skip(sizeOf(prop.type));
          }
          continue;
        }
        in.need(sizeOf(prop.countType), e, i);
        const size_t countAt = in.pos();
        const double count = in.read(prop.countType);
        if (count < 0)
          failAtByte(name, countAt, "negative list length in element '" + e.name + "'");
        const size_t n = static_cast<size_t>(count);
        const size_t itemBytes = sizeOf(prop.type);
        if (n > in.remaining() / itemBytes) in.need(n * itemBytes, e, i);
        if (!(isFace && pi == layout.indices)) {
          in.skip(n * itemBytes);
          continue;
        }
        if (n < 3) {
          failAtByte(name, countAt,
                     "face " + std::to_string(i) + " has " + std::to_string(n) +
                         " vertices, needs at least 3");
        }
        polygon.clear();
        for (size_t k = 0; k < n; ++k) {
          const size_t at = in.pos();
          const double index = in.read(prop.type);
          if (index < 0 || index >= static_cast<double>(layout.vertex->count)) {
            failAtByte(name, at,
                       "vertex index " + std::to_string(static_cast<long long>(index)) +
                           " is out of range: the file has " +
                           std::to_string(layout.vertex->count) + " vertices");
          }
          polygon.push_back(static_cast<uint32_t>(index));
        }
        for (size_t k = 1; k + 1 < polygon.size(); ++k) {
          mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
        }
      }
      if (isVertex) mesh.positions.push_back(p);
    }
  }
  if (in.remaining() > 0) {
    failAtByte(name, in.pos(),
               std::to_string(in.remaining()) +
                   " bytes of data after the last element (the header's counts disagree with "
                   "the data)");
  }
}

// ---- Ascii ----

// One element instance per line, each property's values in the order the header declares
// them; the vertex's x, y, z and the face's index list go into the mesh.
class AsciiBodyParser {
 public:
  AsciiBodyParser(const std::string& name, const std::string& bytes, const Header& header,
                  const Layout& layout, TriangleMesh& mesh)
      : name_(name),
        bytes_(bytes),
        header_(header),
        layout_(layout),
        mesh_(mesh),
        lines_(bytes, header.bodyStart, header.lines) {}

  void parse() {
    for (const Element& e : header_.elements) {
      if (&e == layout_.vertex) {
        mesh_.positions.reserve(std::min<uint64_t>(e.count, bytes_.size() / 6 + 1));
      }
      for (uint64_t i = 0; i < e.count; ++i) {
        nextInstanceLine(e, i);
        readInstance(e, i);
      }
    }
    std::string_view line;
    while (lines_.next(line)) {
      splitTokens(line, tokens_, /*hashComments=*/false);
      if (!tokens_.empty()) {
        failAtLine(name_, lines_.lineNumber(),
                   "data after the last element (the header's counts disagree with the data)");
      }
    }
  }

 private:
  // The next line with values, into tokens_ and lineNo_; instance i of element e is expected.
  void nextInstanceLine(const Element& e, uint64_t i) {
    std::string_view line;
    do {
      if (!lines_.next(line)) {
        failAtLine(name_, lines_.lineNumber() + 1,
                   "unexpected end of file: expected " + std::to_string(e.count) + " '" + e.name +
                       "' elements, found " + std::to_string(i) +
                       " (truncated, or the header's counts are wrong)");
      }
      splitTokens(line, tokens_, /*hashComments=*/false);
    } while (tokens_.empty());
    lineNo_ = lines_.lineNumber();
    next_ = 0;
  }

  // The line's next value, of instance i of element e.
  std::string_view nextToken(const Element& e, uint64_t i) {
    if (next_ >= tokens_.size()) {
      failAtLine(name_, lineNo_,
                 "too few values for element '" + e.name + "' " + std::to_string(i) +
                     " (the header's counts may be wrong)");
    }
    return tokens_[next_++];
  }

  void readInstance(const Element& e, uint64_t i) {
    const bool isVertex = &e == layout_.vertex;
    glm::dvec3 p(0.0);
    for (int pi = 0; pi < static_cast<int>(e.properties.size()); ++pi) {
      if (e.properties[pi].isList) {
        readList(e, i, &e == layout_.face && pi == layout_.indices);
        continue;
      }
      const std::string_view token = nextToken(e, i);
      if (isVertex && (pi == layout_.x || pi == layout_.y || pi == layout_.z)) {
        p[pi == layout_.x ? 0 : pi == layout_.y ? 1 : 2] = parseCoordinate(name_, lineNo_, token);
      } else {
        requireNumber(token);
      }
    }
    if (next_ != tokens_.size()) {
      failAtLine(name_, lineNo_,
                 "element '" + e.name + "' " + std::to_string(i) + " has " +
                     std::to_string(tokens_.size()) + " values, expected " + std::to_string(next_) +
                     " (the header's counts may be wrong)");
    }
    if (isVertex) mesh_.positions.push_back(p);
  }

  // A list property: its length, then its values; `indices` when it is the face's index list,
  // which is fan-triangulated into the mesh.
  void readList(const Element& e, uint64_t i, bool indices) {
    const std::string_view countToken = nextToken(e, i);
    long long n = 0;
    if (!parseInteger(countToken, n) || n < 0) {
      failAtLine(name_, lineNo_,
                 "bad list length " + quoted(countToken) + " in element '" + e.name + "'");
    }
    if (static_cast<size_t>(n) > tokens_.size() - next_) {
      failAtLine(name_, lineNo_,
                 "list of " + std::to_string(n) + " values has only " +
                     std::to_string(tokens_.size() - next_) + " on the line");
    }
    if (!indices) {
      for (long long k = 0; k < n; ++k) requireNumber(nextToken(e, i));
      return;
    }
    if (n < 3) {
      failAtLine(name_, lineNo_,
                 "face " + std::to_string(i) + " has " + std::to_string(n) +
                     " vertices, needs at least 3");
    }
    polygon_.clear();
    for (long long k = 0; k < n; ++k) polygon_.push_back(readIndex(nextToken(e, i)));
    for (size_t k = 1; k + 1 < polygon_.size(); ++k) {
      mesh_.triangles.push_back({polygon_[0], polygon_[k], polygon_[k + 1]});
    }
  }

  uint32_t readIndex(std::string_view token) const {
    long long index = 0;
    if (!parseInteger(token, index))
      failAtLine(name_, lineNo_, "bad vertex index " + quoted(token));
    if (index < 0 || static_cast<uint64_t>(index) >= layout_.vertex->count) {
      failAtLine(name_, lineNo_,
                 "vertex index " + std::to_string(index) + " is out of range: the file has " +
                     std::to_string(layout_.vertex->count) + " vertices");
    }
    return static_cast<uint32_t>(index);
  }

  void requireNumber(std::string_view token) const {
    double ignored;
    if (!parseNumber(token, ignored)) failAtLine(name_, lineNo_, "not a number: " + quoted(token));
  }

  const std::string& name_;
  const std::string& bytes_;
  const Header& header_;
  const Layout& layout_;
  TriangleMesh& mesh_;
  LineReader lines_;
  std::vector<std::string_view> tokens_;  // of the current line
  size_t lineNo_ = 0;                     // of the current line
  size_t next_ = 0;                       // the current line's next token
  std::vector<uint32_t> polygon_;         // of the current face
};

// ---- In pieces ----

// n bytes of the file open as `fd` from byte `at`. Throws naming the file when it cannot.
void readFileAt(const std::string& name, int fd, uint64_t at, char* into, size_t n) {
  size_t done = 0;
  while (done < n) {
    const ssize_t got = ::pread(fd, into + done, n - done, off_t(at + done));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0)
      throw Error(name + ": cannot read" +
                  (got < 0 ? std::string(": ") + std::strerror(errno)
                           : std::string(": the file ended early (it shrank while read)")));
    done += size_t(got);
  }
}

// A binary PLY's vertices read on demand, a page at a time (pages of kPageVertices decoded to
// doubles, up to kPagesHeld of them, the least recently used let go), each coordinate checked
// finite when its page is first read.
class VertexPages {
 public:
  static constexpr uint64_t kPageVertices = uint64_t(1) << 16;  // 1.5 MB decoded
  static constexpr size_t kPagesHeld = 32;

  VertexPages(const std::string& name, int fd, const Header& header, const Layout& layout)
      : name_(name), fd_(fd), header_(header), layout_(layout) {
    for (const Property& p : layout.vertex->properties) {
      offsets_.push_back(record_);
      record_ += sizeOf(p.type);
    }
    const uint64_t pages = (layout.vertex->count + kPageVertices - 1) / kPageVertices;
    slotOf_.assign(size_t(pages), -1);
    checked_.assign(size_t(pages), false);
  }

  uint64_t count() const { return layout_.vertex->count; }
  size_t recordBytes() const { return record_; }
  uint64_t pages() const { return slotOf_.size(); }

  // The positions of page `page`, read (and held) where not held. Before a page's first read
  // throws for a coordinate that is not finite, every earlier page is read and checked: the
  // error names the first such coordinate in the file, as the whole read does.
  const glm::dvec3* page(uint64_t page) {
    int slot = slotOf_[size_t(page)];
    if (slot < 0) slot = load(page);
    used_[size_t(slot)] = ++clock_;
    return slots_[size_t(slot)].data();
  }

  // Every page not yet read, read and checked (in file order; the rest of the file's
  // coordinates, as the whole read checks them all).
  void checkAll() {
    for (uint64_t p = 0; p < pages(); ++p)
      if (!checked_[size_t(p)]) page(p);
  }

 private:
  int load(uint64_t page) {
    // Decoded first, into a vector of its own: a coordinate not finite is named (after every
    // earlier page is checked, which loads pages itself) before the page takes a slot.
    const uint64_t first = page * kPageVertices;
    const uint64_t n = std::min(kPageVertices, count() - first);
    std::string raw(size_t(n * record_), '\0');
    const uint64_t at = header_.bodyStart + first * record_;
    readAt(at, &raw);
    std::vector<glm::dvec3> out(static_cast<size_t>(n));
    const bool big = header_.format == Format::BigEndian;
    const int axes[3] = {layout_.x, layout_.y, layout_.z};
    std::atomic<bool> finite{true};
    parallelFor(0, int64_t(n), 4096, [&](int64_t begin, int64_t end) {
      bool all = true;
      for (int64_t v = begin; v < end; ++v)
        for (int k = 0; k < 3; ++k) {
          const size_t property = size_t(axes[k]);
          const double x = decode(raw.data() + size_t(v) * record_ + offsets_[property],
                                  layout_.vertex->properties[property].type, big);
          out[size_t(v)][k] = x;
          all = all && std::isfinite(x);
        }
      if (!all) finite = false;
    });
    if (!finite) {
      for (uint64_t earlier = 0; earlier < page; ++earlier)
        if (!checked_[size_t(earlier)]) this->page(earlier);
      for (uint64_t v = 0; v < n; ++v)
        for (int k = 0; k < 3; ++k) {
          const size_t property = size_t(axes[k]);
          requireFiniteAtByte(name_, size_t(at + v * record_ + offsets_[property]),
                              out[size_t(v)][k]);
        }
    }
    // A slot: a new one while fewer than kPagesHeld, else the least recently used.
    int slot;
    if (slots_.size() < kPagesHeld) {
      slot = int(slots_.size());
      slots_.emplace_back();
      pageOf_.push_back(0);
      used_.push_back(0);
    } else {
      slot = int(std::min_element(used_.begin(), used_.end()) - used_.begin());
      slotOf_[size_t(pageOf_[size_t(slot)])] = -1;
    }
    slots_[size_t(slot)] = std::move(out);
    checked_[size_t(page)] = true;
    slotOf_[size_t(page)] = slot;
    pageOf_[size_t(slot)] = page;
    return slot;
  }

  void readAt(uint64_t at, std::string* into) const {
    readFileAt(name_, fd_, at, into->data(), into->size());
  }

  const std::string& name_;
  const int fd_;
  const Header& header_;
  const Layout& layout_;
  std::vector<size_t> offsets_;  // of each vertex property in a record
  size_t record_ = 0;
  std::vector<int> slotOf_;  // per page: its slot, or -1
  std::vector<bool> checked_;
  std::vector<std::vector<glm::dvec3>> slots_;
  std::vector<uint64_t> pageOf_, used_;  // per slot
  uint64_t clock_ = 0;
};

}  // namespace

bool visitPlyBlocks(const std::string& path, const TriangleBlockVisitor& visit,
                    const Progress* progress) {
  InputFile file(path);
  // The header, from the first 64 KB (a longer one: false, the whole read takes the file).
  std::string head(size_t(std::min<uint64_t>(file.size(), 65536)), '\0');
  file.readExactly(head.data(), head.size());
  if (hasUtf8Bom(head) || head.compare(0, 4, "ply\n") != 0) return false;
  Header header;
  Layout layout;
  try {
    header = HeaderParser(path, head).parse();
    layout = findLayout(path, header);
  } catch (const Error&) {
    return false;  // the whole read names what is wrong
  }
  // The form read here: binary, the vertices (scalars only) and then the faces (the index list
  // only), nothing else.
  if (header.format == Format::Ascii || header.elements.size() != 2 ||
      layout.vertex != &header.elements[0] || layout.face != &header.elements[1] ||
      layout.face->properties.size() != 1)
    return false;
  for (const Property& p : layout.vertex->properties)
    if (p.isList) return false;
  VertexPages vertices(path, file.descriptor(), header, layout);
  const uint64_t faceStart = header.bodyStart + vertices.count() * vertices.recordBytes();
  const uint64_t faces = layout.face->count;
  if (faceStart > file.size() || faces > file.size() - faceStart) return false;
  const Property& list = layout.face->properties[0];
  const bool big = header.format == Format::BigEndian;
  const size_t countBytes = sizeOf(list.countType), indexBytes = sizeOf(list.type);
  // Fewer bytes than the faces' counts need: the whole read names it as it does.
  if (faces > (file.size() - faceStart) / countBytes) return false;

  // The faces read in pieces of about 4 MB, each piece's triangles (fans of its polygons) listed
  // by index first, then visited in blocks on several threads where their pages are few enough
  // to hold at once (a file written in pieces by the streamed export refers to a few).
  constexpr size_t kPieceBytes = size_t(4) << 20;
  constexpr int64_t kBlockTriangles = 4096;
  std::string buffer;
  size_t bufferAt = 0;              // the next unread byte of the buffer
  uint64_t bufferFile = faceStart;  // the file offset of buffer[0]
  uint64_t fileAt = faceStart;      // the next byte to read from the file
  const auto need = [&](size_t n, uint64_t face) {
    if (buffer.size() - bufferAt >= n) return;
    buffer.erase(0, bufferAt);
    bufferFile += bufferAt;
    bufferAt = 0;
    const uint64_t left = file.size() - fileAt;
    const size_t more = size_t(std::min<uint64_t>(left, std::max(kPieceBytes, n)));
    const size_t had = buffer.size();
    buffer.resize(had + more);
    if (more > 0) readFileAt(path, file.descriptor(), fileAt, &buffer[had], more);
    fileAt += more;
    if (buffer.size() < n) {
      vertices.checkAll();  // a coordinate not finite comes first, as in the whole read
      failAtByte(path, size_t(file.size()),
                 "unexpected end of file in element 'face' " + std::to_string(face) + " of " +
                     std::to_string(faces) + " (truncated, or the header's counts are wrong)");
    }
  };
  std::vector<std::array<uint32_t, 3>> triangles;
  uint64_t visited = 0;  // triangles visited
  std::vector<uint32_t> polygon;
  // The usual form (a byte's count of 3, 32-bit little-endian indices; what Strata writes) read
  // at once; anything else (or an index out of range: the message) as the whole read reads it.
  const bool usual = !big && countBytes == 1 &&
                     (list.type == Type::Int32 || list.type == Type::UInt32) &&
                     hostIsLittleEndian();
  const uint64_t usualLimit = list.type == Type::Int32
                                  ? std::min<uint64_t>(vertices.count(), uint64_t(1) << 31)
                                  : vertices.count();
  std::vector<uint8_t> needed(size_t(vertices.pages()), 0);  // per page, for one piece
  for (uint64_t face = 0; face < faces;) {
    // One piece's triangles, by index: in the usual form, a piece of triangles decoded on
    // several threads where every record is one; else (or where one is not) a face at a time.
    triangles.clear();
    const uint64_t pieceEnd = bufferFile + bufferAt + kPieceBytes;
    const uint64_t whole = std::min<uint64_t>(faces - face, kPieceBytes / 13);
    bool byFace = true;
    if (usual && whole * 13 <= file.size() - (bufferFile + bufferAt)) {
      need(size_t(whole * 13), face);
      triangles.resize(size_t(whole));
      std::atomic<bool> unusual{false};
      const char* records = &buffer[bufferAt];
      parallelFor(0, int64_t(whole), kBlockTriangles, [&](int64_t first, int64_t last) {
        for (int64_t t = first; t < last; ++t) {
          const char* record = records + 13 * size_t(t);
          uint32_t corners[3];
          std::memcpy(corners, record + 1, 12);
          if (uint8_t(record[0]) != 3 || corners[0] >= usualLimit || corners[1] >= usualLimit ||
              corners[2] >= usualLimit)
            unusual = true;
          triangles[size_t(t)] = {corners[0], corners[1], corners[2]};
        }
      });
      if (unusual) {
        triangles.clear();
      } else {
        bufferAt += size_t(whole * 13);
        face += whole;
        byFace = false;
      }
    }
    while (byFace && face < faces && bufferFile + bufferAt < pieceEnd) {
      if (usual && buffer.size() - bufferAt >= 13 && uint8_t(buffer[bufferAt]) == 3) {
        uint32_t corners[3];
        std::memcpy(corners, &buffer[bufferAt + 1], 12);
        if (corners[0] < usualLimit && corners[1] < usualLimit && corners[2] < usualLimit) {
          triangles.push_back({corners[0], corners[1], corners[2]});
          bufferAt += 13;
          ++face;
          continue;
        }
      }
      need(countBytes, face);
      const size_t countAt = size_t(bufferFile + bufferAt);
      const double count = decode(&buffer[bufferAt], list.countType, big);
      bufferAt += countBytes;
      if (count < 0) {
        vertices.checkAll();
        failAtByte(path, countAt, "negative list length in element 'face'");
      }
      const size_t n = size_t(count);
      if (double(n) * double(indexBytes) > double(file.size() - (bufferFile + bufferAt))) {
        vertices.checkAll();  // a list longer than the file: truncated, as the whole read says
        failAtByte(path, size_t(file.size()),
                   "unexpected end of file in element 'face' " + std::to_string(face) + " of " +
                       std::to_string(faces) + " (truncated, or the header's counts are wrong)");
      }
      need(n * indexBytes, face);
      if (n < 3) {
        vertices.checkAll();
        failAtByte(path, countAt,
                   "face " + std::to_string(face) + " has " + std::to_string(n) +
                       " vertices, needs at least 3");
      }
      polygon.clear();
      for (size_t k = 0; k < n; ++k) {
        const double index = decode(&buffer[bufferAt], list.type, big);
        if (index < 0 || index >= double(vertices.count())) {
          vertices.checkAll();
          failAtByte(path, size_t(bufferFile + bufferAt),
                     "vertex index " + std::to_string(static_cast<long long>(index)) +
                         " is out of range: the file has " + std::to_string(vertices.count()) +
                         " vertices");
        }
        bufferAt += indexBytes;
        polygon.push_back(uint32_t(index));
      }
      for (size_t k = 1; k + 1 < polygon.size(); ++k)
        triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
      ++face;
    }
    if (progress) progress->check();
    // The pages this piece refers to, held at once where they fit.
    std::vector<uint64_t> pages;
    for (const auto& t : triangles)
      for (uint32_t v : t) {
        const uint64_t page = v / VertexPages::kPageVertices;
        if (needed[size_t(page)]) continue;
        needed[size_t(page)] = 1;
        pages.push_back(page);
      }
    for (uint64_t page : pages) needed[size_t(page)] = 0;
    std::sort(pages.begin(), pages.end());
    if (pages.size() <= VertexPages::kPagesHeld) {
      std::vector<const glm::dvec3*> held(size_t(vertices.pages()), nullptr);
      for (uint64_t p : pages) held[size_t(p)] = vertices.page(p);
      parallelFor(0, int64_t(triangles.size()), kBlockTriangles, [&](int64_t first, int64_t last) {
        std::vector<glm::dvec3> corners(size_t(3 * kBlockTriangles));
        for (int64_t b = first; b < last; b += kBlockTriangles) {
          const int64_t e = std::min(last, b + kBlockTriangles);
          for (int64_t t = b; t < e; ++t)
            for (int k = 0; k < 3; ++k) {
              const uint32_t v = triangles[size_t(t)][size_t(k)];
              corners[3 * size_t(t - b) + size_t(k)] =
                  held[v / VertexPages::kPageVertices][v % VertexPages::kPageVertices];
            }
          visit(visited + uint64_t(b), corners.data(), size_t(e - b));
        }
      });
    } else {
      // Scattered (not a file of ours): a block at a time on this thread.
      std::vector<glm::dvec3> corners;
      for (size_t b = 0; b < triangles.size(); b += size_t(kBlockTriangles)) {
        if (progress) progress->check();
        const size_t e = std::min(triangles.size(), b + size_t(kBlockTriangles));
        corners.clear();
        for (size_t t = b; t < e; ++t)
          for (uint32_t v : triangles[t])
            corners.push_back(
                vertices.page(v / VertexPages::kPageVertices)[v % VertexPages::kPageVertices]);
        visit(visited + b, corners.data(), e - b);
      }
    }
    visited += triangles.size();
  }
  vertices.checkAll();
  const uint64_t end = bufferFile + bufferAt;
  if (end < file.size())
    failAtByte(path, size_t(end),
               std::to_string(file.size() - end) +
                   " bytes of data after the last element (the header's counts disagree with "
                   "the data)");
  return true;
}

TriangleMesh parsePly(const std::string& name, const std::string& bytes, MeshReadReport* report) {
  // A UTF-8 byte order mark before the first line (Windows editors write one): skipped.
  if (hasUtf8Bom(bytes)) return parsePly(name, bytes.substr(3), report);
  // Text with classic Mac OS line ends is read from an LF copy of the same length: the header's
  // byte offsets hold in the file too, from which a binary body is read as it is.
  const std::optional<std::string> lf = lfCopyIfCrOnlyLineEnds(bytes);
  const std::string& text = lf ? *lf : bytes;
  const Header header = HeaderParser(name, text).parse();
  const Layout layout = findLayout(name, header);
  TriangleMesh mesh;
  if (header.format == Format::Ascii) {
    AsciiBodyParser(name, text, header, layout, mesh).parse();
  } else {
    parseBinaryBody(name, bytes, header, layout, mesh);
  }
  report->fileVertices = layout.vertex->count;
  report->fileFaces = layout.face->count;
  requireMeasurableExtent(name, mesh);
  return mesh;
}

}  // namespace meshio
}  // namespace strata
