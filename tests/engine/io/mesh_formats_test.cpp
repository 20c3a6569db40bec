// The table of mesh formats: every entry is well formed, every writable format reads back
// through every reading path, dispatch goes through the table (case-insensitively), unknown
// extensions get the listed messages, and the usage lists name every extension. Written
// against the table itself, so a new entry is tested without editing this file.
#include "engine/io/mesh_formats.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cctype>
#include <functional>
#include <set>

#include "engine/geometry/mesh_check.h"
#include "engine/io/mesh_io.h"
#include "engine/io/mesh_writers.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace {

// A unit cube (leaf 1) and a tetrahedron beside it (leaf 2): closed, outward, two components,
// coordinates exact in float32. Volume 1 + 1/6.
ExportMesh smallClosedMesh() {
  ExportMesh em;
  em.mesh.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1},
                       {1, 1, 1}, {0, 1, 1}, {3, 0, 0}, {4, 0, 0}, {3, 1, 0}, {3, 0, 1}};
  em.mesh.triangles = {{0, 2, 1},  {0, 3, 2},  {4, 5, 6},   {4, 6, 7},  {0, 1, 5}, {0, 5, 4},
                       {3, 7, 6},  {3, 6, 2},  {0, 4, 7},   {0, 7, 3},  {1, 2, 6}, {1, 6, 5},
                       {8, 10, 9}, {8, 9, 11}, {8, 11, 10}, {9, 10, 11}};
  em.triangleLeaf.assign(12, 1);
  em.triangleLeaf.resize(16, 2);
  em.leaves[1] = {"cube", {1.0f, 0.0f, 0.0f}};
  em.leaves[2] = {"tetrahedron", {0.0f, 0.0f, 1.0f}};
  return em;
}
constexpr double kVolume = 1.0 + 1.0 / 6.0;

std::string tempPath(const std::string& fileName) {
  const auto* info = testing::UnitTest::GetInstance()->current_test_info();
  return testing::TempDir() + "/strata_formats_" + info->name() + "_" + std::to_string(::getpid()) +
         "_" + fileName;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

std::string upper(std::string text) {
  for (char& ch : text) {
    if (ch >= 'a' && ch <= 'z') ch = static_cast<char>(ch - 'a' + 'A');
  }
  return text;
}

// Whether `text` names ".ext" as a whole word (not ".st" inside ".stl").
bool namesExtension(const std::string& text, const std::string& ext) {
  const std::string dotted = "." + ext;
  for (size_t at = text.find(dotted); at != std::string::npos; at = text.find(dotted, at + 1)) {
    const size_t end = at + dotted.size();
    if (end == text.size() || !std::isalnum(static_cast<unsigned char>(text[end]))) return true;
  }
  return false;
}

void expectSmallClosedMesh(const TriangleMesh& mesh, const std::string& what) {
  const MeshCheck check = checkMesh(mesh);
  EXPECT_TRUE(check.watertight()) << what;
  EXPECT_EQ(mesh.triangles.size(), 16u) << what;
  EXPECT_EQ(check.components, 2) << what;
  EXPECT_NEAR(check.volume, kVolume, 1e-9) << what;
}

// ---- The table ----

TEST(MeshFormats, EntriesAreWellFormedAndExtensionsUnique) {
  std::set<std::string> seen;
  for (const MeshFormat& format : meshFormats()) {
    EXPECT_STRNE(format.label, "");
    EXPECT_FALSE(format.extensions.empty()) << format.label;
    EXPECT_TRUE(format.supports(MeshAccess::Read) || format.supports(MeshAccess::Write))
        << format.label;
    ASSERT_NE(format.readNote, nullptr) << format.label;
    ASSERT_NE(format.writeNote, nullptr) << format.label;
    for (const std::string& ext : format.extensions) {
      EXPECT_FALSE(ext.empty()) << format.label;
      EXPECT_EQ(ext.find('.'), std::string::npos) << format.label << ": " << ext;
      EXPECT_EQ(lowerExtension("x." + ext), ext) << format.label << ": not lower case";
      EXPECT_TRUE(seen.insert(ext).second) << ext << " belongs to two formats";
    }
  }
}

// Exports are re-read and checked (app/command_export.cpp), so what is written must be readable.
TEST(MeshFormats, EveryWritableFormatIsReadable) {
  for (const MeshFormat& format : meshFormats()) {
    if (format.supports(MeshAccess::Write)) {
      EXPECT_TRUE(format.supports(MeshAccess::Read)) << format.label;
    }
  }
}

TEST(MeshFormats, LowerExtension) {
  EXPECT_EQ(lowerExtension("part.stl"), "stl");
  EXPECT_EQ(lowerExtension("dir.v2/Part.STL"), "stl");
  EXPECT_EQ(lowerExtension("C:\\dir.v2\\Part.3MF"), "3mf");
  EXPECT_EQ(lowerExtension("archive.tar.Gz"), "gz");
  EXPECT_EQ(lowerExtension("README"), "");
  EXPECT_EQ(lowerExtension("dir.d/file"), "");
  EXPECT_EQ(lowerExtension("file."), "");
  EXPECT_EQ(lowerExtension(""), "");
}

TEST(MeshFormats, LookupByPathIgnoresCase) {
  for (const MeshFormat& format : meshFormats()) {
    for (const std::string& ext : format.extensions) {
      EXPECT_EQ(meshFormatForPath("dir/part." + ext), &format) << ext;
      EXPECT_EQ(meshFormatForPath("dir/PART." + upper(ext)), &format) << ext;
      for (MeshAccess access : {MeshAccess::Read, MeshAccess::Write}) {
        EXPECT_EQ(meshFormatFor("p." + upper(ext), access),
                  format.supports(access) ? &format : nullptr)
            << ext;
      }
    }
  }
  EXPECT_EQ(meshFormatForPath("part.step"), nullptr);
  EXPECT_EQ(meshFormatForPath("stl"), nullptr);
  EXPECT_EQ(meshFormatForPath("stl.d/part"), nullptr);
}

// ---- Round trips through every writable format ----

TEST(MeshFormats, EveryWritableFormatRoundTrips) {
  const ExportMesh em = smallClosedMesh();
  for (const std::string& ext : meshExtensions(MeshAccess::Write)) {
    const std::string path = tempPath("round." + ext);
    writeMeshFile(path, em);
    expectSmallClosedMesh(readMeshFileRaw(path), path + " (raw)");
    MeshReadReport report;
    expectSmallClosedMesh(readMeshFile(path, {}, &report), path + " (prepared)");
    EXPECT_TRUE(report.warnings.empty()) << path << ": " << report.warnings.front();
    // The entry's own functions, as the table holds them.
    const MeshFormat* format = meshFormatForPath(path);
    ASSERT_NE(format, nullptr);
    MeshReadReport direct;
    expectSmallClosedMesh(format->parse(path, readWholeFile(path), &direct), path + " (parse)");
  }
}

TEST(MeshFormats, UpperCaseExtensionsWriteAndRead) {
  const ExportMesh em = smallClosedMesh();
  for (const std::string& ext : meshExtensions(MeshAccess::Write)) {
    const std::string path = tempPath("UPPER." + upper(ext));
    writeMeshFile(path, em);
    expectSmallClosedMesh(readMeshFile(path), path);
    expectSmallClosedMesh(readMeshBytes(path, readWholeFile(path)), path + " (bytes)");
  }
}

// Every readable extension reaches its parser: empty bytes fail there, not as unknown.
TEST(MeshFormats, EveryReadableExtensionReachesItsParser) {
  for (const std::string& ext : meshExtensions(MeshAccess::Read)) {
    const std::string message = errorOf([&] { readMeshBytes("empty." + ext, ""); });
    EXPECT_EQ(message.find("unknown mesh format"), std::string::npos) << message;
    EXPECT_EQ(message.rfind("empty." + ext, 0), 0u) << message;
  }
}

// ---- Messages ----

TEST(MeshFormats, UnknownExtensionsGetTheListedMessages) {
  EXPECT_EQ(errorOf([] { readMeshBytes("model.3ds", "x"); }),
            "model.3ds: unknown mesh format '.3ds' (expected " +
                meshExtensionList(MeshAccess::Read) + ")");
  EXPECT_EQ(errorOf([] { readMeshBytes("model", "x"); }),
            "model: unknown mesh format '' (expected " + meshExtensionList(MeshAccess::Read) + ")");
  const std::string path = tempPath("model.Step");
  EXPECT_EQ(errorOf([&] { writeMeshFile(path, smallClosedMesh()); }),
            path + ": cannot write mesh format '.step' (supported: " +
                meshExtensionList(MeshAccess::Write, ", ") + ")");
  // A format that is read but not written is refused by the writer with the same message.
  for (const MeshFormat& format : meshFormats()) {
    if (format.supports(MeshAccess::Write)) continue;
    const std::string readOnly = tempPath("model." + format.extensions.front());
    EXPECT_EQ(errorOf([&] { writeMeshFile(readOnly, smallClosedMesh()); }),
              readOnly + ": cannot write mesh format '." + format.extensions.front() +
                  "' (supported: " + meshExtensionList(MeshAccess::Write, ", ") + ")");
  }
}

TEST(MeshFormats, ExtensionListsNameEveryExtensionOnce) {
  for (MeshAccess access : {MeshAccess::Read, MeshAccess::Write}) {
    const std::vector<std::string> extensions = meshExtensions(access);
    ASSERT_GE(extensions.size(), 2u);
    const std::string list = meshExtensionList(access);
    const std::string commas = meshExtensionList(access, ", ");
    std::string expected;
    for (size_t i = 0; i < extensions.size(); ++i) {
      if (i > 0) expected += i + 1 == extensions.size() ? " or " : ", ";
      expected += "." + extensions[i];
    }
    EXPECT_EQ(list, expected);
    EXPECT_EQ(commas.find(" or "), std::string::npos) << commas;
    EXPECT_EQ(commas.size(), list.size() - 2) << commas;  // " or " became ", "
  }
}

TEST(MeshFormats, UsageListsEveryExtensionWithItsNote) {
  for (MeshAccess access : {MeshAccess::Read, MeshAccess::Write}) {
    const std::string usage = meshFormatUsage(access);
    EXPECT_EQ(usage.find('\n'), std::string::npos) << usage;
    for (const MeshFormat& format : meshFormats()) {
      const char* note = access == MeshAccess::Read ? format.readNote : format.writeNote;
      for (const std::string& ext : format.extensions) {
        EXPECT_EQ(namesExtension(usage, ext), format.supports(access)) << usage << " / ." << ext;
      }
      if (format.supports(access) && note[0] != '\0') {
        EXPECT_NE(usage.find(std::string("(") + note + ")"), std::string::npos) << usage;
      }
    }
  }
}

}  // namespace
}  // namespace strata
