// The OpenGL 4.5 core API as pelage uses it: prototypes from <GL/glcorearb.h>, resolved at link
// time against libglvnd's libOpenGL.so.0 (CMake target OpenGL::OpenGL), which dispatches to
// whichever context is current (EGL or GLX). No loader library is needed
// (../shared/docs/headless-gl.md).
#pragma once

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
