#pragma once
// The image `radchain render` draws, as data: a point-target frame or an Earth scene from a sensor chain and the
// render options. The command writes it to files (render.cpp); the Python module returns it as a numpy array
// (python/src/imaging.cpp, radchain.render). One function, so both give the same pixels for the same request.
#include "../option_schema.hpp"

#include "radchain/chain.hpp"
#include "radchain/imaging/image.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace radchain::cli {

// What a render takes besides the sensor: the options of render_option_schema() (validated), and the plain ones.
struct RenderRequest {
  std::vector<std::string> targets;  // "x,y,mag" (pixels, row 0 at the top) or "mag" (centre); mag may be "limit"
  std::string scene;                 // Earth scenes: a reflectance map (empty: the built-in test scene)
  std::uint64_t seed = 1;            // noise
  std::uint64_t star_seed = 1;       // field stars
};

struct RenderedImage {
  render::Image image;
  render::Header header;
  bool point_targets = true;         // a detector frame (else an Earth scene)
  std::vector<std::string> summary;  // what the command prints about it, line by line
};

// Throws InputError for a request the chain cannot render (bad targets, sizes, a sensor without what it needs).
RenderedImage render_image(Chain& chain, const Report& report, const Params& options, const RenderRequest& request);

}  // namespace radchain::cli
