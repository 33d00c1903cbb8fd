// Shared helpers for image-space compute passes.
#ifndef LUCID_IMAGE_COORDS_GLSL
#define LUCID_IMAGE_COORDS_GLSL

// True when the invocation covers a pixel of an image of size `size` (dispatches round up; an
// invocation's pixel is never negative).
bool pixel_in_bounds(ivec2 pixel, ivec2 size) {
    return all(lessThan(pixel, size));
}

// True when `q`, which may lie on either side of the image (a neighbour), is one of its pixels.
bool inside_image(ivec2 q, ivec2 size) {
    return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size));
}

#endif
