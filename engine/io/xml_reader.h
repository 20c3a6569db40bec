// Private to engine/io: XML through expat, with namespaces resolved, for 3MF parts (models and
// OPC relationships). Element and attribute names arrive as (namespace URI, local name, prefix
// as written), so callers match namespaces by URI whatever prefix a file binds them to. Expat
// checks well-formedness and decodes character and predefined entity references in attribute
// values; this reader adds the limits outside input needs:
// - a document type declaration (DOCTYPE) or entity declaration stops the parse with an error
//   (no entity expansion at all, so no "billion laughs"; expat's amplification limits are set
//   too where the library has them);
// - at most kMaxXmlAttributes attributes (namespace declarations included) per element and
//   kMaxXmlDepth nested elements.
// Character data, comments and processing instructions are not reported.
//
// Errors throw strata::Error "<where>: line <n>: <what>", `where` naming the file and part.
// Synchronous; one reader parses one document on one thread.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace strata {
namespace meshio {

constexpr size_t kMaxXmlAttributes = 256;
constexpr size_t kMaxXmlDepth = 1000;

// A name as the document wrote it, its namespace resolved. Views into the parser's buffers:
// valid only during the callback that received them.
struct XmlName {
  std::string_view uri;     // "" when the name is in no namespace
  std::string_view local;   // "vertex"
  std::string_view prefix;  // as written, "" when none ("m" for m:color)

  // "prefix:local" or "local", for messages.
  std::string qualified() const;
};

struct XmlAttribute {
  XmlName name;
  std::string_view value;  // entity and character references decoded
};

// A start tag (<a ...> or <a .../>; an empty-element tag is a start and an end).
struct XmlElement {
  XmlName name;
  std::vector<XmlAttribute> attributes;  // xmlns declarations are not among them
  size_t line = 0;                       // 1-based, where the tag starts

  // The value of the attribute in no namespace with this local name (how XML writes an
  // element's own attributes: unprefixed), or nullptr.
  const std::string_view* attribute(std::string_view local) const;
};

class XmlReader {
 public:
  // What a document is reported to. A callback may throw: the parse stops and parse()
  // rethrows that exception.
  class Handler {
   public:
    virtual ~Handler() = default;
    virtual void startElement(const XmlElement& element) = 0;
    // `line`: where the end tag is (for <a/>, where the tag starts).
    virtual void endElement(const XmlName& name, size_t line) = 0;
  };

  // `where` prefixes every message: "<file>: <part path inside the zip>".
  explicit XmlReader(std::string where);

  // Parses one whole document held in memory (any size), calling `handler` in document order.
  // Throws strata::Error on malformed XML (with the line), on the limits above, and on a
  // document with no root element; rethrows what a callback threw.
  void parse(std::string_view text, Handler& handler);

  // The URI bound to `prefix` ("" for the default namespace) where the parse is now (inside a
  // callback: the scope of the element reported), or nullptr when none is bound.
  const std::string* namespaceUri(std::string_view prefix) const;
  // Whether some prefix in scope (or the default namespace) is bound to `uri`.
  bool isBound(std::string_view uri) const;

  [[noreturn]] void fail(size_t line, const std::string& what) const;
  const std::string& where() const { return where_; }

 private:
  struct Parse;  // one parse's expat state and callbacks (xml_reader.cpp)

  std::string where_;
  std::vector<std::pair<std::string, std::string>> bindings_;  // (prefix, URI), innermost last
};

}  // namespace meshio
}  // namespace strata
