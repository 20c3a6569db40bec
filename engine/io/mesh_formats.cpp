// The table of mesh file formats (mesh_formats.h) and what derives from it.
#include "engine/io/mesh_formats.h"

#include "engine/io/mesh_readers.h"
#include "engine/io/mesh_writer_formats.h"

namespace strata {

const std::vector<MeshFormat>& meshFormats() {
  // label, extensions, parser, writer, read note, write note, bytes per triangle written,
  // unindexed, the stored coordinate, the block reader
  static const std::vector<MeshFormat> formats = {
      {"STL",
       {"stl"},
       meshio::parseStl,
       meshio::writeStl,
       "ascii or binary",
       "binary",
       50.0,
       true,
       meshio::storedAsFloat,
       meshio::visitStlBlocks},
      {"OBJ",
       {"obj"},
       meshio::parseObj,
       meshio::writeObj,
       "",
       "+ .mtl, a material per leaf",
       38.0,
       false,
       meshio::storedAsNineDigits},
      {"PLY",
       {"ply"},
       meshio::parsePly,
       meshio::writePly,
       "ascii or binary",
       "vertex colours",
       27.0,
       false,
       meshio::storedExactly,
       meshio::visitPlyBlocks},
      {"OFF", {"off"}, meshio::parseOff, nullptr, "", "", 0.0},
      {"3MF",
       {"3mf"},
       meshio::parse3mf,
       meshio::write3mf,
       "",
       "colour per leaf, the scene's unit",
       19.0,
       false,
       meshio::storedAsNineDigits},
  };
  return formats;
}

std::string lowerExtension(const std::string& path) {
  const size_t slash = path.find_last_of("/\\");
  const size_t dot = path.rfind('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot + 1);
  for (char& ch : ext) {
    if (ch >= 'A' && ch <= 'Z') ch = static_cast<char>(ch - 'A' + 'a');
  }
  return ext;
}

const MeshFormat* meshFormatForPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  if (ext.empty()) return nullptr;
  for (const MeshFormat& format : meshFormats()) {
    for (const std::string& candidate : format.extensions) {
      if (candidate == ext) return &format;
    }
  }
  return nullptr;
}

namespace {

// Joins items with ", ", the last one with `lastJoin`.
std::string joinList(const std::vector<std::string>& items, const char* lastJoin) {
  std::string text;
  for (size_t i = 0; i < items.size(); ++i) {
    if (i > 0) text += i + 1 == items.size() ? lastJoin : ", ";
    text += items[i];
  }
  return text;
}

}  // namespace

const MeshFormat* meshFormatFor(const std::string& path, MeshAccess access) {
  const MeshFormat* format = meshFormatForPath(path);
  return format && format->supports(access) ? format : nullptr;
}

std::vector<std::string> meshExtensions(MeshAccess access) {
  std::vector<std::string> extensions;
  for (const MeshFormat& format : meshFormats()) {
    if (!format.supports(access)) continue;
    extensions.insert(extensions.end(), format.extensions.begin(), format.extensions.end());
  }
  return extensions;
}

std::string meshExtensionList(MeshAccess access, const char* lastJoin) {
  std::vector<std::string> dotted;
  for (const std::string& ext : meshExtensions(access)) dotted.push_back("." + ext);
  return joinList(dotted, lastJoin);
}

std::string meshFormatUsage(MeshAccess access) {
  std::vector<std::string> items;
  for (const MeshFormat& format : meshFormats()) {
    if (!format.supports(access)) continue;
    std::string item;
    for (const std::string& ext : format.extensions) item += (item.empty() ? "." : "/.") + ext;
    const char* note = access == MeshAccess::Read ? format.readNote : format.writeNote;
    if (note[0] != '\0') item += std::string(" (") + note + ")";
    items.push_back(item);
  }
  return joinList(items, " or ");
}

}  // namespace strata
