// The GLSL sources of shaders/, compiled into the library by ui/embed_shaders.cmake.
#pragma once

namespace strata::ui {

// The source of shaders/<name> (e.g. "surfel.vert"), or nullptr when there is no such shader.
const char* embeddedShader(const char* name);

}  // namespace strata::ui
