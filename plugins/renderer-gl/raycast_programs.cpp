#include "raycast_programs.hpp"
#include "shader_sources.hpp"

#include <initializer_list>
#include <stdexcept>
#include <string_view>
#include <vector>

namespace arbor::glraycast {

void check_gl(const char *what)
{
    const GLenum e = glGetError();
    if (e == GL_NO_ERROR)
        return;
    while (glGetError() != GL_NO_ERROR) {
    }
    if (e == GL_OUT_OF_MEMORY)
        throw std::runtime_error(std::string(what) + ": the graphics device is out of memory");
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", e);
    throw std::runtime_error(std::string(what) + ": OpenGL error " + code);
}

namespace {

std::string source(const char *name)
{
    const auto text = shader_source(name);
    if (!text)
        throw std::logic_error(std::string("shader ") + name + " is not embedded");
    return std::string(*text);
}

GLuint compile(GLenum type, const std::string &text, const char *name)
{
    const GLuint shader = glCreateShader(type);
    const char *p = text.c_str();
    glShaderSource(shader, 1, &p, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint length = 0;
        glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
        std::vector<char> log(static_cast<std::size_t>(std::max(length, 1)));
        glGetShaderInfoLog(shader, length, nullptr, log.data());
        glDeleteShader(shader);
        throw std::runtime_error(std::string(name) + " does not compile: " + log.data());
    }
    return shader;
}

// raycast.vert with `fragment`, under `header`; `outputs` name the
// fragment outputs at locations 0, 1, ...
Program link(const std::string &header, const char *fragment, std::initializer_list<const char *> outputs)
{
    const GLuint vs = compile(GL_VERTEX_SHADER, header + source("shaders/raycast.vert"), "raycast.vert");
    GLuint fs = 0;
    try {
        fs = compile(GL_FRAGMENT_SHADER, header + source((std::string("shaders/") + fragment).c_str()), fragment);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    Program program(glCreateProgram());
    glAttachShader(program.get(), vs);
    glAttachShader(program.get(), fs);
    GLuint location = 0;
    for (const char *output : outputs)
        glBindFragDataLocation(program.get(), location++, output);
    glLinkProgram(program.get());
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[4096] = {};
        glGetProgramInfoLog(program.get(), sizeof log, nullptr, log);
        throw std::runtime_error(std::string(fragment) + " does not link: " + log);
    }
    return program;
}

} // namespace

GLuint RaycastPrograms::get(unsigned variant)
{
    if (auto it = programs_.find(variant); it != programs_.end())
        return it->second.get();
    std::string header = "#version 330 core\n";
    const std::pair<unsigned, const char *> defines[] = {
        {kLabelled, "LABELLED"}, {kShaded, "SHADED"}, {kBoundary, "BOUNDARY"},
        {kJitter, "JITTER"},     {kVisibility, "VISIBILITY"}, {kOcclusion, "OCCLUSION"},
        {kResolve, "RESOLVE"},   {kSmooth, "SMOOTH"},         {kIsotropic, "ISOTROPIC"},
        {kRefined, "REFINE"}};
    for (const auto &[bit, name] : defines)
        if (variant & bit)
            header += std::string("#define ") + name + "\n";
    header += "#line 1\n";
    Program program = (variant & kVisibility) ? link(header, "raycast.frag", {"o_visibility"})
                                              : link(header, "raycast.frag", {"o_rgba", "o_depth"});
    const GLuint name = program.get();
    programs_.emplace(variant, std::move(program));
    return name;
}

GLuint RaycastPrograms::present()
{
    if (!present_)
        present_ = link("#version 330 core\n#line 1\n", "present.frag", {"o_rgba"});
    return present_.get();
}

} // namespace arbor::glraycast
