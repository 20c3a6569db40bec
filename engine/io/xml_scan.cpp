// The strict XML tag scanner of xml_scan.h.
#include "engine/io/xml_scan.h"

#include <algorithm>

#include "engine/io/mesh_readers.h"
#include "engine/util/error.h"

namespace strata {
namespace meshio {
namespace {

// Attributes per tag: 3MF elements have a handful; the bound keeps duplicate checks cheap.
constexpr size_t kMaxAttributes = 256;

bool isXmlSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

// Name characters: ASCII letters, digits and "_:.-", and any byte of a multi-byte UTF-8
// sequence (non-ASCII names are allowed by XML; they are compared byte-wise).
bool isNameChar(char c) {
  const unsigned char u = static_cast<unsigned char>(c);
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
         c == ':' || c == '.' || c == '-' || u >= 0x80;
}

bool isNameStart(char c) {
  return isNameChar(c) && !(c >= '0' && c <= '9') && c != '.' && c != '-';
}

}  // namespace

const std::string_view* XmlTag::attribute(std::string_view qualifiedName) const {
  for (const auto& a : attributes) {
    if (a.first == qualifiedName) return &a.second;
  }
  return nullptr;
}

std::string_view XmlTag::prefixOf(std::string_view qualifiedName) {
  const size_t colon = qualifiedName.find(':');
  return colon == std::string_view::npos ? std::string_view() : qualifiedName.substr(0, colon);
}

std::string_view XmlTag::localOf(std::string_view qualifiedName) {
  const size_t colon = qualifiedName.find(':');
  return colon == std::string_view::npos ? qualifiedName : qualifiedName.substr(colon + 1);
}

XmlScanner::XmlScanner(std::string_view text, std::string where)
    : text_(text), where_(std::move(where)) {
  if (text_.size() >= 3 && text_.substr(0, 3) == "\xEF\xBB\xBF") pos_ = 3;  // UTF-8 BOM
}

void XmlScanner::fail(size_t line, const std::string& what) const {
  failAtLine(where_, line, what);
}

void XmlScanner::advanceTo(size_t pos) {
  line_ += static_cast<size_t>(std::count(text_.begin() + static_cast<std::ptrdiff_t>(pos_),
                                          text_.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
  pos_ = pos;
}

void XmlScanner::skipPast(std::string_view terminator, const char* construct) {
  const size_t startLine = line_;
  const size_t end = text_.find(terminator, pos_);
  if (end == std::string_view::npos) fail(startLine, std::string("unterminated ") + construct);
  advanceTo(end + terminator.size());
}

void XmlScanner::skipSpace() {
  while (pos_ < text_.size() && isXmlSpace(text_[pos_])) {
    if (text_[pos_] == '\n') ++line_;
    ++pos_;
  }
}

std::string_view XmlScanner::scanName(const char* context) {
  const size_t begin = pos_;
  if (pos_ >= text_.size() || !isNameStart(text_[pos_])) {
    fail(line_, std::string("expected ") + context + " name, found " +
                    (pos_ < text_.size() ? quoted(text_.substr(pos_, 1)) : "end of text"));
  }
  while (pos_ < text_.size() && isNameChar(text_[pos_])) ++pos_;
  return text_.substr(begin, pos_ - begin);
}

bool XmlScanner::next(XmlTag& tag) {
  for (;;) {
    // Character data up to the next markup.
    const size_t lt = text_.find('<', pos_);
    const size_t dataEnd = lt == std::string_view::npos ? text_.size() : lt;
    if (open_.empty()) {
      // Outside the root element only whitespace may appear between markup.
      for (size_t i = pos_; i < dataEnd; ++i) {
        if (text_[i] == '\n') ++line_;
        if (!isXmlSpace(text_[i])) {
          pos_ = i;
          fail(line_, std::string("text outside the ") +
                          (rootSeen_ ? "root element (after it closed): " : "root element: ") +
                          quoted(text_.substr(i, 20)));
        }
      }
      pos_ = dataEnd;
    } else {
      advanceTo(dataEnd);
    }
    if (pos_ >= text_.size()) {
      if (!open_.empty()) {
        fail(line_,
             "unexpected end of text: element <" + std::string(open_.back()) + "> is not closed");
      }
      if (!rootSeen_) fail(line_, "no root element (empty XML document)");
      return false;
    }

    const std::string_view rest = text_.substr(pos_);
    if (rest.substr(0, 4) == "<!--") {
      skipPast("-->", "comment");
      continue;
    }
    if (rest.substr(0, 2) == "<?") {
      skipPast("?>", "processing instruction");
      continue;
    }
    if (rest.substr(0, 9) == "<![CDATA[") {
      if (open_.empty()) fail(line_, "CDATA section outside the root element");
      skipPast("]]>", "CDATA section");
      continue;
    }
    if (rest.substr(0, 2) == "<!") {
      fail(line_, "document type declarations and other '<!' markup are not allowed in 3MF");
    }

    tag.attributes.clear();
    tag.line = line_;
    ++pos_;  // '<'
    if (pos_ < text_.size() && text_[pos_] == '/') {
      ++pos_;
      tag.kind = XmlTag::Kind::End;
      tag.name = scanName("element");
      skipSpace();
      if (pos_ >= text_.size() || text_[pos_] != '>') {
        fail(line_, "expected '>' to end </" + std::string(tag.name) + ">");
      }
      ++pos_;
      if (open_.empty() || open_.back() != tag.name) {
        fail(tag.line, "end tag </" + std::string(tag.name) + "> " +
                           (open_.empty() ? std::string("without a start tag")
                                          : "does not match <" + std::string(open_.back()) + ">"));
      }
      open_.pop_back();
      return true;
    }

    tag.name = scanName("element");
    if (open_.empty() && rootSeen_) {
      fail(tag.line, "a second root element <" + std::string(tag.name) + ">");
    }
    for (;;) {
      const size_t beforeSpace = pos_;
      skipSpace();
      if (pos_ >= text_.size()) fail(tag.line, "unterminated tag <" + std::string(tag.name) + ">");
      const char c = text_[pos_];
      if (c == '>' || c == '/') {
        if (c == '/') {
          ++pos_;
          if (pos_ >= text_.size() || text_[pos_] != '>') {
            fail(line_, "expected '>' after '/' in <" + std::string(tag.name) + ">");
          }
          tag.kind = XmlTag::Kind::Empty;
        } else {
          tag.kind = XmlTag::Kind::Start;
          open_.push_back(tag.name);
        }
        ++pos_;
        rootSeen_ = true;
        return true;
      }
      if (pos_ == beforeSpace) {
        fail(line_, "expected whitespace, '>' or '/>' in <" + std::string(tag.name) + ">, found " +
                        quoted(text_.substr(pos_, 1)));
      }
      const std::string_view attrName = scanName("attribute");
      skipSpace();
      if (pos_ >= text_.size() || text_[pos_] != '=') {
        fail(line_, "attribute " + std::string(attrName) + " has no '=' and value");
      }
      ++pos_;
      skipSpace();
      if (pos_ >= text_.size() || (text_[pos_] != '"' && text_[pos_] != '\'')) {
        fail(line_, "value of attribute " + std::string(attrName) + " is not quoted");
      }
      const char quote = text_[pos_];
      const size_t valueBegin = pos_ + 1;
      const size_t valueEnd = text_.find(quote, valueBegin);
      if (valueEnd == std::string_view::npos) {
        fail(line_, "value of attribute " + std::string(attrName) + " is not terminated");
      }
      const std::string_view value = text_.substr(valueBegin, valueEnd - valueBegin);
      if (value.find('<') != std::string_view::npos) {
        fail(line_, "'<' inside the value of attribute " + std::string(attrName));
      }
      if (tag.attributes.size() >= kMaxAttributes) {
        fail(tag.line, "more than " + std::to_string(kMaxAttributes) + " attributes in <" +
                           std::string(tag.name) + ">");
      }
      if (tag.attribute(attrName)) {
        fail(line_, "attribute " + std::string(attrName) + " appears twice in <" +
                        std::string(tag.name) + ">");
      }
      tag.attributes.emplace_back(attrName, value);
      advanceTo(valueEnd + 1);
    }
  }
}

}  // namespace meshio
}  // namespace strata
