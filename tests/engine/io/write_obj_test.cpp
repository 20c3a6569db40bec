// OBJ + MTL as one atomic set (engine/io/write_obj.cpp): both files are replaced or neither.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

#include "engine/io/mesh_writers.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace {
namespace fs = std::filesystem;

// A closed tetrahedron of one leaf, and `copies` more far apart (for a file long enough to
// cancel midway).
ExportMesh tetrahedra(int copies = 1) {
  ExportMesh em;
  for (int i = 0; i < copies; ++i) {
    const uint32_t b = static_cast<uint32_t>(em.mesh.positions.size());
    const glm::dvec3 at(2.0 * i, 0, 0);
    em.mesh.positions.push_back(at);
    em.mesh.positions.push_back(at + glm::dvec3(1, 0, 0));
    em.mesh.positions.push_back(at + glm::dvec3(0, 1, 0));
    em.mesh.positions.push_back(at + glm::dvec3(0, 0, 1));
    for (const auto& t : {std::array<uint32_t, 3>{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}}) {
      em.mesh.triangles.push_back({b + t[0], b + t[1], b + t[2]});
      em.triangleLeaf.push_back(1);
    }
  }
  em.leaves[1] = {"part", {0.5f, 0.25f, 1.0f}};
  return em;
}

class WriteObjSet : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(testing::TempDir()) /
           ("strata_write_obj_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    obj_ = (dir_ / "part.obj").string();
    mtl_ = (dir_ / "part.mtl").string();
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  void plantOld() {
    writeFileAtomically(obj_, [](std::ostream& o) { o << "old obj"; });
    writeFileAtomically(mtl_, [](std::ostream& o) { o << "old mtl"; });
  }
  void expectNoTemporaryFiles() {
    EXPECT_TRUE(temporaryFilesOf(obj_).empty());
    EXPECT_TRUE(temporaryFilesOf(mtl_).empty());
  }

  fs::path dir_;
  std::string obj_, mtl_;
};

TEST_F(WriteObjSet, ReplacesBothFiles) {
  plantOld();
  writeMeshFile(obj_, tetrahedra());
  EXPECT_NE(readWholeFile(obj_).find("mtllib part.mtl\n"), std::string::npos);
  EXPECT_NE(readWholeFile(mtl_).find("newmtl part\n"), std::string::npos);
  expectNoTemporaryFiles();
}

// An OBJ written through a link (out.obj -> part.obj) is the link's destination, and its MTL
// goes beside that file, named after it (part.mtl, which part.obj names), not beside the link.
TEST_F(WriteObjSet, ThroughALinkTheMtlGoesBesideTheFile) {
  const std::string link = (dir_ / "out.obj").string();
  fs::create_symlink(obj_, link);
  writeMeshFile(link, tetrahedra());
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_NE(readWholeFile(obj_).find("mtllib part.mtl\n"), std::string::npos);
  EXPECT_NE(readWholeFile(mtl_).find("newmtl part\n"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir_ / "out.mtl"));
}

// The MTL is replaced first; then the OBJ cannot be (a folder stands at its path): the previous
// MTL is put back.
TEST_F(WriteObjSet, AnObjThatCannotBeReplacedLeavesThePreviousMtl) {
  writeFileAtomically(mtl_, [](std::ostream& o) { o << "old mtl"; });
  fs::create_directory(obj_);
  try {
    writeMeshFile(obj_, tetrahedra());
    ADD_FAILURE() << "a folder cannot be replaced by an OBJ";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(obj_), std::string::npos) << e.what();
  }
  EXPECT_EQ(readWholeFile(mtl_), "old mtl");
  EXPECT_TRUE(fs::is_directory(obj_));
  expectNoTemporaryFiles();

  // Without a previous MTL, the new one is removed again.
  fs::remove(mtl_);
  EXPECT_THROW(writeMeshFile(obj_, tetrahedra()), Error);
  EXPECT_FALSE(fs::exists(mtl_));
  expectNoTemporaryFiles();
}

// The MTL cannot be replaced (a folder at its path): nothing is, the OBJ keeps its old text.
TEST_F(WriteObjSet, AnMtlThatCannotBeReplacedLeavesThePreviousObj) {
  writeFileAtomically(obj_, [](std::ostream& o) { o << "old obj"; });
  fs::create_directory(mtl_);
  try {
    writeMeshFile(obj_, tetrahedra());
    ADD_FAILURE() << "a folder cannot be replaced by an MTL";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(mtl_), std::string::npos) << e.what();
  }
  EXPECT_EQ(readWholeFile(obj_), "old obj");
  expectNoTemporaryFiles();
}

TEST_F(WriteObjSet, CancelledMidwayKeepsBothPreviousFiles) {
  plantOld();
  Progress* self = nullptr;
  Progress progress([&](const std::string&, double) { self->cancel(); });
  self = &progress;
  EXPECT_THROW(writeMeshFile(obj_, tetrahedra(20000), &progress), Cancelled);
  EXPECT_EQ(readWholeFile(obj_), "old obj");
  EXPECT_EQ(readWholeFile(mtl_), "old mtl");
  expectNoTemporaryFiles();
}

}  // namespace
}  // namespace strata
