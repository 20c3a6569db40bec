// The expat wrapper of xml_reader.h.
#include "engine/io/xml_reader.h"

// expat.h declares the amplification limits only under XML_DTD, a macro of the library's own
// build; CMake checked that the library has them (engine/CMakeLists.txt).
#if defined(STRATA_EXPAT_HAS_AMPLIFICATION_LIMITS) && !defined(XML_DTD)
#define XML_DTD 1
#endif
#include <expat.h>

#include <algorithm>
#include <exception>
#include <iterator>
#include <memory>
#include <new>

#include "engine/io/mesh_readers.h"

namespace strata {
namespace meshio {
namespace {

// Between namespace URI, local name and prefix in the names expat reports ("uri\1local\1p").
// Not a character XML allows, so it is in no URI or name of a well-formed document (expat also
// refuses a URI containing the separator).
constexpr XML_Char kSeparator = '\x01';

// Bytes handed to expat per call. A token longer than a chunk is scanned again from its start
// at each call (expat 2.5 has no reparse deferral), so chunks double while a token is pending.
constexpr size_t kFirstChunk = size_t(1) << 20;
constexpr size_t kLargestChunk = size_t(1) << 30;  // XML_Parse takes an int

XmlName splitName(const XML_Char* expatName) {
  const std::string_view text(expatName);
  XmlName name;
  const size_t first = text.find(kSeparator);
  if (first == std::string_view::npos) {
    name.local = text;
    return name;
  }
  name.uri = text.substr(0, first);
  const std::string_view rest = text.substr(first + 1);
  const size_t second = rest.find(kSeparator);
  name.local = rest.substr(0, second);
  if (second != std::string_view::npos) name.prefix = rest.substr(second + 1);
  return name;
}

struct ParserFree {
  void operator()(XML_ParserStruct* parser) const { XML_ParserFree(parser); }
};

}  // namespace

std::string XmlName::qualified() const {
  return prefix.empty() ? std::string(local) : std::string(prefix) + ":" + std::string(local);
}

const std::string_view* XmlElement::attribute(std::string_view local) const {
  for (const XmlAttribute& a : attributes) {
    if (a.name.uri.empty() && a.name.local == local) return &a.value;
  }
  return nullptr;
}

// One document's parse: the expat parser, its callbacks (which forward to the handler and turn
// any exception into a stopped parse), and what messages need (the open elements).
struct XmlReader::Parse {
  Parse(XmlReader& reader, Handler& handler);

  bool feed(std::string_view text);
  [[noreturn]] void failFromExpat() const;

  size_t line() const { return static_cast<size_t>(XML_GetCurrentLineNumber(parser.get())); }
  // Runs a callback's work; an exception stops the parse and is kept for parse() to rethrow.
  template <typename Work>
  void guarded(Work&& work);
  void start(const XML_Char* name, const XML_Char** attributes);
  void end(const XML_Char* name);
  void declare(const XML_Char* prefix, const XML_Char* uri);
  void undeclare(const XML_Char* prefix);

  // expat's callbacks; `data` is the Parse.
  static void XMLCALL onStart(void* data, const XML_Char* name, const XML_Char** attributes);
  static void XMLCALL onEnd(void* data, const XML_Char* name);
  static void XMLCALL onNamespaceStart(void* data, const XML_Char* prefix, const XML_Char* uri);
  static void XMLCALL onNamespaceEnd(void* data, const XML_Char* prefix);
  static void XMLCALL onDoctype(void* data, const XML_Char*, const XML_Char*, const XML_Char*, int);
  static void XMLCALL onEntityDeclaration(void* data, const XML_Char* name, int, const XML_Char*,
                                          int, const XML_Char*, const XML_Char*, const XML_Char*,
                                          const XML_Char*);

  XmlReader& reader;
  Handler& handler;
  std::unique_ptr<XML_ParserStruct, ParserFree> parser;
  std::exception_ptr error;
  XmlElement element;                  // reused for every start tag
  std::vector<std::string> openNames;  // qualified; [0, depth) are open
  std::vector<size_t> openLines;       // where each open element starts
  size_t depth = 0;
  size_t declarations = 0;  // namespace declarations in the coming start tag
};

XmlReader::Parse::Parse(XmlReader& reader, Handler& handler)
    : reader(reader), handler(handler), parser(XML_ParserCreateNS(nullptr, kSeparator)) {
  if (!parser) throw std::bad_alloc();
  XML_Parser x = parser.get();
  XML_SetUserData(x, this);
  XML_SetReturnNSTriplet(x, XML_TRUE);  // prefixes too, to name elements as written
  XML_SetElementHandler(x, onStart, onEnd);
  XML_SetNamespaceDeclHandler(x, onNamespaceStart, onNamespaceEnd);
  // No entity can be declared, so none expands: a DOCTYPE stops the parse where it starts
  // (before an internal subset), an entity declaration anyway.
  XML_SetStartDoctypeDeclHandler(x, onDoctype);
  XML_SetEntityDeclHandler(x, onEntityDeclaration);
  XML_SetParamEntityParsing(x, XML_PARAM_ENTITY_PARSING_NEVER);
#ifdef STRATA_EXPAT_HAS_AMPLIFICATION_LIMITS
  // Tighter than expat's defaults (100x after 8 MiB); without entities the factor stays 1.
  XML_SetBillionLaughsAttackProtectionMaximumAmplification(x, 10.0f);
  XML_SetBillionLaughsAttackProtectionActivationThreshold(x, 1u << 20);
#endif
}

template <typename Work>
void XmlReader::Parse::guarded(Work&& work) {
  if (error) return;  // expat may call back once more after a stop
  try {
    work();
  } catch (...) {
    error = std::current_exception();
    XML_StopParser(parser.get(), XML_FALSE);
  }
}

void XMLCALL XmlReader::Parse::onStart(void* data, const XML_Char* name,
                                       const XML_Char** attributes) {
  Parse& p = *static_cast<Parse*>(data);
  p.guarded([&] { p.start(name, attributes); });
}

void XMLCALL XmlReader::Parse::onEnd(void* data, const XML_Char* name) {
  Parse& p = *static_cast<Parse*>(data);
  p.guarded([&] { p.end(name); });
}

void XMLCALL XmlReader::Parse::onNamespaceStart(void* data, const XML_Char* prefix,
                                                const XML_Char* uri) {
  Parse& p = *static_cast<Parse*>(data);
  p.guarded([&] { p.declare(prefix, uri); });
}

void XMLCALL XmlReader::Parse::onNamespaceEnd(void* data, const XML_Char* prefix) {
  Parse& p = *static_cast<Parse*>(data);
  p.guarded([&] { p.undeclare(prefix); });
}

void XMLCALL XmlReader::Parse::onDoctype(void* data, const XML_Char*, const XML_Char*,
                                         const XML_Char*, int) {
  Parse& p = *static_cast<Parse*>(data);
  p.guarded([&] {
    p.reader.fail(p.line(), "document type declarations (<!DOCTYPE ...>) are not allowed in 3MF");
  });
}

void XMLCALL XmlReader::Parse::onEntityDeclaration(void* data, const XML_Char* name, int,
                                                   const XML_Char*, int, const XML_Char*,
                                                   const XML_Char*, const XML_Char*,
                                                   const XML_Char*) {
  Parse& p = *static_cast<Parse*>(data);
  p.guarded([&] {
    p.reader.fail(p.line(), "entity declarations are not allowed in 3MF (entity " +
                                quoted(name ? name : "") + ")");
  });
}

void XmlReader::Parse::start(const XML_Char* name, const XML_Char** attributes) {
  element.name = splitName(name);
  element.line = line();
  element.attributes.clear();
  size_t count = declarations;
  declarations = 0;
  for (const XML_Char** a = attributes; *a; a += 2) {
    if (++count > kMaxXmlAttributes) {
      reader.fail(element.line, "more than " + std::to_string(kMaxXmlAttributes) +
                                    " attributes in <" + element.name.qualified() + ">");
    }
    element.attributes.push_back({splitName(a[0]), std::string_view(a[1])});
  }
  if (depth >= kMaxXmlDepth) {
    reader.fail(element.line, "elements nest more than " + std::to_string(kMaxXmlDepth) +
                                  " deep (at <" + element.name.qualified() + ">)");
  }
  if (openNames.size() == depth) {
    openNames.emplace_back();
    openLines.emplace_back();
  }
  openNames[depth].assign(element.name.prefix);
  if (!element.name.prefix.empty()) openNames[depth] += ':';
  openNames[depth].append(element.name.local);
  openLines[depth] = element.line;
  ++depth;
  handler.startElement(element);
}

void XmlReader::Parse::end(const XML_Char* name) {
  --depth;
  handler.endElement(splitName(name), line());
}

void XmlReader::Parse::declare(const XML_Char* prefix, const XML_Char* uri) {
  // Counted with the attributes of the start tag that follows; checked here too, so that a tag
  // of a million declarations stops at the limit.
  if (++declarations > kMaxXmlAttributes) {
    reader.fail(line(), "more than " + std::to_string(kMaxXmlAttributes) +
                            " attributes (namespace declarations) in one tag");
  }
  reader.bindings_.emplace_back(prefix ? prefix : "", uri ? uri : "");
}

void XmlReader::Parse::undeclare(const XML_Char* prefix) {
  const std::string_view name = prefix ? prefix : "";
  auto& bindings = reader.bindings_;
  for (auto it = bindings.rbegin(); it != bindings.rend(); ++it) {
    if (it->first == name) {
      bindings.erase(std::next(it).base());
      return;
    }
  }
}

bool XmlReader::Parse::feed(std::string_view text) {
  size_t fed = 0;
  size_t chunk = kFirstChunk;
  while (fed < text.size()) {
    const size_t n = std::min(chunk, text.size() - fed);
    if (XML_Parse(parser.get(), text.data() + fed, static_cast<int>(n), XML_FALSE) !=
        XML_STATUS_OK) {
      return false;
    }
    fed += n;
    // After a call, the current byte index is where expat stopped: the start of a pending token.
    const XML_Index parsed = XML_GetCurrentByteIndex(parser.get());
    if (parsed >= 0 && fed - static_cast<size_t>(parsed) > chunk / 2 && chunk < kLargestChunk) {
      chunk *= 2;
    }
  }
  return XML_Parse(parser.get(), "", 0, XML_TRUE) == XML_STATUS_OK;
}

void XmlReader::Parse::failFromExpat() const {
  const XML_Error code = XML_GetErrorCode(parser.get());
  const size_t at = line();
  if (code == XML_ERROR_NO_ELEMENTS) {
    if (depth > 0) {
      reader.fail(at, "unexpected end of text: element <" + openNames[depth - 1] +
                          "> is not closed (it starts at line " +
                          std::to_string(openLines[depth - 1]) + ")");
    }
    reader.fail(at, "no root element (empty XML document)");
  }
  std::string what = std::string("malformed XML: ") + XML_ErrorString(code) + " (column " +
                     std::to_string(XML_GetCurrentColumnNumber(parser.get()) + 1) + ")";
  if (code == XML_ERROR_TAG_MISMATCH && depth > 0) {
    what += ": the open element is <" + openNames[depth - 1] + "> from line " +
            std::to_string(openLines[depth - 1]);
  }
  reader.fail(at, what);
}

XmlReader::XmlReader(std::string where) : where_(std::move(where)) {}

void XmlReader::parse(std::string_view text, Handler& handler) {
  bindings_.clear();
  Parse parse(*this, handler);
  const bool ok = parse.feed(text);
  if (parse.error) std::rethrow_exception(parse.error);
  if (!ok) parse.failFromExpat();
}

const std::string* XmlReader::namespaceUri(std::string_view prefix) const {
  for (auto it = bindings_.rbegin(); it != bindings_.rend(); ++it) {
    if (it->first == prefix) return it->second.empty() ? nullptr : &it->second;
  }
  return nullptr;
}

bool XmlReader::isBound(std::string_view uri) const {
  for (const auto& binding : bindings_) {
    if (binding.second == uri && namespaceUri(binding.first) == &binding.second) return true;
  }
  return false;
}

void XmlReader::fail(size_t line, const std::string& what) const {
  failAtLine(where_, line, what);
}

}  // namespace meshio
}  // namespace strata
