#include "ui/gl_program.h"

#include <glm/gtc/type_ptr.hpp>

#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

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

// `source` (the embedded shaders/<name>) with each line `#include "FILE"` replaced by the
// embedded shaders/FILE (itself expanded, at most kMaxDepth deep). Each included file gets a
// source-string number of its own (`files`: the numbers' names, the shader itself 0), and #line
// directives give every line its file's number and line, so that the driver's log ("N:LINE")
// names the file and line of an error. (A file included inside a block an #if leaves out keeps
// the lines after it off by its length: the shaders include outside such blocks.)
std::string expandIncludes(const char* name, const char* source, std::vector<std::string>* files,
                           int depth = 0) {
  constexpr int kMaxDepth = 4;
  const size_t self = files->size() - 1;  // this file's number
  std::string out;
  int line = 1;
  for (const char* at = source; *at; ++line) {
    const char* end = std::strchr(at, '\n');
    const std::string text(at, end ? end : at + std::strlen(at));
    at = end ? end + 1 : at + text.size();
    const char* directive = "#include \"";
    if (text.rfind(directive, 0) != 0) {
      out += text + "\n";
      continue;
    }
    const size_t close = text.find('"', std::strlen(directive));
    const std::string included =
        close == std::string::npos
            ? ""
            : text.substr(std::strlen(directive), close - std::strlen(directive));
    const char* body = included.empty() ? nullptr : embeddedShader(included.c_str());
    if (!body || depth >= kMaxDepth)
      throw Error(std::string("shaders/") + name + ":" + std::to_string(line) + ": " +
                  (body ? "includes nested too deep" : "includes a file that was not embedded") +
                  " (" + text + ")");
    files->push_back(included);
    out += "#line 1 " + std::to_string(files->size() - 1) + "\n";
    out += expandIncludes(included.c_str(), body, files, depth + 1);
    out += "#line " + std::to_string(line + 1) + " " + std::to_string(self) + "\n";
  }
  return out;
}

// `defines` go right after the source's first line (its #version); included files are expanded.
GLuint compile(GLenum type, const char* name, const char* defines) {
  const char* embedded = embeddedShader(name);
  if (!embedded)
    throw Error(std::string("shaders/") + name +
                ": no such shader was embedded into this build (ui/embed_shaders.cmake)");
  std::vector<std::string> files{name};
  const std::string expanded = expandIncludes(name, embedded, &files);
  const char* source = expanded.c_str();
  const char* firstLineEnd = std::strchr(source, '\n');
  const char* rest = firstLineEnd ? firstLineEnd + 1 : source + std::strlen(source);
  const std::string version(source, rest);
  // After the defines, the source's own line numbers again (the driver's log names them).
  const std::string inserted = defines && *defines ? std::string(defines) + "#line 2 0\n" : "";
  const char* parts[3] = {version.c_str(), inserted.c_str(), rest};
  GLuint shader = glCreateShader(type);
  glShaderSource(shader, 3, parts, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    std::string log = shaderLog(shader);
    glDeleteShader(shader);
    std::string numbers;  // which file each source-string number in the log is
    for (size_t i = 1; i < files.size(); ++i)
      numbers += (i == 1 ? " (source strings: 0 " + std::string(name) : std::string()) + ", " +
                 std::to_string(i) + " " + files[i] + (i + 1 == files.size() ? ")" : "");
    throw Error(std::string("shaders/") + name + ": does not compile" + numbers + ":\n" + log);
  }
  return shader;
}

// Links `shaders` (deleting them) into a program; throws naming `what` with the driver's log.
GLuint link(std::initializer_list<GLuint> shaders, const std::string& what) {
  GLuint program = glCreateProgram();
  for (GLuint shader : shaders) glAttachShader(program, shader);
  glLinkProgram(program);
  for (GLuint shader : shaders) glDeleteShader(shader);
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    GLint length = 0;
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(static_cast<size_t>(length > 0 ? length : 1), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    throw Error("shaders/" + what + ": do not link:\n" + log.c_str());
  }
  return program;
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
  program_ = link({vs, fs}, std::string(vertexName) + " + " + fragmentName);
}

GlProgram GlProgram::compute(const char* computeName, const char* defines) {
  GlProgram program;
  program.program_ = link({compile(GL_COMPUTE_SHADER, computeName, defines)}, computeName);
  return program;
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
void GlProgram::set(const char* name, unsigned value) const {
  glUniform1ui(glGetUniformLocation(program_, name), value);
}
void GlProgram::set(const char* name, const glm::ivec2& value) const {
  glUniform2iv(glGetUniformLocation(program_, name), 1, glm::value_ptr(value));
}

std::string describeGlContext() {
  auto text = [](GLenum e) {
    const GLubyte* s = glGetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  return "OpenGL " + text(GL_VERSION) + ", " + text(GL_RENDERER);
}

}  // namespace strata::ui
