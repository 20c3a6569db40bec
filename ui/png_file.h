// Writing RGBA8 images as PNG (stb_image_write), atomically.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace strata::ui {

// `rgba`: width * height * 4 bytes, top row first. Writes opaque RGB (alpha dropped). Throws
// strata::Error naming the path when it cannot be written.
void writePng(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba);

}  // namespace strata::ui
