#pragma once
// stb_image's decoder for tests that read back PNG previews and screenshots. Each test program
// is its own executable and includes this from one file, so the implementation is compiled
// static into that file alone.
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_image.h>
#pragma GCC diagnostic pop
