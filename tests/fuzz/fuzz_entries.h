// The entry logic of the fuzz targets, shared with the FuzzCorpus gtest
// (tests/engine/io/fuzz_corpus_test.cpp) so that every normal test run (and the sanitizer build
// CI does) checks the same no-crash property on fixed inputs. Header-only: the fuzz targets
// are built outside the gtest binary.
//
// The property: any bytes either parse or throw strata::Error. Any other exception, a crash, a
// sanitizer report or a hang is a bug.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/io/mesh_io.h"
#include "engine/io/scene_file.h"
#include "engine/util/error.h"

namespace strata {
namespace fuzz {

// CRC-32 (IEEE 802.3, as zip uses).
inline uint32_t crc32(std::string_view bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  uint32_t crc = 0xFFFFFFFFu;
  for (char ch : bytes) crc = table[(crc ^ static_cast<uint8_t>(ch)) & 0xFF] ^ (crc >> 8);
  return crc ^ 0xFFFFFFFFu;
}

// A zip archive holding `entries` (name, content) uncompressed ("stored"), written here rather
// than with libzip so tests can build packages byte by byte, including broken ones.
inline std::string storedZip(const std::vector<std::pair<std::string, std::string>>& entries) {
  auto put16 = [](std::string& out, uint32_t v) {
    out += static_cast<char>(v & 0xFF);
    out += static_cast<char>((v >> 8) & 0xFF);
  };
  auto put32 = [&](std::string& out, uint32_t v) {
    put16(out, v & 0xFFFF);
    put16(out, v >> 16);
  };
  const uint32_t kDosDate = (0 << 9) | (1 << 5) | 1;  // 1980-01-01
  std::string zip;
  std::string central;
  for (const auto& [name, content] : entries) {
    const uint32_t offset = static_cast<uint32_t>(zip.size());
    const uint32_t crc = crc32(content);
    const uint32_t size = static_cast<uint32_t>(content.size());
    put32(zip, 0x04034b50);
    put16(zip, 20);  // version needed
    put16(zip, 0);   // flags
    put16(zip, 0);   // stored
    put16(zip, 0);   // time
    put16(zip, kDosDate);
    put32(zip, crc);
    put32(zip, size);
    put32(zip, size);
    put16(zip, static_cast<uint32_t>(name.size()));
    put16(zip, 0);  // extra
    zip += name;
    zip += content;

    put32(central, 0x02014b50);
    put16(central, 20);  // made by
    put16(central, 20);  // needed
    put16(central, 0);
    put16(central, 0);
    put16(central, 0);
    put16(central, kDosDate);
    put32(central, crc);
    put32(central, size);
    put32(central, size);
    put16(central, static_cast<uint32_t>(name.size()));
    put16(central, 0);  // extra
    put16(central, 0);  // comment
    put16(central, 0);  // disk
    put16(central, 0);  // internal attributes
    put32(central, 0);  // external attributes
    put32(central, offset);
    central += name;
  }
  const uint32_t centralOffset = static_cast<uint32_t>(zip.size());
  zip += central;
  put32(zip, 0x06054b50);
  put16(zip, 0);
  put16(zip, 0);
  put16(zip, static_cast<uint32_t>(entries.size()));
  put16(zip, static_cast<uint32_t>(entries.size()));
  put32(zip, static_cast<uint32_t>(central.size()));
  put32(zip, centralOffset);
  put16(zip, 0);
  return zip;
}

// A 3MF package around `modelXml`: content types, the model relationship, the model part.
inline std::string packageModel(const std::string& modelXml) {
  return storedZip(
      {{"[Content_Types].xml",
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Types "
        "xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"><Default "
        "Extension=\"model\" "
        "ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/></Types>\n"},
       {"_rels/.rels",
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships "
        "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"><Relationship "
        "Target=\"/3D/3dmodel.model\" Id=\"rel0\" "
        "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/></"
        "Relationships>\n"},
       {"3D/3dmodel.model", modelXml}});
}

// Mesh readers. Byte 0 picks the input: bits 0-2 (mod 6) the format, 0 .obj, 1 .stl, 2 .ply,
// 3 .off, 4 .3mf (the rest is the package), 5 .3mf (the rest is the model XML, packaged here
// so that mutations reach the XML parser past the zip's CRC); bit 7 sets allowOpen.
inline void runMeshReaders(const uint8_t* data, size_t size) {
  if (size == 0) return;
  static const char* const kNames[6] = {"fuzz.obj", "fuzz.stl", "fuzz.ply",
                                        "fuzz.off", "fuzz.3mf", "fuzz.3mf"};
  const int format = (data[0] & 7) % 6;
  MeshReadOptions options;
  options.allowOpen = (data[0] & 0x80) != 0;
  std::string bytes(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (format == 5) bytes = packageModel(bytes);
  try {
    MeshReadReport report;
    readMeshBytes(kNames[format], bytes, options, &report);
  } catch (const Error&) {
    // A readable error is the expected outcome for malformed input.
  }
}

// Scene files: the bytes as scene JSON. Mesh paths resolve against a folder that does not
// exist, so mesh nodes fail to load with an Error unless the path is absolute.
inline void runSceneFile(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    SceneLoadReport report;
    parseScene(text, "fuzz.strata.json", "/nonexistent-strata-fuzz-folder", &report);
  } catch (const Error&) {
  }
}

}  // namespace fuzz
}  // namespace strata
