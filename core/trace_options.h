#pragma once

namespace refract {

// How a render searches and walks (RenderOptions::trace): facet-local intersection (off:
// the full plane loop, for comparison; core/hit_search.h) and packets of rays (the
// wavelength bands of a split, the samples of a pixel; off: one ray at a time). Either way
// the same images to the last bit. Per render, not per process.
struct TraceOptions {
    bool facet_local = true;
    bool packets = true;
};

}  // namespace refract
