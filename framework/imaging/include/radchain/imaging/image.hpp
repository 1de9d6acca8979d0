#pragma once
// Images of the renderer and their files, through OpenImageIO 2.4 (private to framework/src/render):
//   FITS (the data: float, or 16/32-bit integers, with the sensor in the header) and PNG/TIFF previews with a
//   display stretch; any format OpenImageIO reads as input (a reflectance map for an Earth scene).
//
// Orientation: row 0 is the top row, as in PNG and TIFF. FITS stores rows bottom-up; OpenImageIO's FITS
// writer and reader flip them, so a FITS viewer (DS9) shows the frame as the PNG does.
//
// What OpenImageIO 2.4's FITS writer does with metadata (checked by tests/imaging/fits_test.cpp): every extra
// attribute becomes one card `KEY = value`, the key upper-cased and cut to 8 characters; the value is written
// verbatim, so text must carry its own quotes and a comment may follow " / ". Integer, float and text
// attributes are written; double attributes are written empty, and HIERARCH and long text (> 68 characters)
// are mangled. write_fits() therefore formats every card's value itself (numbers with 17 significant digits,
// text quoted with '' escapes and cut to 68 characters) and hands it over as text. The reader returns
// numbers as float (7 digits) and text without quotes or comment; read_fits_header_cards() reads the cards
// exactly. Unsigned 16-bit data would be written as BITPIX 16 without BZERO (read back as negative numbers
// by other readers), so integer frames use int16 only when every value fits in 0..32767, else int32.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace radchain::render {

// One channel, row-major, row 0 at the top.
struct Image {
  int width = 0, height = 0;
  std::vector<float> pixels;

  Image() = default;
  Image(int width_px, int height_px, float fill = 0.0f);
  float& operator()(int x, int y) { return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x]; }
  float operator()(int x, int y) const { return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x]; }
  std::size_t size() const { return pixels.size(); }
  bool empty() const { return pixels.empty(); }
};

// One FITS header card. Key: 1-8 characters of A-Z, 0-9, '-', '_' (FITS 4.0 §4.1.2.1). Text values are cut to
// 68 characters. The comment starts with the unit in brackets where there is one: "[s] integration time".
struct HeaderCard {
  std::string key;
  std::variant<bool, std::int64_t, double, std::string> value;
  std::string comment;
};
using Header = std::vector<HeaderCard>;

const HeaderCard* find_card(const Header& header, const std::string& key);
// The card's value as a number (bool → 0/1); nullopt for text or when absent.
std::optional<double> card_number(const Header& header, const std::string& key);
// The card's value as written in the FITS file: T, 42, 1.2345678901234567e-05, 'text'.
std::string card_value_text(const HeaderCard& card);

enum class FitsPixel {
  float32,  // BITPIX -32
  int16,    // BITPIX 16, values 0..32767 (the writer stores no BZERO)
  int32,    // BITPIX 32
};
// int16 when every pixel is an integer in [0, 32767], int32 when every pixel is an integer that fits, else float32.
FitsPixel fits_pixel_for(const Image& image);

// Writes a single-HDU FITS file: the pixels converted to `pixel` (integers rounded; an integer type that cannot
// hold a value throws std::invalid_argument) and the cards in order after the mandatory ones. Throws
// std::runtime_error naming the path when OpenImageIO fails.
void write_fits(const std::string& path, const Image& image, const Header& header, FitsPixel pixel = FitsPixel::float32);
// The same data, unstretched, as 32-bit float TIFF or OpenEXR (by extension), the header cards as "radchain:KEY"
// metadata: for tools that do not read FITS.
void write_float_image(const std::string& path, const Image& image, const Header& header);

// How integer pixels of a file are returned.
enum class PixelValues {
  as_stored,   // the stored integers (a FITS frame in DN)
  normalised,  // integer formats scaled to 0..1 (8-bit 255 → 1, 16-bit 65535 → 1); float formats unchanged
};
struct ImageFile {
  Image image;
  Header header;      // OpenImageIO's metadata as cards: keys upper-cased, numbers as double (from float)
  std::string format; // OpenImageIO's format name: "fits", "png", "tiff"
  std::string pixel_type;  // "uint8", "uint16", "int16", "int", "float"
  int channels = 1;        // in the file; the image is their mean (colour channels only, alpha left out)
};
// Any format OpenImageIO reads. Throws std::runtime_error naming the path when it cannot.
ImageFile read_image(const std::string& path, PixelValues values = PixelValues::as_stored);
// A reflectance map: read_image(path, normalised); values outside [0, 1] are an error (std::invalid_argument).
Image read_reflectance_map(const std::string& path);

// The header cards of a FITS file read directly from its 2880-byte blocks (no OpenImageIO): every card's key,
// exact value text and comment; used to check what other FITS readers will see.
struct RawCard {
  std::string key, value, comment;
};
std::vector<RawCard> read_fits_header_cards(const std::string& path);

// Display stretch for previews: values between the low and high percentiles map to 0..1, then
//   linear:  v
//   asinh:   asinh(v / softening) / asinh(1 / softening)  (Lupton et al. 1999, AJ 118, 1406: faint stars and
//            bright ones in one picture; softening ≈ the background noise over the display range)
enum class Stretch { linear, asinh };
struct PreviewOptions {
  Stretch stretch = Stretch::asinh;
  double low_percentile = 50.0;    // black point, % of pixels below (the median: a star frame's background)
  double high_percentile = 99.99;  // white point
  double softening = 0.1;          // asinh only
  int upscale = 1;                 // nearest-neighbour magnification (small frames)
  // Star frames: the black point at the background's median + black_sigmas σ instead of low_percentile, so that the
  // sky and detector noise are dark and every star above it shows. σ is robust: 1.4826 × the median absolute
  // deviation, or, when the noise is quantised to a DN or two and that is 0, the standard deviation of the pixels
  // below the 99th percentile. NaN: low_percentile is the black point.
  double black_sigmas = std::numeric_limits<double>::quiet_NaN();
};
// PNG (8-bit) or TIFF (16-bit) by the file's extension (.png, .tif, .tiff). Throws std::invalid_argument for
// another extension and std::runtime_error when OpenImageIO fails.
void write_preview(const std::string& path, const Image& image, const PreviewOptions& options = {});
// A 16-bit grayscale PNG of values in [0, 1] (value × 65535, rounded): how scenes are stored.
void write_png16(const std::string& path, const Image& image);

}  // namespace radchain::render
