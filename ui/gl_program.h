// GLSL programs from the embedded shaders (shaders/, ui/embedded_shaders.h).
//
// Threads: the UI thread, with the editor's GL context current.
#pragma once

#include <epoxy/gl.h>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <string>

namespace strata::ui {

// A linked program; deletes it on destruction. Move-only.
class GlProgram {
 public:
  GlProgram() = default;
  // Compiles shaders/<vertexName> and shaders/<fragmentName>, with `defines` (lines such as
  // "#define X\n", or nullptr) right after each one's #version line. Throws strata::Error naming
  // the file and quoting the driver's log when a shader is missing or fails to compile or link.
  // A line `#include "FILE"` in a shader is replaced by the embedded shaders/FILE.
  GlProgram(const char* vertexName, const char* fragmentName, const char* defines = nullptr);
  // A compute program from shaders/<computeName> (GL 4.3), likewise.
  static GlProgram compute(const char* computeName, const char* defines = nullptr);
  ~GlProgram();
  GlProgram(GlProgram&& other) noexcept;
  GlProgram& operator=(GlProgram&& other) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;

  GLuint id() const { return program_; }
  void use() const { glUseProgram(program_); }
  // Uniform setters; a name the program does not use is ignored (as GL does for location -1).
  void set(const char* name, const glm::mat4& value) const;
  void set(const char* name, const glm::vec3& value) const;
  void set(const char* name, const glm::vec4& value) const;
  void set(const char* name, float value) const;
  void set(const char* name, int value) const;
  void set(const char* name, const glm::vec2& value) const;
  void set(const char* name, unsigned value) const;
  void set(const char* name, const glm::ivec2& value) const;

 private:
  GLuint program_ = 0;
};

// Describes the current context: "OpenGL 4.5 (Core Profile) Mesa 22.3.6, llvmpipe (LLVM 15.0.6,
// 256 bits)".
std::string describeGlContext();

}  // namespace strata::ui
