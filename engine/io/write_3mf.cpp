// 3MF package: [Content_Types].xml, _rels/.rels (the 3D-model relationship) and
// 3D/3dmodel.model. The model: unit from the scene unit; an m:colorgroup (id 1, materials
// extension, not required) with one sRGB colour per leaf in leaf id order; one object (id 2,
// type model, pid 1) whose mesh lists every vertex (%.9g) and every triangle with pid="1" and
// p1 = its leaf's colour index; one build item placing it untransformed. The zip is built in
// memory (libzip, zip_archive.h) and committed with writeFileAtomically.
#include <cctype>
#include <map>

#include "engine/io/mesh_writer_formats.h"
#include "engine/io/zip_archive.h"
#include "engine/util/atomic_file.h"
#include "engine/util/error.h"

namespace strata {
namespace meshio {
namespace {

const char* const kContentTypes =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">\n"
    "  <Default Extension=\"rels\" "
    "ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/>\n"
    "  <Default Extension=\"model\" "
    "ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/>\n"
    "</Types>\n";

const char* const kRelationships =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
    "<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">\n"
    "  <Relationship Target=\"/3D/3dmodel.model\" Id=\"rel0\" "
    "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/>\n"
    "</Relationships>\n";

// The 3MF unit for a scene unit (British or American spelling or the usual abbreviation,
// case-insensitive); empty when 3MF has none.
std::string modelUnit(const std::string& sceneUnit) {
  std::string unit;
  for (char ch : sceneUnit) unit += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  static const std::map<std::string, std::string> kUnits = {{"millimetre", "millimeter"},
                                                            {"millimeter", "millimeter"},
                                                            {"mm", "millimeter"},
                                                            {"centimetre", "centimeter"},
                                                            {"centimeter", "centimeter"},
                                                            {"cm", "centimeter"},
                                                            {"metre", "meter"},
                                                            {"meter", "meter"},
                                                            {"m", "meter"},
                                                            {"inch", "inch"},
                                                            {"in", "inch"},
                                                            {"foot", "foot"},
                                                            {"ft", "foot"},
                                                            {"micron", "micron"},
                                                            {"micrometre", "micron"},
                                                            {"micrometer", "micron"},
                                                            {"um", "micron"}};
  auto it = kUnits.find(unit);
  return it == kUnits.end() ? std::string() : it->second;
}

std::string hexColour(const std::array<uint8_t, 3>& rgb) {
  static const char* const kDigits = "0123456789ABCDEF";
  std::string text = "#";
  for (uint8_t c : rgb) {
    text += kDigits[c >> 4];
    text += kDigits[c & 15];
  }
  return text;
}

std::string modelXml(const ExportMesh& em, const std::string& unit, Progress* progress) {
  const TriangleMesh& mesh = em.mesh;
  std::map<uint32_t, size_t> colourIndex;
  std::string xml;
  xml.reserve(64 + 48 * mesh.positions.size() + 56 * mesh.triangles.size());
  xml +=
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      "<model unit=\"" +
      unit +
      "\" xml:lang=\"en-US\" "
      "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\" "
      "xmlns:m=\"http://schemas.microsoft.com/3dmanufacturing/material/2015/02\">\n"
      " <metadata name=\"Application\">Strata</metadata>\n"
      " <resources>\n"
      "  <m:colorgroup id=\"1\">\n";
  for (const auto& [id, style] : em.leaves) {
    colourIndex[id] = colourIndex.size();
    xml += "   <m:color color=\"" + hexColour(srgb8(style.color)) + "\"/>\n";
  }
  xml +=
      "  </m:colorgroup>\n"
      "  <object id=\"2\" type=\"model\" pid=\"1\" pindex=\"0\">\n"
      "   <mesh>\n"
      "    <vertices>\n";
  const size_t total = mesh.positions.size() + mesh.triangles.size();
  size_t done = 0;
  for (const glm::dvec3& p : mesh.positions) {
    reportEvery(progress, "write 3MF", done++, total);
    xml += "     <vertex x=\"";
    appendNumber(xml, p.x);
    xml += "\" y=\"";
    appendNumber(xml, p.y);
    xml += "\" z=\"";
    appendNumber(xml, p.z);
    xml += "\"/>\n";
  }
  xml +=
      "    </vertices>\n"
      "    <triangles>\n";
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    reportEvery(progress, "write 3MF", done++, total);
    const auto& tri = mesh.triangles[t];
    xml += "     <triangle v1=\"" + std::to_string(tri[0]) + "\" v2=\"" + std::to_string(tri[1]) +
           "\" v3=\"" + std::to_string(tri[2]) + "\" pid=\"1\" p1=\"" +
           std::to_string(colourIndex.at(em.triangleLeaf[t])) + "\"/>\n";
  }
  xml +=
      "    </triangles>\n"
      "   </mesh>\n"
      "  </object>\n"
      " </resources>\n"
      " <build>\n"
      "  <item objectid=\"2\"/>\n"
      " </build>\n"
      "</model>\n";
  return xml;
}

}  // namespace

void write3mf(const std::string& path, const ExportMesh& em, Progress* progress) {
  const std::string unit = modelUnit(em.unit);
  if (unit.empty()) {
    throw Error(path + ": the scene unit " + oneLine(em.unit) +
                " has no 3MF equivalent (3MF allows millimetre, centimetre, metre, inch, foot, "
                "micron)");
  }
  std::vector<zipio::ZipEntry> entries;
  entries.push_back({"[Content_Types].xml", kContentTypes});
  entries.push_back({"_rels/.rels", kRelationships});
  entries.push_back({"3D/3dmodel.model", modelXml(em, unit, progress)});
  if (progress) progress->check();
  const std::string bytes = zipio::makeZip(entries, path);
  if (progress) progress->check();
  writeFileAtomically(path, [&](std::ostream& out) {
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  });
}

}  // namespace meshio
}  // namespace strata
