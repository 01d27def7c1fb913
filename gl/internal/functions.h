// SPDX-License-Identifier: MIT
// The OpenGL 3.3 core entry points gl/ calls, loaded through the context's GetProcAddress
// (EGL or OSMesa). No loader library is needed, and calls never go through a link-time libGL
// symbol that might belong to the other back-end's dispatch.
#pragma once

#include "gl/context.h"

#include <GL/glcorearb.h>

namespace inkline::gl::internal {

// Members are named after the GL function without its "gl" prefix: fn.DrawElements(...).
struct Functions {
    PFNGLGETERRORPROC GetError = nullptr;
    PFNGLGETINTEGERVPROC GetIntegerv = nullptr;
    PFNGLENABLEPROC Enable = nullptr;
    PFNGLDISABLEPROC Disable = nullptr;
    PFNGLVIEWPORTPROC Viewport = nullptr;
    PFNGLDEPTHFUNCPROC DepthFunc = nullptr;
    PFNGLDEPTHMASKPROC DepthMask = nullptr;
    PFNGLCLEARBUFFERFVPROC ClearBufferfv = nullptr;
    PFNGLFINISHPROC Finish = nullptr;
    PFNGLPIXELSTOREIPROC PixelStorei = nullptr;
    PFNGLREADBUFFERPROC ReadBuffer = nullptr;
    PFNGLDRAWBUFFERSPROC DrawBuffers = nullptr;
    PFNGLREADPIXELSPROC ReadPixels = nullptr;
    PFNGLDRAWELEMENTSPROC DrawElements = nullptr;

    PFNGLGENBUFFERSPROC GenBuffers = nullptr;
    PFNGLDELETEBUFFERSPROC DeleteBuffers = nullptr;
    PFNGLBINDBUFFERPROC BindBuffer = nullptr;
    PFNGLBUFFERDATAPROC BufferData = nullptr;
    PFNGLBUFFERSUBDATAPROC BufferSubData = nullptr;
    PFNGLGENVERTEXARRAYSPROC GenVertexArrays = nullptr;
    PFNGLDELETEVERTEXARRAYSPROC DeleteVertexArrays = nullptr;
    PFNGLBINDVERTEXARRAYPROC BindVertexArray = nullptr;
    PFNGLENABLEVERTEXATTRIBARRAYPROC EnableVertexAttribArray = nullptr;
    PFNGLVERTEXATTRIBPOINTERPROC VertexAttribPointer = nullptr;

    PFNGLCREATESHADERPROC CreateShader = nullptr;
    PFNGLSHADERSOURCEPROC ShaderSource = nullptr;
    PFNGLCOMPILESHADERPROC CompileShader = nullptr;
    PFNGLGETSHADERIVPROC GetShaderiv = nullptr;
    PFNGLGETSHADERINFOLOGPROC GetShaderInfoLog = nullptr;
    PFNGLDELETESHADERPROC DeleteShader = nullptr;
    PFNGLCREATEPROGRAMPROC CreateProgram = nullptr;
    PFNGLATTACHSHADERPROC AttachShader = nullptr;
    PFNGLLINKPROGRAMPROC LinkProgram = nullptr;
    PFNGLGETPROGRAMIVPROC GetProgramiv = nullptr;
    PFNGLGETPROGRAMINFOLOGPROC GetProgramInfoLog = nullptr;
    PFNGLDELETEPROGRAMPROC DeleteProgram = nullptr;
    PFNGLUSEPROGRAMPROC UseProgram = nullptr;
    PFNGLGETUNIFORMLOCATIONPROC GetUniformLocation = nullptr;
    PFNGLUNIFORMMATRIX4FVPROC UniformMatrix4fv = nullptr;

    PFNGLGENFRAMEBUFFERSPROC GenFramebuffers = nullptr;
    PFNGLDELETEFRAMEBUFFERSPROC DeleteFramebuffers = nullptr;
    PFNGLBINDFRAMEBUFFERPROC BindFramebuffer = nullptr;
    PFNGLFRAMEBUFFERRENDERBUFFERPROC FramebufferRenderbuffer = nullptr;
    PFNGLCHECKFRAMEBUFFERSTATUSPROC CheckFramebufferStatus = nullptr;
    PFNGLGENRENDERBUFFERSPROC GenRenderbuffers = nullptr;
    PFNGLDELETERENDERBUFFERSPROC DeleteRenderbuffers = nullptr;
    PFNGLBINDRENDERBUFFERPROC BindRenderbuffer = nullptr;
    PFNGLRENDERBUFFERSTORAGEPROC RenderbufferStorage = nullptr;

    // Preview pass (gl/preview.cpp): textures, blending, stencil, multisampling.
    PFNGLDRAWARRAYSPROC DrawArrays = nullptr;
    PFNGLBLENDFUNCSEPARATEPROC BlendFuncSeparate = nullptr;
    PFNGLSTENCILFUNCPROC StencilFunc = nullptr;
    PFNGLSTENCILOPPROC StencilOp = nullptr;
    PFNGLSTENCILMASKPROC StencilMask = nullptr;
    PFNGLCLEARBUFFERFIPROC ClearBufferfi = nullptr;
    PFNGLGENTEXTURESPROC GenTextures = nullptr;
    PFNGLDELETETEXTURESPROC DeleteTextures = nullptr;
    PFNGLBINDTEXTUREPROC BindTexture = nullptr;
    PFNGLACTIVETEXTUREPROC ActiveTexture = nullptr;
    PFNGLTEXIMAGE2DPROC TexImage2D = nullptr;
    PFNGLTEXPARAMETERIPROC TexParameteri = nullptr;
    PFNGLGENERATEMIPMAPPROC GenerateMipmap = nullptr;
    PFNGLUNIFORM1IPROC Uniform1i = nullptr;
    PFNGLUNIFORM1FPROC Uniform1f = nullptr;
    PFNGLUNIFORM1FVPROC Uniform1fv = nullptr;
    PFNGLUNIFORM2FPROC Uniform2f = nullptr;
    PFNGLUNIFORM3FPROC Uniform3f = nullptr;
    PFNGLUNIFORM4FPROC Uniform4f = nullptr;
    PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC RenderbufferStorageMultisample = nullptr;
    PFNGLBLITFRAMEBUFFERPROC BlitFramebuffer = nullptr;
};

// Loads every entry point of `context`, which must be current; throws ContextError naming the
// first one the platform does not provide.
Functions load_functions(const Context& context);

// Compiles and links a vertex and a fragment shader into a program. Throws ContextError with the
// driver's log, naming the pass (`what`, e.g. "preview") whose shaders failed.
GLuint link_program(const Functions& fn, const char* vertex, const char* fragment, const char* what);

}  // namespace inkline::gl::internal
