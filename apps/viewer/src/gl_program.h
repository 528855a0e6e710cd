// Compiling and linking the viewer's GLSL programs (the renderer's and the frame cache's).
#pragma once

#define GL_GLEXT_PROTOTYPES
#include <GL/gl.h>
#include <GL/glext.h>

namespace lapis::viewer {

// A linked program of a vertex and a fragment shader. Needs a current OpenGL 3.3 core context.
// Throws lapis::Error with the driver's log when a shader does not compile or link.
GLuint link_program(const char* vertex_source, const char* fragment_source);
// The same with a geometry shader between them (`geometry_source` may be null: none).
GLuint link_program(const char* vertex_source, const char* geometry_source, const char* fragment_source);

}  // namespace lapis::viewer
