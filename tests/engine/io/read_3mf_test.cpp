// The 3MF reader's XML (engine/io/read_3mf.cpp over expat): namespaces are matched by URI, so
// the core namespace may be bound to any prefix or be the default; <model> in another namespace
// is refused and core-named elements of other namespaces are skipped; malformed XML and the
// reader's own errors name the part and line; DOCTYPEs are refused. The package-level tests
// (relationships, zip errors, transforms) are in mesh_writers_test.cpp.
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <utility>

#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_io.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"
#include "tests/fuzz/fuzz_entries.h"

namespace strata {
namespace {

const char* const kCore = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";
const char* const kMaterial = "http://schemas.microsoft.com/3dmanufacturing/material/2015/02";
const char* const kProduction = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06";

// A closed tetrahedron (volume 1/6). `modelTag` is the root's start tag (line 2; the end tag
// repeats its name), `p` the prefix written before every other element ("" or "c:").
// `extraResource` goes inside <resources> (line 3), `itemAttrs` on the <item> and `extraItem`
// after it (line 11). Lines: 4 object and mesh, 5-6 vertices, 7-8 triangles, 9 end of object,
// 10 end of resources, 11 build, 12 end of model.
std::string tetraModel(const std::string& modelTag, const std::string& p,
                       const std::string& extraResource = "", const std::string& itemAttrs = "",
                       const std::string& extraItem = "") {
  const std::string close = "</" + modelTag.substr(1, modelTag.find_first_of(" >") - 1) + ">";
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + modelTag + "\n<" + p + "resources>" +
         extraResource + "\n<" + p + "object id=\"1\" type=\"model\"><" + p + "mesh><" + p +
         "vertices>\n<" + p + "vertex x=\"0\" y=\"0\" z=\"0\"/><" + p +
         "vertex x=\"1\" y=\"0\" z=\"0\"/>\n<" + p + "vertex x=\"0\" y=\"1\" z=\"0\"/><" + p +
         "vertex x=\"0\" y=\"0\" z=\"1\"/></" + p + "vertices><" + p + "triangles>\n<" + p +
         "triangle v1=\"0\" v2=\"2\" v3=\"1\"/><" + p + "triangle v1=\"0\" v2=\"1\" v3=\"3\"/>\n<" +
         p + "triangle v1=\"0\" v2=\"3\" v3=\"2\"/><" + p +
         "triangle v1=\"1\" v2=\"2\" v3=\"3\"/></" + p + "triangles>\n</" + p + "mesh></" + p +
         "object>\n</" + p + "resources>\n<" + p + "build><" + p + "item objectid=\"1\" " +
         itemAttrs + "/>" + extraItem + "</" + p + "build>\n" + close + "\n";
}

std::string coreDefault(const std::string& extraAttrs = "") {
  return "<model unit=\"millimeter\" xmlns=\"" + std::string(kCore) + "\"" + extraAttrs + ">";
}

TriangleMesh readModel(const std::string& xml, MeshReadReport* report = nullptr) {
  return readMeshBytes("part.3mf", fuzz::packageModel(xml), {}, report);
}

// The message of reading a package.
std::string errorOf(const std::string& bytes) {
  try {
    readMeshBytes("part.3mf", bytes);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

void expectContains(const std::string& message, std::initializer_list<std::string> parts) {
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos)
        << "\"" << message << "\" lacks \"" << part << "\"";
  }
}

// Expects reading `xml` as the model part of a package to fail with all of `parts`.
void expectError(const std::string& xml, std::initializer_list<std::string> parts) {
  expectContains(errorOf(fuzz::packageModel(xml)), parts);
}

void expectSameMesh(const TriangleMesh& a, const TriangleMesh& b) {
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.triangles, b.triangles);
}

TEST(Read3mfXml, CoreNamespaceUnderAnyPrefixReadsTheSame) {
  MeshReadReport report;
  const TriangleMesh reference = readModel(tetraModel(coreDefault(), ""), &report);
  EXPECT_EQ(reference.triangles.size(), 4u);
  EXPECT_NEAR(signedVolume(reference), 1.0 / 6.0, 1e-12);
  EXPECT_TRUE(report.warnings.empty());

  const std::string prefixed =
      "<c:model unit=\"millimeter\" xmlns:c=\"" + std::string(kCore) + "\">";
  // The default namespace bound to something else: unprefixed names are not core names.
  const std::string prefixedWithOtherDefault = "<core3mf:model xmlns:core3mf=\"" +
                                               std::string(kCore) +
                                               "\" xmlns=\"http://example.com/not-3mf\">";
  // Extensions required under unusual prefixes are still recognized by URI.
  const std::string extensions = "<x:model xmlns:x=\"" + std::string(kCore) +
                                 "\" xmlns:colours=\"" + kMaterial + "\" xmlns:prod=\"" +
                                 kProduction + "\" requiredextensions=\"colours prod\">";
  for (const auto& [tag, prefix] : {std::pair<std::string, std::string>{prefixed, "c:"},
                                    {prefixedWithOtherDefault, "core3mf:"},
                                    {extensions, "x:"}}) {
    SCOPED_TRACE(tag);
    MeshReadReport other;
    expectSameMesh(readModel(tetraModel(tag, prefix), &other), reference);
    EXPECT_TRUE(other.warnings.empty());
  }
  // The core namespace bound to a prefix on the root and made the default below it.
  std::string lower = tetraModel("<c:model xmlns:c=\"" + std::string(kCore) + "\">", "");
  for (const std::string element : {"<resources", "<build"}) {
    lower.insert(lower.find(element) + element.size(), " xmlns=\"" + std::string(kCore) + "\"");
  }
  expectSameMesh(readModel(lower), reference);
}

TEST(Read3mfXml, ModelInAnotherNamespaceIsRefused) {
  // Not the core namespace (a later year): not a 3MF model in any version Strata knows.
  const std::string future = "http://schemas.microsoft.com/3dmanufacturing/core/2099/01";
  expectError(tetraModel("<model xmlns=\"" + future + "\">", ""),
              {"part.3mf: 3D/3dmodel.model: line 2:", "<model> is not in the 3MF core namespace",
               "2099/01"});
  expectError(tetraModel("<m:model xmlns:m=\"" + future + "\">", "m:"),
              {"line 2:", "<m:model> is not in the 3MF core namespace"});
  // The core namespace is declared, but under a prefix the unprefixed <model> does not use.
  expectError(tetraModel("<model xmlns:c=\"" + std::string(kCore) + "\">", ""),
              {"line 2:", "<model> is not in the 3MF core namespace"});
  // A model in no namespace at all (no xmlns) is read as before, with a warning.
  MeshReadReport report;
  EXPECT_EQ(readModel(tetraModel("<model>", ""), &report).triangles.size(), 4u);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("declares no 3MF core namespace"), std::string::npos);
}

TEST(Read3mfXml, CoreNamesInOtherNamespacesAreSkipped) {
  // Elements with core local names in a namespace that is not required are extension content
  // the reader does not know: the specification has consumers ignore them. Read as core, these
  // would fail (object id 1 twice, a bad coordinate, an item placing a missing object).
  const std::string other = " xmlns:o=\"http://example.com/not-3mf\"";
  const std::string foreignObject =
      "<o:object id=\"1\" type=\"model\"><o:mesh><o:vertices><o:vertex x=\"bad\"/>"
      "</o:vertices></o:mesh></o:object>";
  MeshReadReport report;
  const TriangleMesh mesh = readModel(
      tetraModel(coreDefault(other), "", foreignObject, "", "<o:item objectid=\"99\"/>"), &report);
  EXPECT_EQ(mesh.triangles.size(), 4u);
  EXPECT_TRUE(report.warnings.empty());

  // Unprefixed elements are in the default namespace: another URI there hides the whole body.
  expectError(tetraModel("<c:model xmlns:c=\"" + std::string(kCore) +
                             "\" xmlns=\"http://example.com/not-3mf\">",
                         ""),
              {"line 12:", "the model has no <build> element"});

  // A path attribute is the production extension's only by its URI.
  expectError(tetraModel(coreDefault(" xmlns:prod=\"" + std::string(kProduction) + "\""), "", "",
                         "prod:path=\"/3D/other.model\""),
              {"line 11:", "refers to another model part", "prod:path='/3D/other.model'"});
  EXPECT_EQ(readModel(tetraModel(coreDefault(other), "", "", "o:path=\"/3D/other.model\""))
                .triangles.size(),
            4u);

  // A required extension is found by URI too, whatever its prefix.
  expectError(tetraModel(coreDefault(" xmlns:bl=\"http://schemas.microsoft.com/3dmanufacturing/"
                                     "beamlattice/2017/02\" requiredextensions=\"bl\""),
                         ""),
              {"line 2:", "beamlattice", "cannot read"});
  expectError(tetraModel(coreDefault(" requiredextensions=\"nope\""), ""),
              {"line 2:", "prefix 'nope'", "no xmlns"});
}

TEST(Read3mfXml, MalformedXmlNamesTheLine) {
  const std::string model = tetraModel(coreDefault(), "");
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = model;
    text.replace(text.find(from), from.size(), to);
    return text;
  };
  expectError(replaced("</vertices>", "</vertex>"),
              {"part.3mf: 3D/3dmodel.model: line 6:", "malformed XML", "mismatched tag",
               "<vertices> from line 4"});
  expectError(replaced("v2=\"2\"", "v2=2"), {"3D/3dmodel.model: line 7:", "malformed XML"});
  expectError(replaced("<triangle v1=\"0\" v2=\"3\"", "<triangle v1=\"0\" v1=\"3\""),
              {"line 8:", "duplicate attribute"});
  expectError(model + "<model/>\n", {"line 13:", "junk after document element"});
  expectError(model.substr(0, model.find("</resources>")),
              {"3D/3dmodel.model: line 10:", "<resources> is not closed (it starts at line 3)"});
  expectError(replaced("x=\"1\"", "x=\"&one;\""), {"line 5:", "undefined entity"});
  // Character references are XML, decoded before the number is read.
  expectSameMesh(readModel(replaced("x=\"1\"", "x=\"&#49;\"")), readModel(model));
  // The reader's own checks keep their lines under any prefix.
  const std::string prefixed = tetraModel("<c:model xmlns:c=\"" + std::string(kCore) + "\">", "c:");
  std::string badIndex = prefixed;
  badIndex.replace(badIndex.find("v3=\"3\"/></c:triangles>"), 6, "v3=\"4\"");
  expectError(badIndex, {"line 8:", "v3=4", "out of range"});
  std::string unexpected = prefixed;
  unexpected.replace(unexpected.find("<c:vertex "), 10, "<c:vortex ");
  expectError(unexpected, {"line 5:", "unexpected element <c:vortex> inside <vertices>"});
}

TEST(Read3mfXml, DoctypeIsRefused) {
  const std::string model = tetraModel(coreDefault(), "");
  const std::string declaration = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  const std::string body = model.substr(declaration.size());
  expectError(declaration + "<!DOCTYPE model [\n<!ENTITY e \"1\">\n]>\n" + body,
              {"part.3mf: 3D/3dmodel.model: line 2:", "document type declarations"});
  expectError(declaration + "<!DOCTYPE model SYSTEM \"http://example.com/model.dtd\">\n" + body,
              {"line 2:", "document type declarations"});
  // In the relationships part too.
  const std::string rels =
      "<?xml version=\"1.0\"?>\n<!DOCTYPE Relationships>\n<Relationships "
      "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"/>";
  expectContains(errorOf(fuzz::storedZip({{"_rels/.rels", rels}, {"3D/3dmodel.model", model}})),
                 {"part.3mf: _rels/.rels: line 2: document type declarations"});
}

// Nested components multiply: objects eight wide and twenty deep place 8^20 leaves from a file
// of a few KB. The reader counts placements, vertices and triangles before placing anything.
std::string nestedComponents(int width, int depth, bool leafTriangles) {
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n" + coreDefault() +
                    "\n<resources>\n<object id=\"1\" type=\"model\"><mesh><vertices>";
  for (int v = 0; v < 1000; ++v) xml += "<vertex x=\"" + std::to_string(v) + "\" y=\"0\" z=\"0\"/>";
  xml += "</vertices><triangles>";
  if (leafTriangles) xml += "<triangle v1=\"0\" v2=\"1\" v3=\"2\"/>";
  xml += "</triangles></mesh></object>\n";
  for (int level = 2; level <= depth + 1; ++level) {
    xml += "<object id=\"" + std::to_string(level) + "\" type=\"model\"><components>";
    for (int w = 0; w < width; ++w)
      xml += "<component objectid=\"" + std::to_string(level - 1) + "\"/>";
    xml += "</components></object>\n";
  }
  xml += "</resources>\n<build><item objectid=\"" + std::to_string(depth + 1) +
         "\"/></build>\n</model>\n";
  return xml;
}

TEST(Read3mf, NestedComponentsAreCountedBeforeTheyArePlaced) {
  const std::string noTriangles = errorOf(fuzz::packageModel(nestedComponents(8, 20, false)));
  EXPECT_NE(noTriangles.find("places more than 100000000 vertices"), std::string::npos)
      << noTriangles;
  const std::string withTriangles = errorOf(fuzz::packageModel(nestedComponents(8, 20, true)));
  EXPECT_NE(withTriangles.find("places more than 100000000 triangles (components included); raise "
                               "the limit with --max-triangles"),
            std::string::npos)
      << withTriangles;
}

// The uncompressed model part is bounded by the input limit (a small package may inflate to
// gigabytes), and the message says how to raise it; lifted on this thread, the same part reads.
TEST(Read3mfXml, ModelPartOverTheInputLimitNamesTheOption) {
  const std::string model = tetraModel(coreDefault(), "");
  const std::string package = fuzz::packageModel(model);
  const uint64_t saved = maxInputFileBytes();
  setMaxInputFileBytes(model.size() - 1);
  const std::string message = errorOf(package);
  bool readLifted = false;
  {
    const InputLimitLifted lifted;
    readLifted = !readMeshBytes("part.3mf", package).triangles.empty();
  }
  const std::string again = errorOf(package);
  setMaxInputFileBytes(saved);
  expectContains(message, {"3D/3dmodel.model", "part is too large", "--max-file-size"});
  EXPECT_TRUE(readLifted);
  expectContains(again, {"part is too large"});  // lifted only while alive
  EXPECT_NE(errorOf(package), again);            // and the default limit reads it
}

}  // namespace
}  // namespace strata
