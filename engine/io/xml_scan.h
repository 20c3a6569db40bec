// Private to engine/io: a small strict XML tag scanner for 3MF parts (models and OPC
// relationships). It yields start, end and empty-element tags with their raw attributes and
// the line each tag starts on; it skips the XML declaration, processing instructions,
// comments, CDATA and character data. It checks well-formedness of tags (names, quoting,
// duplicate attributes, nesting, one root element) and refuses document type declarations.
// It does not resolve namespaces or decode entity references in attribute values (3MF's
// numeric attributes contain none); callers compare qualified names.
//
// Errors throw strata::Error "<where>: line <n>: <what>", `where` naming the file and part.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace strata {
namespace meshio {

struct XmlTag {
  enum class Kind { Start, End, Empty };  // <a ...>, </a>, <a .../>
  Kind kind = Kind::Start;
  std::string_view name;  // qualified, e.g. "vertex" or "m:color"
  std::vector<std::pair<std::string_view, std::string_view>> attributes;  // raw values
  size_t line = 0;                                                        // 1-based

  // The raw value of the attribute with this qualified name, or nullptr.
  const std::string_view* attribute(std::string_view qualifiedName) const;
  // The part of the name before ':' ("" when unprefixed) and the part after.
  static std::string_view prefixOf(std::string_view qualifiedName);
  static std::string_view localOf(std::string_view qualifiedName);
};

class XmlScanner {
 public:
  // `text` must outlive the scanner and the tags it returns.
  XmlScanner(std::string_view text, std::string where);

  // The next tag; false once the root element is closed and only whitespace, comments and
  // processing instructions follow. Throws on malformed XML, including unclosed elements.
  bool next(XmlTag& tag);
  // Elements open around the position after the last tag returned (0 after the root closed).
  size_t depth() const { return open_.size(); }
  // The line the scanner has reached (after the last tag returned).
  size_t line() const { return line_; }

  [[noreturn]] void fail(size_t line, const std::string& what) const;

 private:
  void advanceTo(size_t pos);  // moves pos_ forward, counting newlines
  void skipPast(std::string_view terminator, const char* construct);
  std::string_view scanName(const char* context);
  void skipSpace();

  std::string_view text_;
  std::string where_;
  size_t pos_ = 0;
  size_t line_ = 1;
  bool rootSeen_ = false;
  std::vector<std::string_view> open_;
};

}  // namespace meshio
}  // namespace strata
