#include "ui/gl_program.h"

#include <glm/gtc/type_ptr.hpp>

#include <cstring>

#include "engine/util/error.h"
#include "ui/embedded_shaders.h"

namespace strata::ui {
namespace {

std::string shaderLog(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.c_str();
}

// `defines` go right after the source's first line (its #version).
GLuint compile(GLenum type, const char* name, const char* defines) {
  const char* source = embeddedShader(name);
  if (!source)
    throw Error(std::string("shaders/") + name +
                ": no such shader was embedded into this build (ui/embed_shaders.cmake)");
  const char* firstLineEnd = std::strchr(source, '\n');
  const char* rest = firstLineEnd ? firstLineEnd + 1 : source + std::strlen(source);
  const std::string version(source, rest);
  // After the defines, the source's own line numbers again (the driver's log names them).
  const std::string inserted = defines && *defines ? std::string(defines) + "#line 2\n" : "";
  const char* parts[3] = {version.c_str(), inserted.c_str(), rest};
  GLuint shader = glCreateShader(type);
  glShaderSource(shader, 3, parts, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    std::string log = shaderLog(shader);
    glDeleteShader(shader);
    throw Error(std::string("shaders/") + name + ": does not compile:\n" + log);
  }
  return shader;
}

}  // namespace

GlProgram::GlProgram(const char* vertexName, const char* fragmentName, const char* defines) {
  GLuint vs = compile(GL_VERTEX_SHADER, vertexName, defines);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragmentName, defines);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program_, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(program_, length, nullptr, log.data());
    glDeleteProgram(program_);
    program_ = 0;
    throw Error(std::string("shaders/") + vertexName + " + " + fragmentName + ": do not link:\n" +
                log.c_str());
  }
}

GlProgram::~GlProgram() {
  if (program_) glDeleteProgram(program_);
}

GlProgram::GlProgram(GlProgram&& other) noexcept : program_(other.program_) {
  other.program_ = 0;
}

GlProgram& GlProgram::operator=(GlProgram&& other) noexcept {
  if (this != &other) {
    if (program_) glDeleteProgram(program_);
    program_ = other.program_;
    other.program_ = 0;
  }
  return *this;
}

void GlProgram::set(const char* name, const glm::mat4& value) const {
  glUniformMatrix4fv(glGetUniformLocation(program_, name), 1, GL_FALSE, glm::value_ptr(value));
}
void GlProgram::set(const char* name, const glm::vec2& value) const {
  glUniform2fv(glGetUniformLocation(program_, name), 1, glm::value_ptr(value));
}
void GlProgram::set(const char* name, const glm::vec3& value) const {
  glUniform3fv(glGetUniformLocation(program_, name), 1, glm::value_ptr(value));
}
void GlProgram::set(const char* name, const glm::vec4& value) const {
  glUniform4fv(glGetUniformLocation(program_, name), 1, glm::value_ptr(value));
}
void GlProgram::set(const char* name, float value) const {
  glUniform1f(glGetUniformLocation(program_, name), value);
}
void GlProgram::set(const char* name, int value) const {
  glUniform1i(glGetUniformLocation(program_, name), value);
}

std::string describeGlContext() {
  auto text = [](GLenum e) {
    const GLubyte* s = glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return "OpenGL " + text(GL_VERSION) + ", " + text(GL_RENDERER);
}

}  // namespace strata::ui
