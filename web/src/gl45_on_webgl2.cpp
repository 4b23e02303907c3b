// The OpenGL 4.5 calls of the desktop renderer (web/include/glad/gl.h) in OpenGL ES 3.0 (WebGL2),
// by binding each object to edit it and binding back what was bound, so that, as with direct state
// access, no binding changes. Three things WebGL2 lacks are emulated:
//   - buffer textures: the buffer's texels, row after row, in a 2D texture kTexelBufferWidth wide
//     (the kernel's prelude reads them so under GL_ES);
//   - three-component float textures (RGB32F) cannot have mipmaps generated (they are not
//     colour-renderable): they are stored as RGBA32F, alpha 1;
//   - WebGL binds a buffer to index data or to other data for life, and a buffer's first use says
//     which: its contents are kept here until then (a uniform buffer's first use is
//     glBindBufferRange, which this file's version of it handles).
#define GLINT_GL45_ON_WEBGL2_IMPLEMENTATION
#include <glad/gl.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <utility>
#include <vector>

namespace {

// The width of the 2D texture that holds a buffer texture's texels (prelude.h, GL_ES branch).
constexpr int kTexelBufferWidth = 2048;

std::map<GLuint, std::pair<GLsizei, GLsizei>> textureSizes;  // level 0's width and height
std::map<GLuint, std::vector<std::uint8_t>> pendingBuffers;  // contents not yet uploaded

struct VertexBinding {
  GLuint buffer = 0;
  GLintptr offset = 0;
  GLsizei stride = 0;
};
struct AttributeFormat {
  GLint size = 4;
  GLenum type = GL_FLOAT;
  GLboolean normalized = GL_FALSE;
  GLuint relativeOffset = 0;
};
struct VertexArrayState {
  std::map<GLuint, VertexBinding> bindings;
  std::map<GLuint, AttributeFormat> formats;
};
std::map<GLuint, VertexArrayState> vertexArrays;

// Binds `buffer` to `target`, uploading its contents on its first use.
void bindBuffer(GLenum target, GLuint buffer) {
  glBindBuffer(target, buffer);
  auto pending = pendingBuffers.find(buffer);
  if (pending != pendingBuffers.end()) {
    glBufferData(target, static_cast<GLsizeiptr>(pending->second.size()), pending->second.data(), GL_STATIC_DRAW);
    pendingBuffers.erase(pending);
  }
}

// Runs `edit` with `texture` bound to the active unit, then binds back the texture that was there:
// direct state access leaves every binding as it is, and the renderer relies on that (it creates a
// texture between binding a material's textures and drawing).
template <typename Edit>
void withTexture2D(GLuint texture, Edit edit) {
  GLint previous = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &previous);
  glBindTexture(GL_TEXTURE_2D, texture);
  edit();
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(previous));
}

// The same for the vertex array and the array buffer.
template <typename Edit>
void withVertexArray(GLuint array, Edit edit) {
  GLint previousArray = 0;
  GLint previousBuffer = 0;
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &previousArray);
  glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &previousBuffer);
  glBindVertexArray(array);
  edit();
  glBindVertexArray(static_cast<GLuint>(previousArray));
  glBindBuffer(GL_ARRAY_BUFFER, static_cast<GLuint>(previousBuffer));
}

// Runs `edit` with `framebuffer` bound, then binds back the one that was.
template <typename Edit>
auto withFramebuffer(GLuint framebuffer, Edit edit) {
  GLint previous = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  auto result = edit();
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous));
  return result;
}

// The external format and type of a texel buffer's internal format.
void texelBufferLayout(GLenum internalFormat, GLenum& format, GLenum& type, int& bytesPerTexel) {
  switch (internalFormat) {
    case GL_RG16F: format = GL_RG; type = GL_HALF_FLOAT; bytesPerTexel = 4; return;
    case GL_RGBA16F: format = GL_RGBA; type = GL_HALF_FLOAT; bytesPerTexel = 8; return;
    case GL_RG32F: format = GL_RG; type = GL_FLOAT; bytesPerTexel = 8; return;
    default: format = GL_RGBA; type = GL_FLOAT; bytesPerTexel = 16; return;  // GL_RGBA32F
  }
}

}  // namespace

extern "C" {

void glCreateTextures(GLenum, GLsizei n, GLuint* textures) {
  glGenTextures(n, textures);
}

void glTextureStorage2D(GLuint texture, GLsizei levels, GLenum internalFormat, GLsizei width, GLsizei height) {
  textureSizes[texture] = {width, height};
  if (internalFormat == GL_RGB32F) internalFormat = GL_RGBA32F;
  withTexture2D(texture, [&] { glTexStorage2D(GL_TEXTURE_2D, levels, internalFormat, width, height); });
}

void glTextureSubImage2D(GLuint texture, GLint level, GLint x, GLint y, GLsizei width, GLsizei height, GLenum format,
                         GLenum type, const void* pixels) {
  // RGB floats go into RGBA32F textures only (RGB32F is stored so): ES 3.0 takes RGBA floats there.
  std::vector<float> rgba;
  if (format == GL_RGB && type == GL_FLOAT) {
    const std::size_t count = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    rgba.assign(count * 4, 1.0f);
    const float* rgb = static_cast<const float*>(pixels);
    for (std::size_t i = 0; i < count; ++i) std::copy_n(rgb + 3 * i, 3, rgba.data() + 4 * i);
    format = GL_RGBA;
    pixels = rgba.data();
  }
  withTexture2D(texture, [&] { glTexSubImage2D(GL_TEXTURE_2D, level, x, y, width, height, format, type, pixels); });
}

void glGenerateTextureMipmap(GLuint texture) {
  withTexture2D(texture, [] { glGenerateMipmap(GL_TEXTURE_2D); });
}

void glTextureParameteri(GLuint texture, GLenum name, GLint value) {
  withTexture2D(texture, [&] { glTexParameteri(GL_TEXTURE_2D, name, value); });
}

void glBindTextureUnit(GLuint unit, GLuint texture) {
  glActiveTexture(GL_TEXTURE0 + unit);
  glBindTexture(GL_TEXTURE_2D, texture);  // texel buffers are 2D textures here too
}

void glTextureBuffer(GLuint texture, GLenum internalFormat, GLuint buffer) {
  GLenum format = GL_RGBA;
  GLenum type = GL_FLOAT;
  int bytesPerTexel = 16;
  texelBufferLayout(internalFormat, format, type, bytesPerTexel);
  std::vector<std::uint8_t> bytes = std::move(pendingBuffers[buffer]);
  pendingBuffers.erase(buffer);
  const std::size_t texels = bytes.size() / static_cast<std::size_t>(bytesPerTexel);
  const std::size_t rows = std::max<std::size_t>(1, (texels + kTexelBufferWidth - 1) / kTexelBufferWidth);
  bytes.resize(rows * kTexelBufferWidth * static_cast<std::size_t>(bytesPerTexel), 0);
  withTexture2D(texture, [&] {
    glTexStorage2D(GL_TEXTURE_2D, 1, internalFormat, kTexelBufferWidth, static_cast<GLsizei>(rows));
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kTexelBufferWidth, static_cast<GLsizei>(rows), format, type, bytes.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  });
}

void glGetTextureImage(GLuint texture, GLint level, GLenum format, GLenum type, GLsizei, void* pixels) {
  GLuint framebuffer = 0;
  glGenFramebuffers(1, &framebuffer);
  withFramebuffer(framebuffer, [&] {
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, level);
    const auto [width, height] = textureSizes.at(texture);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, std::max(1, width >> level), std::max(1, height >> level), format, type, pixels);
    return 0;
  });
  glDeleteFramebuffers(1, &framebuffer);
}

void glCreateBuffers(GLsizei n, GLuint* buffers) { glGenBuffers(n, buffers); }

void glNamedBufferStorage(GLuint buffer, GLsizeiptr size, const void* data, GLbitfield) {
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  pendingBuffers[buffer].assign(bytes, bytes + size);
}

// Into the contents kept for the buffer's first use, or, once it has been used, through the uniform
// buffer target (the only one the renderer updates a buffer for), bound back as it was.
void glNamedBufferSubData(GLuint buffer, GLintptr offset, GLsizeiptr size, const void* data) {
  auto pending = pendingBuffers.find(buffer);
  if (pending != pendingBuffers.end()) {
    std::memcpy(pending->second.data() + offset, data, static_cast<std::size_t>(size));
    return;
  }
  GLint previous = 0;
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &previous);
  glBindBuffer(GL_UNIFORM_BUFFER, buffer);
  glBufferSubData(GL_UNIFORM_BUFFER, offset, size, data);
  glBindBuffer(GL_UNIFORM_BUFFER, static_cast<GLuint>(previous));
}

void glCreateVertexArrays(GLsizei n, GLuint* arrays) {
  glGenVertexArrays(n, arrays);
  for (GLsizei i = 0; i < n; ++i) vertexArrays[arrays[i]] = {};
}

void glVertexArrayVertexBuffer(GLuint array, GLuint binding, GLuint buffer, GLintptr offset, GLsizei stride) {
  vertexArrays[array].bindings[binding] = {buffer, offset, stride};
}

void glVertexArrayElementBuffer(GLuint array, GLuint buffer) {
  withVertexArray(array, [&] { bindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffer); });
}

void glEnableVertexArrayAttrib(GLuint array, GLuint index) {
  withVertexArray(array, [&] { glEnableVertexAttribArray(index); });
}

void glVertexArrayAttribFormat(GLuint array, GLuint index, GLint size, GLenum type, GLboolean normalized,
                               GLuint relativeOffset) {
  vertexArrays[array].formats[index] = {size, type, normalized, relativeOffset};
}

// The attribute's pointer, from its format and its binding's buffer (the renderer sets both first).
void glVertexArrayAttribBinding(GLuint array, GLuint index, GLuint binding) {
  const VertexArrayState& state = vertexArrays[array];
  const VertexBinding& b = state.bindings.at(binding);
  const AttributeFormat& f = state.formats.at(index);
  withVertexArray(array, [&] {
    bindBuffer(GL_ARRAY_BUFFER, b.buffer);
    glVertexAttribPointer(index, f.size, f.type, f.normalized, b.stride,
                          reinterpret_cast<const void*>(static_cast<std::uintptr_t>(b.offset + f.relativeOffset)));
  });
}

void glCreateFramebuffers(GLsizei n, GLuint* framebuffers) { glGenFramebuffers(n, framebuffers); }

void glNamedFramebufferTexture(GLuint framebuffer, GLenum attachment, GLuint texture, GLint level) {
  withFramebuffer(framebuffer, [&] {
    glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, texture, level);
    return 0;
  });
}

void glNamedFramebufferRenderbuffer(GLuint framebuffer, GLenum attachment, GLenum target, GLuint renderbuffer) {
  withFramebuffer(framebuffer, [&] {
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, attachment, target, renderbuffer);
    return 0;
  });
}

GLenum glCheckNamedFramebufferStatus(GLuint framebuffer, GLenum target) {
  return withFramebuffer(framebuffer, [&] { return glCheckFramebufferStatus(target); });
}

void glClearNamedFramebufferfv(GLuint framebuffer, GLenum buffer, GLint drawBuffer, const GLfloat* value) {
  withFramebuffer(framebuffer, [&] {
    glClearBufferfv(buffer, drawBuffer, value);
    return 0;
  });
}

void glClearNamedFramebufferfi(GLuint framebuffer, GLenum buffer, GLint drawBuffer, GLfloat depth, GLint stencil) {
  withFramebuffer(framebuffer, [&] {
    glClearBufferfi(buffer, drawBuffer, depth, stencil);
    return 0;
  });
}

void glCreateRenderbuffers(GLsizei n, GLuint* renderbuffers) { glGenRenderbuffers(n, renderbuffers); }

void glNamedRenderbufferStorage(GLuint renderbuffer, GLenum internalFormat, GLsizei width, GLsizei height) {
  GLint previous = 0;
  glGetIntegerv(GL_RENDERBUFFER_BINDING, &previous);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
  glRenderbufferStorage(GL_RENDERBUFFER, internalFormat, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, static_cast<GLuint>(previous));
}

void glNamedRenderbufferStorageMultisample(GLuint renderbuffer, GLsizei samples, GLenum internalFormat, GLsizei width,
                                           GLsizei height) {
  GLint previous = 0;
  glGetIntegerv(GL_RENDERBUFFER_BINDING, &previous);
  glBindRenderbuffer(GL_RENDERBUFFER, renderbuffer);
  glRenderbufferStorageMultisample(GL_RENDERBUFFER, samples, internalFormat, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, static_cast<GLuint>(previous));
}

void glBlitNamedFramebuffer(GLuint readFramebuffer, GLuint drawFramebuffer, GLint srcX0, GLint srcY0, GLint srcX1,
                            GLint srcY1, GLint dstX0, GLint dstY0, GLint dstX1, GLint dstY1, GLbitfield mask,
                            GLenum filter) {
  GLint previousRead = 0;
  GLint previousDraw = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previousRead);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &previousDraw);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, readFramebuffer);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, drawFramebuffer);
  glBlitFramebuffer(srcX0, srcY0, srcX1, srcY1, dstX0, dstY0, dstX1, dstY1, mask, filter);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previousRead));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(previousDraw));
}

void glNamedFramebufferTextureLayer(GLuint framebuffer, GLenum attachment, GLuint texture, GLint level, GLint layer) {
  withFramebuffer(framebuffer, [&] {
    glFramebufferTextureLayer(GL_FRAMEBUFFER, attachment, texture, level, layer);
    return 0;
  });
}

void glNamedFramebufferDrawBuffer(GLuint framebuffer, GLenum buffer) {
  withFramebuffer(framebuffer, [&] {
    glDrawBuffers(1, &buffer);
    return 0;
  });
}

void glNamedFramebufferReadBuffer(GLuint framebuffer, GLenum buffer) {
  GLint previous = 0;
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  glReadBuffer(buffer);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous));
}

void glTextureStorage3D(GLuint texture, GLsizei levels, GLenum internalFormat, GLsizei width, GLsizei height,
                        GLsizei depth) {
  GLint previous = 0;
  glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &previous);
  glBindTexture(GL_TEXTURE_2D_ARRAY, texture);
  glTexStorage3D(GL_TEXTURE_2D_ARRAY, levels, internalFormat, width, height, depth);
  glBindTexture(GL_TEXTURE_2D_ARRAY, static_cast<GLuint>(previous));
}

void glintWebBindBufferRange(GLenum target, GLuint index, GLuint buffer, GLintptr offset, GLsizeiptr size) {
  bindBuffer(target, buffer);
  glBindBufferRange(target, index, buffer, offset, size);
}

void glintWebGetIntegerv(GLenum name, GLint* value) {
  if (name == GL_MAX_TEXTURE_BUFFER_SIZE) {
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    *value = kTexelBufferWidth * maxSize;
    return;
  }
  glGetIntegerv(name, value);
}

}  // extern "C"
