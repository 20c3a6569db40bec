// The expat wrapper under the 3MF reader: names arrive as (namespace URI, local name, prefix)
// whatever prefix binds the namespace, with the line of each tag; malformed XML names its line;
// DOCTYPEs and entity declarations, too many attributes and too deep nesting are refused; a
// handler's exception leaves parse() unchanged; tokens longer than expat's chunks read intact.
#include "engine/io/xml_reader.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "engine/util/error.h"

namespace strata {
namespace meshio {
namespace {

// Records every event as text: "start uri|local|prefix @line [attr=value ...]", "end ... @line".
class Recorder : public XmlReader::Handler {
 public:
  void startElement(const XmlElement& element) override {
    std::string event = "start " + describe(element.name) + " @" + std::to_string(element.line);
    for (const XmlAttribute& a : element.attributes) {
      event += " " + describe(a.name) + "=" + std::string(a.value);
    }
    events.push_back(event);
    if (onStart) onStart(element);
  }
  void endElement(const XmlName& name, size_t line) override {
    events.push_back("end " + describe(name) + " @" + std::to_string(line));
  }

  std::vector<std::string> events;
  std::function<void(const XmlElement&)> onStart;

 private:
  static std::string describe(const XmlName& name) {
    return std::string(name.uri) + "|" + std::string(name.local) + "|" + std::string(name.prefix);
  }
};

std::vector<std::string> eventsOf(const std::string& text) {
  XmlReader xml("doc.3mf: part.model");
  Recorder recorder;
  xml.parse(text, recorder);
  return recorder.events;
}

std::string errorOf(const std::string& text) {
  try {
    eventsOf(text);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

void expectError(const std::string& text, std::initializer_list<std::string> parts) {
  const std::string message = errorOf(text);
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos)
        << "\"" << message << "\" lacks \"" << part << "\"";
  }
}

TEST(XmlReader, NamesCarryTheirNamespaceWhateverThePrefix) {
  const std::vector<std::string> events = eventsOf(
      "<?xml version=\"1.0\"?>\n"
      "<a:root xmlns:a=\"urn:one\" xmlns=\"urn:two\" plain=\"1\" a:qualified=\"2\">\n"
      "  <child/>\n"
      "  <b:child xmlns:b=\"urn:one\" xmlns=\"\"><none/></b:child>\n"
      "</a:root>\n");
  const std::vector<std::string> expected = {
      "start urn:one|root|a @2 |plain|=1 urn:one|qualified|a=2",
      "start urn:two|child| @3",
      "end urn:two|child| @3",
      "start urn:one|child|b @4",
      "start |none| @4",
      "end |none| @4",
      "end urn:one|child|b @4",
      "end urn:one|root|a @5"};
  EXPECT_EQ(events, expected);
}

TEST(XmlReader, ResolvesPrefixesInScope) {
  XmlReader xml("doc");
  Recorder recorder;
  std::vector<std::string> seen;
  recorder.onStart = [&](const XmlElement& element) {
    const std::string* p = xml.namespaceUri("p");
    const std::string* d = xml.namespaceUri("");
    seen.push_back(std::string(element.name.local) + ":" + (p ? *p : "-") + "," + (d ? *d : "-") +
                   "," + (xml.isBound("urn:x") ? "x" : "") + (xml.isBound("urn:y") ? "y" : ""));
  };
  xml.parse(
      "<r xmlns:p=\"urn:x\"><s xmlns:p=\"urn:y\" xmlns=\"urn:d\"/><t xmlns=\"urn:d\"><u "
      "xmlns=\"\"/></t></r>",
      recorder);
  const std::vector<std::string> expected = {"r:urn:x,-,x", "s:urn:y,urn:d,y", "t:urn:x,urn:d,x",
                                             "u:urn:x,-,x"};
  EXPECT_EQ(seen, expected);
}

TEST(XmlReader, DecodesReferencesInAttributeValues) {
  const std::vector<std::string> events = eventsOf("<r v=\"&#49;&amp;&lt;&#x41;\"/>");
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0], "start |r| @1 |v|=1&<A");
}

TEST(XmlReader, MalformedXmlNamesTheLine) {
  expectError("<r>\n<a>\n</b>\n</r>",
              {"doc.3mf: part.model: line 3:", "mismatched tag", "open element is <a>", "line 2"});
  expectError("<r>\n<a x=1/>\n</r>", {"line 2:", "malformed XML", "not well-formed"});
  expectError("<r>\n<a x=\"1\" x=\"2\"/>\n</r>", {"line 2:", "duplicate attribute"});
  expectError("<r/>\n\n<s/>", {"line 3:", "junk after document element"});
  expectError("<r>\n<a>\n", {"line 3:", "element <a> is not closed (it starts at line 2)"});
  expectError("<r a=\"&undefined;\"/>", {"line 1:", "undefined entity"});
  expectError("<r>\n<p:a/>\n</r>", {"line 2:", "unbound prefix"});
  expectError("", {"no root element"});
  expectError("  \n <!-- only a comment -->\n", {"no root element"});
}

TEST(XmlReader, DoctypesAndEntitiesAreRefused) {
  // The billion laughs: refused where the DOCTYPE starts, before any entity is declared.
  std::string laughs = "<?xml version=\"1.0\"?>\n<!DOCTYPE r [\n<!ENTITY a \"lol\">\n";
  for (int i = 1; i < 10; ++i) {
    laughs += "<!ENTITY " + std::string(1, char('a' + i)) + " \"";
    for (int k = 0; k < 10; ++k) laughs += "&" + std::string(1, char('a' + i - 1)) + ";";
    laughs += "\">\n";
  }
  laughs += "]>\n<r v=\"&j;\">&j;</r>\n";
  expectError(laughs, {"line 2:", "document type declarations", "not allowed"});
  expectError("<!DOCTYPE r SYSTEM \"file:///etc/passwd\">\n<r>&x;</r>",
              {"line 1:", "document type declarations"});
  expectError("<!DOCTYPE r>\n<r/>", {"line 1:", "document type declarations"});
}

TEST(XmlReader, AttributeAndDepthLimits) {
  std::string many = "<r";
  for (size_t i = 0; i <= kMaxXmlAttributes; ++i) many += " a" + std::to_string(i) + "=\"1\"";
  expectError(many + "/>", {"line 1:", "more than 256 attributes in <r>"});

  std::string declarations = "<r";
  for (size_t i = 0; i <= kMaxXmlAttributes; ++i) {
    declarations += " xmlns:p" + std::to_string(i) + "=\"urn:" + std::to_string(i) + "\"";
  }
  expectError(declarations + "/>", {"line 1:", "more than 256 attributes"});

  auto nested = [](size_t depth) {
    std::string text;
    for (size_t i = 0; i < depth; ++i) text += "<e>";
    for (size_t i = 0; i < depth; ++i) text += "</e>";
    return text;
  };
  EXPECT_EQ(eventsOf(nested(kMaxXmlDepth)).size(), 2 * kMaxXmlDepth);
  expectError(nested(kMaxXmlDepth + 1), {"line 1:", "nest more than 1000 deep"});
}

TEST(XmlReader, HandlerExceptionsPassThrough) {
  XmlReader xml("doc");
  Recorder recorder;
  recorder.onStart = [&](const XmlElement& element) {
    if (element.name.local == "bad") xml.fail(element.line, "bad element");
  };
  try {
    xml.parse("<r>\n<ok/>\n<bad/>\n<never/>\n</r>", recorder);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "doc: line 3: bad element");
  }
  EXPECT_EQ(recorder.events.back(), "start |bad| @3");  // nothing after the throw
}

TEST(XmlReader, TokensLongerThanAChunkReadIntact) {
  // 5 MiB in one attribute value after 1.5 MiB of text: both span expat's 1 MiB chunks.
  const size_t size = size_t(5) << 20;
  std::string text = "<r>\n" + std::string(size_t(3) << 19, ' ') + "<a v=\"";
  text += std::string(size, 'x');
  text += "\"/>\n</r>\n";
  XmlReader xml("doc");
  Recorder recorder;
  size_t valueSize = 0;
  recorder.onStart = [&](const XmlElement& element) {
    if (element.name.local == "a") valueSize = element.attribute("v")->size();
  };
  xml.parse(text, recorder);
  EXPECT_EQ(valueSize, size);
  EXPECT_EQ(recorder.events.back(), "end |r| @3");
}

}  // namespace
}  // namespace meshio
}  // namespace strata
