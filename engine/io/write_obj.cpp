// OBJ + MTL. The OBJ: comments naming Strata, the unit and the counts, `mtllib
// <basename>.mtl` (white space in the basename as '_'), every vertex as `v x y z` (%.9g), then per
// leaf (in leaf id order) `usemtl <material>` followed by its triangles as `f a b c` (1-based). The
// MTL: per leaf `newmtl`, a comment with the leaf's id and name, Ka 0, Kd = the colour
// sRGB-encoded, Ks 0, d 1, illum 1. Both files are one atomic set (writeFilesAtomically): both are
// replaced or neither, the OBJ (written first) replaced after the MTL it refers to.
#include <charconv>
#include <cstdio>
#include <map>
#include <set>
#include <vector>

#include "engine/io/mesh_writer_formats.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace meshio {
namespace {

// Material names: the leaf name with every character outside [A-Za-z0-9_-] replaced by '_'
// ("leaf_<id>" when empty), then "_2", "_3", ... appended until unique.
std::map<uint32_t, std::string> materialNames(const std::map<uint32_t, LeafStyle>& leaves) {
  std::map<uint32_t, std::string> names;
  std::set<std::string> taken;
  for (const auto& [id, style] : leaves) {
    std::string base;
    for (char ch : style.name) {
      const bool ok = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                      (ch >= '0' && ch <= '9') || ch == '_' || ch == '-';
      base += ok ? ch : '_';
    }
    if (base.empty()) base = "leaf_" + std::to_string(id);
    std::string name = base;
    for (int n = 2; taken.count(name); ++n) name = base + "_" + std::to_string(n);
    taken.insert(name);
    names[id] = name;
  }
  return names;
}

std::string stemOf(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t begin = slash == std::string::npos ? 0 : slash + 1;
  const size_t dot = path.rfind('.');
  return path.substr(begin,
                     dot == std::string::npos || dot < begin ? std::string::npos : dot - begin);
}

std::string mtlText(const ExportMesh& em, const std::map<uint32_t, std::string>& names) {
  std::string text = "# Strata export: one material per CSG leaf; Kd is the leaf colour (sRGB)\n";
  for (const auto& [id, style] : em.leaves) {
    text += "\nnewmtl " + names.at(id) + "\n";
    text += "# leaf " + std::to_string(id) + ": " + oneLine(style.name) + "\n";
    text += "Ka 0 0 0\nKd ";
    for (int k = 0; k < 3; ++k) {
      if (k) text += ' ';
      // 6 significant digits are finer than any display's steps.
      char buffer[32];
      std::snprintf(buffer, sizeof(buffer), "%.6f", linearToSrgb(style.color[k]));
      std::string number = buffer;
      while (number.back() == '0') number.pop_back();
      if (number.back() == '.') number.pop_back();
      text += number;
    }
    text += "\nKs 0 0 0\nd 1\nillum 1\n";
  }
  return text;
}

}  // namespace

void writeObj(const std::string& given, const ExportMesh& em, Progress* progress) {
  const TriangleMesh& mesh = em.mesh;
  const std::map<uint32_t, std::string> names = materialNames(em.leaves);
  // The MTL beside the OBJ the file is (a link's destination: out.obj -> /data/real.obj writes
  // /data/real.mtl, which /data/real.obj names), not beside the link.
  const std::string path = resolvedOutputPath(given);
  const size_t slash = path.find_last_of("/\\");
  const std::string folder = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  // `mtllib` takes names separated by white space: a space in the material file's name would
  // make other programs look for two files, so it becomes '_' there ("part 2.obj" refers to
  // "part_2.mtl").
  std::string mtlName = stemOf(path) + ".mtl";
  for (char& c : mtlName)
    if (c == ' ' || c == '\t') c = '_';
  const std::string mtlPath = folder + mtlName;

  // Triangles grouped by leaf, keeping their order within a leaf.
  std::map<uint32_t, std::vector<uint32_t>> byLeaf;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    byLeaf[em.triangleLeaf[t]].push_back(static_cast<uint32_t>(t));
  }

  auto writeMtl = [&](std::ostream& mtl) { mtl << mtlText(em, names); };
  auto writeObjText = [&](std::ostream& out) {
    std::string text;
    text += "# Strata export\n# unit: " + oneLine(em.unit) + "\n";
    text += "# " + std::to_string(mesh.positions.size()) + " vertices, " +
            std::to_string(mesh.triangles.size()) + " triangles, " + std::to_string(byLeaf.size()) +
            " materials (one per CSG leaf)\n";
    text += "mtllib " + mtlName + "\n";
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    const size_t total = mesh.positions.size() + mesh.triangles.size();
    writeRecords(
        out, mesh.positions.size(),
        [&](size_t first, size_t last, std::string& bytes) {
          for (size_t v = first; v < last; ++v) {
            const glm::dvec3& p = mesh.positions[v];
            bytes += "v ";
            appendNumber(bytes, p.x);
            bytes += ' ';
            appendNumber(bytes, p.y);
            bytes += ' ';
            appendNumber(bytes, p.z);
            bytes += '\n';
          }
        },
        progress, "write OBJ", 0, total);
    size_t done = mesh.positions.size();
    for (const auto& [leaf, triangles] : byLeaf) {
      const std::string group = "usemtl " + names.at(leaf) + "\n";
      out.write(group.data(), static_cast<std::streamsize>(group.size()));
      writeRecords(
          out, triangles.size(),
          [&, &triangles = triangles](size_t first, size_t last, std::string& bytes) {
            char number[16];
            for (size_t i = first; i < last; ++i) {
              bytes += 'f';
              for (uint32_t v : mesh.triangles[triangles[i]]) {
                bytes += ' ';
                const auto printed =
                    std::to_chars(number, number + sizeof(number), uint64_t(v) + 1);
                bytes.append(number, printed.ptr);
              }
              bytes += '\n';
            }
          },
          progress, "write OBJ", done, total);
      done += triangles.size();
    }
    if (progress) progress->check();
  };
  writeFilesAtomically({{given, writeObjText}, {mtlPath, writeMtl}});
}

}  // namespace meshio
}  // namespace strata
