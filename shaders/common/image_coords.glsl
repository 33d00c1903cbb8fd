// Shared helpers for image-space compute passes.
#ifndef LUCID_IMAGE_COORDS_GLSL
#define LUCID_IMAGE_COORDS_GLSL

// True when the invocation covers a pixel of an image of size `size` (dispatches round up).
bool pixel_in_bounds(ivec2 pixel, ivec2 size) {
    return all(lessThan(pixel, size));
}

#endif
