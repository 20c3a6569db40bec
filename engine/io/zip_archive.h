// Private to engine/io: zip archives held in memory, through libzip, for 3MF packages.
// Nothing here touches the file system; callers read and write the bytes themselves (the
// writers with writeFileAtomically). libzip types stay in zip_archive.cpp.
// Synchronous; a ZipReader is used by one thread at a time.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

struct zip;  // libzip's zip_t

namespace strata {
namespace zipio {

// One member of an archive to write: its name inside the archive ("3D/3dmodel.model") and its
// content.
struct ZipEntry {
  std::string name;
  std::string content;
};

// The bytes of a zip archive holding `entries` in order, each deflated (level 1: fast), with a
// fixed modification time (so the same entries always give the same bytes). Throws strata::Error
// "<what>: <libzip's reason>" when libzip fails.
std::string makeZip(const std::vector<ZipEntry>& entries, const std::string& what);

// Reads members of an archive held in memory. `bytes` must outlive the reader.
class ZipReader {
 public:
  // Throws strata::Error "<name>: not a zip archive (...)" when the bytes are not one.
  ZipReader(const std::string& name, const std::string& bytes);
  ~ZipReader();
  ZipReader(const ZipReader&) = delete;
  ZipReader& operator=(const ZipReader&) = delete;

  // Whether a member of that name exists (ASCII case-insensitive, as OPC part names are).
  bool has(const std::string& member) const;
  // The member's uncompressed content. Throws strata::Error "<name>: <member>: ..." when it
  // is missing, corrupt (bad CRC, bad compressed data), encrypted, or larger than maxBytes.
  // `howToRaise`, when given, ends the message about a part over maxBytes.
  std::string read(const std::string& member, size_t maxBytes,
                   const std::string& howToRaise = "") const;

 private:
  std::string name_;
  struct zip* zip_ = nullptr;
};

}  // namespace zipio
}  // namespace strata
