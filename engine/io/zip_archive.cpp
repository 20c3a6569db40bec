// libzip behind zip_archive.h: archives built in and read from memory buffers.
#include "engine/io/zip_archive.h"

#include <zip.h>

#include <cstdio>
#include <ctime>
#include <memory>

#include "engine/util/error.h"

namespace strata {
namespace zipio {
namespace {

// 1 January 2000, 00:00 UTC: a fixed, DOS-representable modification time for every member.
constexpr time_t kFixedMtime = 946684800;

std::string errorText(zip_error_t* error) {
  const char* text = zip_error_strerror(error);
  return text ? text : "unknown libzip error";
}

struct ErrorHolder {
  zip_error_t error;
  ErrorHolder() { zip_error_init(&error); }
  ~ErrorHolder() { zip_error_fini(&error); }
  ErrorHolder(const ErrorHolder&) = delete;
  ErrorHolder& operator=(const ErrorHolder&) = delete;
};

}  // namespace

std::string makeZip(const std::vector<ZipEntry>& entries, const std::string& what) {
  ErrorHolder err;
  zip_source_t* buffer = zip_source_buffer_create(nullptr, 0, 0, &err.error);
  if (!buffer) throw Error(what + ": cannot create a zip buffer: " + errorText(&err.error));
  // The buffer source must survive zip_close, which writes the archive into it.
  zip_source_keep(buffer);
  struct SourceFree {
    void operator()(zip_source_t* s) const { zip_source_free(s); }
  };
  std::unique_ptr<zip_source_t, SourceFree> bufferOwner(buffer);

  zip_t* archive = zip_open_from_source(buffer, ZIP_TRUNCATE, &err.error);
  if (!archive) throw Error(what + ": cannot start a zip archive: " + errorText(&err.error));
  auto fail = [&](const std::string& step) {
    const std::string reason = errorText(zip_get_error(archive));
    zip_discard(archive);
    throw Error(what + ": " + step + ": " + reason);
  };
  for (const ZipEntry& entry : entries) {
    // The content outlives zip_close below, so libzip may reference it without copying.
    zip_source_t* source =
        zip_source_buffer(archive, entry.content.data(), entry.content.size(), 0);
    if (!source) fail("cannot add " + entry.name);
    const zip_int64_t index =
        zip_file_add(archive, entry.name.c_str(), source, ZIP_FL_ENC_UTF_8 | ZIP_FL_OVERWRITE);
    if (index < 0) {
      zip_source_free(source);
      fail("cannot add " + entry.name);
    }
    // Level 1: about eight times faster than zlib's default on model XML, files ~15% larger.
    if (zip_set_file_compression(archive, static_cast<zip_uint64_t>(index), ZIP_CM_DEFLATE, 1) !=
            0 ||
        zip_file_set_mtime(archive, static_cast<zip_uint64_t>(index), kFixedMtime, 0) != 0) {
      fail("cannot set up " + entry.name);
    }
  }
  if (zip_close(archive) != 0) fail("cannot compress the archive");

  if (zip_source_open(buffer) != 0) {
    throw Error(what + ": cannot read the archive back: " + errorText(zip_source_error(buffer)));
  }
  std::string bytes;
  char chunk[1 << 16];
  for (;;) {
    const zip_int64_t n = zip_source_read(buffer, chunk, sizeof(chunk));
    if (n < 0) {
      const std::string reason = errorText(zip_source_error(buffer));
      zip_source_close(buffer);
      throw Error(what + ": cannot read the archive back: " + reason);
    }
    if (n == 0) break;
    bytes.append(chunk, static_cast<size_t>(n));
  }
  zip_source_close(buffer);
  return bytes;
}

ZipReader::ZipReader(const std::string& name, const std::string& bytes) : name_(name) {
  // An empty buffer would open as an empty archive; anything without the local-file or
  // end-of-central-directory signature up front is not a zip at all.
  if (bytes.size() < 22 || bytes[0] != 'P' || bytes[1] != 'K') {
    throw Error(name + ": not a zip archive (no 'PK' signature at byte 0; a 3MF file is a zip " +
                "package)");
  }
  ErrorHolder err;
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &err.error);
  if (!source) throw Error(name + ": cannot open the zip archive: " + errorText(&err.error));
  zip_ = zip_open_from_source(source, ZIP_RDONLY, &err.error);
  if (!zip_) {
    zip_source_free(source);
    throw Error(name + ": not a zip archive (" + errorText(&err.error) + ")");
  }
}

ZipReader::~ZipReader() {
  if (zip_) zip_discard(zip_);
}

bool ZipReader::has(const std::string& member) const {
  return zip_name_locate(zip_, member.c_str(), ZIP_FL_NOCASE) >= 0;
}

std::string ZipReader::read(const std::string& member, size_t maxBytes,
                            const std::string& howToRaise) const {
  const std::string where = name_ + ": " + member;
  const zip_int64_t index = zip_name_locate(zip_, member.c_str(), ZIP_FL_NOCASE);
  if (index < 0) throw Error(where + ": no such part in the zip archive");
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat_index(zip_, static_cast<zip_uint64_t>(index), 0, &st) != 0) {
    throw Error(where + ": cannot read the zip entry: " + errorText(zip_get_error(zip_)));
  }
  if ((st.valid & ZIP_STAT_SIZE) && st.size > maxBytes) {
    throw Error(where + ": part is too large (" + std::to_string(st.size) +
                " bytes uncompressed; at most " + std::to_string(maxBytes) + " are read" +
                (howToRaise.empty() ? "" : "; " + howToRaise) + ")");
  }
  zip_file_t* file = zip_fopen_index(zip_, static_cast<zip_uint64_t>(index), 0);
  if (!file) throw Error(where + ": cannot open the zip entry: " + errorText(zip_get_error(zip_)));
  std::string content;
  char chunk[1 << 16];
  for (;;) {
    const zip_int64_t n = zip_fread(file, chunk, sizeof(chunk));
    if (n < 0) {
      const std::string reason = errorText(zip_file_get_error(file));
      zip_fclose(file);
      throw Error(where + ": corrupt zip entry: " + reason);
    }
    if (n == 0) break;
    if (content.size() + static_cast<size_t>(n) > maxBytes) {
      zip_fclose(file);
      throw Error(where + ": part is too large (more than " + std::to_string(maxBytes) +
                  " bytes when uncompressed" + (howToRaise.empty() ? "" : "; " + howToRaise) + ")");
    }
    content.append(chunk, static_cast<size_t>(n));
  }
  zip_fclose(file);
  return content;
}

}  // namespace zipio
}  // namespace strata
