// The GL header of the frontend: glad 2, generated at build time (GL 3.3 core + KHR_debug).
#pragma once

#include <glad/gl.h>
