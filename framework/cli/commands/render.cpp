// `radchain render` (in the imaging module): a detector frame (point targets) or an Earth scene (pushbroom),
// drawn by render_image() (radchain/imaging/render_request.hpp) and written as FITS/TIFF/EXR and a preview.
#include "imaging_common.hpp"
#include "../overrides.hpp"

#include "radchain/imaging/render.hpp"
#include "radchain/imaging/render_request.hpp"

#include <fmt/format.h>

#include <filesystem>

namespace radchain::cli {
namespace {

using namespace radchain::render;

FitsPixel fits_type_of(const std::string& name, const Image& image) {
  if (name == "float") return FitsPixel::float32;
  if (name == "int16") return FitsPixel::int16;
  if (name == "int32") return FitsPixel::int32;
  return fits_pixel_for(image);  // auto
}

void write_outputs(const RenderCommand& c, const Params& v, const RenderedImage& r) {
  const Image& image = r.image;
  const Header& header = r.header;
  if (!c.out.empty()) {
    const std::string extension = std::filesystem::path(c.out).extension().string();
    if (extension == ".fits" || extension == ".fit" || extension == ".fts") {
      write_fits(c.out, image, header, fits_type_of(v.text("--fits-type"), image));
      fmt::print("wrote {} ({}×{}, FITS, {} header cards)\n", c.out, image.width, image.height, header.size());
    } else if (extension == ".tif" || extension == ".tiff" || extension == ".exr") {
      write_float_image(c.out, image, header);
      fmt::print("wrote {} ({}×{}, 32-bit float, {} metadata entries)\n", c.out, image.width, image.height, header.size());
    } else {
      bad_option("--out", c.out, "expected a .fits, .tif or .exr file for the data (previews: --png frame.png)");
    }
  }
  if (!c.preview.empty()) {
    write_preview(c.preview, image, preview_options(v, r.kind));
    fmt::print("wrote {} (preview)\n", c.preview);
  }
  if (c.out.empty() && c.preview.empty()) fmt::print("nothing written: give --out frame.fits and/or --preview frame.png\n");
}

}  // namespace

int render_command(const RenderCommand& c) {
  const Params values = validated_options(render_option_schema(), c.values, "radchain render");
  Chain chain = load_sensor_of(c.sensor);
  const Report report = chain.run();
  if (!report.all_passed())
    fmt::print(stderr, "radchain render: {}: a solve or an [expected] check failed (rendering anyway)\n", c.sensor.sensor);
  const RenderedImage r = render_image(chain, report, RenderRequest{values, c.targets, c.scene, c.seed, c.star_seed});
  for (const auto& line : r.summary) fmt::print("{}\n", line);
  write_outputs(c, values, r);
  return 0;
}

}  // namespace radchain::cli
