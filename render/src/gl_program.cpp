#include "gl_program.h"

#include <cstring>

#include "pelage/util/error.h"
#include "shader_sources.h"

namespace pelage::render::detail {

std::string_view shaderSource(std::string_view name) {
  for (std::size_t i = 0; i < kShaderCount; ++i)
    if (name == kShaders[i].name) return kShaders[i].text;
  PELAGE_CHECK(false, "no embedded shader '", name, "'");
  return {};
}

namespace {

std::string infoLog(GLuint object, bool isProgram) {
  GLint len = 0;
  if (isProgram)
    glGetProgramiv(object, GL_INFO_LOG_LENGTH, &len);
  else
    glGetShaderiv(object, GL_INFO_LOG_LENGTH, &len);
  std::string log(static_cast<std::size_t>(len > 0 ? len : 1), '\0');
  if (isProgram)
    glGetProgramInfoLog(object, len, nullptr, log.data());
  else
    glGetShaderInfoLog(object, len, nullptr, log.data());
  return log;
}

}  // namespace

GLuint buildProgram(const std::string& name, std::initializer_list<ShaderStage> stages,
                    const std::string& defines) {
  const GLuint program = glCreateProgram();
  std::vector<GLuint> shaders;
  for (const ShaderStage& stage : stages) {
    std::string text = "#version 450 core\n" + defines + "\n";
    std::string files;
    for (std::string_view f : stage.files) {
      // #line keeps driver messages pointing at the file's own line numbers.
      text += "#line 1\n";
      text += shaderSource(f);
      text += "\n";
      files += std::string(f) + " ";
    }
    if (!stage.source.empty()) {
      text += "#line 1\n";
      text += stage.source;
      text += "\n";
      files += "(own source) ";
    }
    const GLuint s = glCreateShader(stage.type);
    const char* src = text.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    PELAGE_CHECK(ok == GL_TRUE, "shader ", name, " (", files, ") does not compile:\n",
                 infoLog(s, false));
    glAttachShader(program, s);
    shaders.push_back(s);
  }
  glLinkProgram(program);
  for (GLuint s : shaders) {
    glDetachShader(program, s);
    glDeleteShader(s);
  }
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  PELAGE_CHECK(ok == GL_TRUE, "program ", name, " does not link:\n", infoLog(program, true));
  return program;
}

}  // namespace pelage::render::detail
