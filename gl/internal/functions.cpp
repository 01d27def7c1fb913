// SPDX-License-Identifier: MIT
#include "gl/internal/functions.h"

#include <string>

namespace inkline::gl::internal {
namespace {

template <typename Fn>
void load(const Context& context, const char* name, Fn& r_fn) {
    r_fn = reinterpret_cast<Fn>(context.proc_address(name));
    if (!r_fn) {
        throw ContextError(std::string(context.backend_name()) + ": OpenGL entry point " + name +
                           " is missing");
    }
}

}  // namespace

Functions load_functions(const Context& context) {
    Functions fn;
#define INKLINE_GL_LOAD(name) load(context, "gl" #name, fn.name)
    INKLINE_GL_LOAD(GetError);
    INKLINE_GL_LOAD(GetIntegerv);
    INKLINE_GL_LOAD(Enable);
    INKLINE_GL_LOAD(Disable);
    INKLINE_GL_LOAD(Viewport);
    INKLINE_GL_LOAD(DepthFunc);
    INKLINE_GL_LOAD(DepthMask);
    INKLINE_GL_LOAD(ClearBufferfv);
    INKLINE_GL_LOAD(Finish);
    INKLINE_GL_LOAD(PixelStorei);
    INKLINE_GL_LOAD(ReadBuffer);
    INKLINE_GL_LOAD(DrawBuffers);
    INKLINE_GL_LOAD(ReadPixels);
    INKLINE_GL_LOAD(DrawElements);

    INKLINE_GL_LOAD(GenBuffers);
    INKLINE_GL_LOAD(DeleteBuffers);
    INKLINE_GL_LOAD(BindBuffer);
    INKLINE_GL_LOAD(BufferData);
    INKLINE_GL_LOAD(BufferSubData);
    INKLINE_GL_LOAD(GenVertexArrays);
    INKLINE_GL_LOAD(DeleteVertexArrays);
    INKLINE_GL_LOAD(BindVertexArray);
    INKLINE_GL_LOAD(EnableVertexAttribArray);
    INKLINE_GL_LOAD(VertexAttribPointer);

    INKLINE_GL_LOAD(CreateShader);
    INKLINE_GL_LOAD(ShaderSource);
    INKLINE_GL_LOAD(CompileShader);
    INKLINE_GL_LOAD(GetShaderiv);
    INKLINE_GL_LOAD(GetShaderInfoLog);
    INKLINE_GL_LOAD(DeleteShader);
    INKLINE_GL_LOAD(CreateProgram);
    INKLINE_GL_LOAD(AttachShader);
    INKLINE_GL_LOAD(LinkProgram);
    INKLINE_GL_LOAD(GetProgramiv);
    INKLINE_GL_LOAD(GetProgramInfoLog);
    INKLINE_GL_LOAD(DeleteProgram);
    INKLINE_GL_LOAD(UseProgram);
    INKLINE_GL_LOAD(GetUniformLocation);
    INKLINE_GL_LOAD(UniformMatrix4fv);

    INKLINE_GL_LOAD(GenFramebuffers);
    INKLINE_GL_LOAD(DeleteFramebuffers);
    INKLINE_GL_LOAD(BindFramebuffer);
    INKLINE_GL_LOAD(FramebufferRenderbuffer);
    INKLINE_GL_LOAD(CheckFramebufferStatus);
    INKLINE_GL_LOAD(GenRenderbuffers);
    INKLINE_GL_LOAD(DeleteRenderbuffers);
    INKLINE_GL_LOAD(BindRenderbuffer);
    INKLINE_GL_LOAD(RenderbufferStorage);

    INKLINE_GL_LOAD(DrawArrays);
    INKLINE_GL_LOAD(BlendFuncSeparate);
    INKLINE_GL_LOAD(StencilFunc);
    INKLINE_GL_LOAD(StencilOp);
    INKLINE_GL_LOAD(StencilMask);
    INKLINE_GL_LOAD(ClearBufferfi);
    INKLINE_GL_LOAD(GenTextures);
    INKLINE_GL_LOAD(DeleteTextures);
    INKLINE_GL_LOAD(BindTexture);
    INKLINE_GL_LOAD(ActiveTexture);
    INKLINE_GL_LOAD(TexImage2D);
    INKLINE_GL_LOAD(TexParameteri);
    INKLINE_GL_LOAD(GenerateMipmap);
    INKLINE_GL_LOAD(Uniform1i);
    INKLINE_GL_LOAD(Uniform1f);
    INKLINE_GL_LOAD(Uniform2f);
    INKLINE_GL_LOAD(Uniform3f);
    INKLINE_GL_LOAD(Uniform4f);
    INKLINE_GL_LOAD(Uniform1fv);
    INKLINE_GL_LOAD(RenderbufferStorageMultisample);
    INKLINE_GL_LOAD(BlitFramebuffer);
#undef INKLINE_GL_LOAD
    return fn;
}

namespace {

GLuint compile(const Functions& fn, GLenum type, const char* source, const char* what) {
    const GLuint shader = fn.CreateShader(type);
    fn.ShaderSource(shader, 1, &source, nullptr);
    fn.CompileShader(shader);
    GLint ok = GL_FALSE;
    fn.GetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (ok != GL_TRUE) {
        char log[1024] = {};
        fn.GetShaderInfoLog(shader, sizeof log, nullptr, log);
        fn.DeleteShader(shader);
        throw ContextError(std::string(what) + " shader does not compile: " + log);
    }
    return shader;
}

}  // namespace

GLuint link_program(const Functions& fn, const char* vertex, const char* fragment, const char* what) {
    const GLuint vs = compile(fn, GL_VERTEX_SHADER, vertex, what);
    const GLuint fs = compile(fn, GL_FRAGMENT_SHADER, fragment, what);
    const GLuint program = fn.CreateProgram();
    fn.AttachShader(program, vs);
    fn.AttachShader(program, fs);
    fn.LinkProgram(program);
    fn.DeleteShader(vs);
    fn.DeleteShader(fs);
    GLint ok = GL_FALSE;
    fn.GetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok != GL_TRUE) {
        char log[1024] = {};
        fn.GetProgramInfoLog(program, sizeof log, nullptr, log);
        fn.DeleteProgram(program);
        throw ContextError(std::string(what) + " shaders do not link: " + log);
    }
    return program;
}

}  // namespace inkline::gl::internal
