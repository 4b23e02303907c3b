// The OpenGL the desktop renderer (src/gl/) is written against, on WebGL2: the web build puts this
// file where glad's generated header would be, so that src/gl/renderer.cpp, display.cpp,
// environment.cpp, dictionary_texture.cpp and shader.cpp compile for the page unchanged. WebGL2
// is OpenGL ES 3.0; the OpenGL 4.5 calls the renderer makes beyond it (direct state access, buffer
// textures, reading a texture back) are implemented in web/src/gl45_on_webgl2.cpp with ES 3.0
// calls.
#pragma once

#include <GLES3/gl3.h>
#include <GLES2/gl2ext.h>

#define GL_TEXTURE_BUFFER 0x8C2A
#define GL_DYNAMIC_STORAGE_BIT 0x0100  // glNamedBufferStorage's flag for glNamedBufferSubData
#define GL_MAX_TEXTURE_BUFFER_SIZE 0x8C2B
// Named so that the shadow maps' code compiles; WebGL2 has no cube-map arrays and the page draws
// no shadows (web/src/glint_web.cpp).
#define GL_TEXTURE_CUBE_MAP_ARRAY 0x9009

#ifdef __cplusplus
extern "C" {
#endif

void glCreateTextures(GLenum target, GLsizei n, GLuint* textures);
void glTextureStorage2D(GLuint texture, GLsizei levels, GLenum internalFormat, GLsizei width, GLsizei height);
void glTextureSubImage2D(GLuint texture, GLint level, GLint x, GLint y, GLsizei width, GLsizei height, GLenum format,
                         GLenum type, const void* pixels);
void glGenerateTextureMipmap(GLuint texture);
void glTextureParameteri(GLuint texture, GLenum name, GLint value);
void glBindTextureUnit(GLuint unit, GLuint texture);
void glTextureBuffer(GLuint texture, GLenum internalFormat, GLuint buffer);
void glGetTextureImage(GLuint texture, GLint level, GLenum format, GLenum type, GLsizei size, void* pixels);
void glCreateBuffers(GLsizei n, GLuint* buffers);
void glNamedBufferStorage(GLuint buffer, GLsizeiptr size, const void* data, GLbitfield flags);
void glNamedBufferSubData(GLuint buffer, GLintptr offset, GLsizeiptr size, const void* data);
void glCreateVertexArrays(GLsizei n, GLuint* arrays);
void glVertexArrayVertexBuffer(GLuint array, GLuint binding, GLuint buffer, GLintptr offset, GLsizei stride);
void glVertexArrayElementBuffer(GLuint array, GLuint buffer);
void glEnableVertexArrayAttrib(GLuint array, GLuint index);
void glVertexArrayAttribFormat(GLuint array, GLuint index, GLint size, GLenum type, GLboolean normalized,
                               GLuint relativeOffset);
void glVertexArrayAttribBinding(GLuint array, GLuint index, GLuint binding);
void glCreateFramebuffers(GLsizei n, GLuint* framebuffers);
void glNamedFramebufferTexture(GLuint framebuffer, GLenum attachment, GLuint texture, GLint level);
void glNamedFramebufferRenderbuffer(GLuint framebuffer, GLenum attachment, GLenum target, GLuint renderbuffer);
GLenum glCheckNamedFramebufferStatus(GLuint framebuffer, GLenum target);
void glClearNamedFramebufferfv(GLuint framebuffer, GLenum buffer, GLint drawBuffer, const GLfloat* value);
void glClearNamedFramebufferfi(GLuint framebuffer, GLenum buffer, GLint drawBuffer, GLfloat depth, GLint stencil);
void glCreateRenderbuffers(GLsizei n, GLuint* renderbuffers);
void glNamedRenderbufferStorage(GLuint renderbuffer, GLenum internalFormat, GLsizei width, GLsizei height);
void glNamedRenderbufferStorageMultisample(GLuint renderbuffer, GLsizei samples, GLenum internalFormat, GLsizei width,
                                           GLsizei height);
void glBlitNamedFramebuffer(GLuint readFramebuffer, GLuint drawFramebuffer, GLint srcX0, GLint srcY0, GLint srcX1,
                            GLint srcY1, GLint dstX0, GLint dstY0, GLint dstX1, GLint dstY1, GLbitfield mask,
                            GLenum filter);
void glNamedFramebufferTextureLayer(GLuint framebuffer, GLenum attachment, GLuint texture, GLint level, GLint layer);
void glNamedFramebufferDrawBuffer(GLuint framebuffer, GLenum buffer);
void glNamedFramebufferReadBuffer(GLuint framebuffer, GLenum buffer);
// 2D array textures only (the shadow maps' layers), the one kind of 3D storage WebGL2 can hold for us.
void glTextureStorage3D(GLuint texture, GLsizei levels, GLenum internalFormat, GLsizei width, GLsizei height,
                        GLsizei depth);
// ES 3.0's glGetIntegerv, which also answers GL_MAX_TEXTURE_BUFFER_SIZE (the texel buffers' limit).
void glintWebGetIntegerv(GLenum name, GLint* value);
// ES 3.0's glBindBufferRange, after uploading the buffer's contents if it has not been bound yet.
void glintWebBindBufferRange(GLenum target, GLuint index, GLuint buffer, GLintptr offset, GLsizeiptr size);

#ifdef __cplusplus
}
#endif

#ifndef GLINT_GL45_ON_WEBGL2_IMPLEMENTATION
#define glGetIntegerv glintWebGetIntegerv
#define glBindBufferRange glintWebBindBufferRange
#endif
