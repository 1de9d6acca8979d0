// FITS files as `radchain render --scene` reads them (a reflectance map): CFITSIO reads the image, radchain's own
// card parser (read_fits_header_cards, hand-written: the part of the path that is not a library) reads the header.
// The CLI turns std::runtime_error / std::invalid_argument from the reader into one line at --scene (exit 2); any
// other outcome is a finding. PNG/TIFF scenes are OpenImageIO's parsing, not fuzzed here (docs/fuzzing.md).
#include "fuzz_input.hpp"

#include "radchain/imaging/image.hpp"

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = radchain::fuzz::write_scratch("scene.fits", radchain::fuzz::as_text(data, size));
  try {
    (void)radchain::render::read_fits_header_cards(path);
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  try {
    const radchain::render::Image map = radchain::render::read_reflectance_map(path);
    (void)map.size();
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
