// Images and files: FITS through CFITSIO, everything else through OpenImageIO 2.4.
// Why not OpenImageIO for FITS: its 2.4 FITS plugin (fitsoutput.cpp, fitsinput.cpp) puts row y at (height − y)
// rows into the data instead of (height − 1 − y): the file starts with a blank row, its top row lies past NAXIS2
// rows and the file is not a whole number of 2880-byte blocks. OpenImageIO reads its own files back the same way,
// so they round-trip there, but astropy, DS9 and CFITSIO see the picture shifted by one row. CFITSIO (HEASARC, the
// reference FITS library; Debian libcfitsio-dev) writes and reads the standard layout (FITS Standard 4.0 §3.3,
// §4.4): the header in 2880-byte blocks, then NAXIS1 × NAXIS2 big-endian values, the first row stored being the
// bottom of the picture (pixel (1, 1) at the lower left, the display convention), padded to 2880 bytes.
#include "radchain/atomic_file.hpp"
#include "radchain/imaging/image.hpp"

#include <OpenImageIO/imageio.h>
#include <fitsio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <stdexcept>

namespace radchain::render {

namespace {

std::string lower_extension(const std::string& path) {
  const auto dot = path.rfind('.');
  if (dot == std::string::npos) return {};
  std::string ext = path.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

void check_key(const std::string& key) {
  const bool ok = !key.empty() && key.size() <= 8 && std::all_of(key.begin(), key.end(), [](char c) {
                    return (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
                  });
  if (!ok) throw std::invalid_argument("FITS keyword \"" + key + "\": 1-8 characters of A-Z, 0-9, '-' or '_'");
  static const std::set<std::string> reserved = {"SIMPLE", "BITPIX", "NAXIS", "NAXIS1", "NAXIS2", "END", "EXTEND", "BZERO", "BSCALE", "COMMENT", "HISTORY"};
  if (reserved.count(key)) throw std::invalid_argument("FITS keyword \"" + key + "\" is written by the FITS writer itself");
}

// The shortest decimal that reads back as the same double, always with a '.' or an exponent (a FITS real).
std::string real_text(double value) {
  if (!std::isfinite(value)) throw std::invalid_argument("FITS cannot hold a non-finite number");
  char buffer[64];
  for (int precision = 1; precision <= 17; ++precision) {
    std::snprintf(buffer, sizeof buffer, "%.*G", precision, value);
    if (std::strtod(buffer, nullptr) == value) break;
  }
  std::string text = buffer;
  if (text.find_first_of(".E") == std::string::npos) text += ".0";
  return text;
}

bool is_fits_path(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == "fits" || ext == "fit" || ext == "fts";
}

// A library call that failed on `path`. A failed write is a WriteError, like AtomicFile's (exit 3, "cannot write
// <path>: <reason> (nothing written)": the temporary is discarded); a failed read is bad input at the caller.
[[noreturn]] void failure(const std::string& what, const std::string& path, const std::string& detail) {
  if (what == "cannot write") throw WriteError(what + " " + path + ": " + detail + " (nothing written)");
  throw std::runtime_error(what + " \"" + path + "\": " + detail);
}

// A CFITSIO call that failed: its status as text, and the first message of its error stack.
[[noreturn]] void fits_failure(const std::string& what, const std::string& path, int status) {
  char text[FLEN_STATUS] = {}, message[FLEN_ERRMSG] = {};
  fits_get_errstatus(status, text);
  std::string detail = text;
  if (fits_read_errmsg(message)) detail += std::string(" (") + message + ")";
  fits_clear_errmsg();
  failure(what, path, detail);
}

// The picture's rows bottom-up (FITS stores the bottom row first), converted to T.
template <class T>
std::vector<T> fits_rows(const Image& image, const std::vector<T>& values) {
  std::vector<T> out(values.size());
  const std::size_t w = static_cast<std::size_t>(image.width);
  for (int y = 0; y < image.height; ++y)
    std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(y * w), w,
                out.begin() + static_cast<std::ptrdiff_t>((image.height - 1 - y) * w));
  return out;
}

template <class T>
std::vector<T> integers(const Image& image) {
  std::vector<T> out(image.size());
  for (std::size_t i = 0; i < image.size(); ++i) {
    const double v = std::nearbyint(static_cast<double>(image.pixels[i]));
    if (!(v >= static_cast<double>(std::numeric_limits<T>::lowest()) && v <= static_cast<double>(std::numeric_limits<T>::max())))
      throw std::invalid_argument("write_fits: a pixel value does not fit the chosen integer type");
    out[i] = static_cast<T>(v);
  }
  return out;
}

// Percentile of a sample (nth_element on a copy).
float percentile(std::vector<float> values, double percent) {
  if (values.empty()) return 0.0f;
  const double position = std::clamp(percent, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
  const auto index = static_cast<std::size_t>(std::llround(position));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(index), values.end());
  return values[index];
}

template <class T>
double widened(const unsigned char* bytes) {
  T value;
  std::memcpy(&value, bytes, sizeof value);
  return static_cast<double>(value);
}

[[noreturn]] void oiio_failure(const std::string& what, const std::string& path, const std::string& detail) {
  failure(what, path, detail.empty() ? OIIO::geterror() : detail);
}

}  // namespace

Image::Image(int width_px, int height_px, float fill)
    : width(width_px), height(height_px),
      pixels(static_cast<std::size_t>(std::max(0, width_px)) * static_cast<std::size_t>(std::max(0, height_px)), fill) {
  if (width_px < 0 || height_px < 0) throw std::invalid_argument("Image: negative size");
}

const HeaderCard* find_card(const Header& header, const std::string& key) {
  const std::string k = upper(key);
  for (const auto& card : header)
    if (upper(card.key) == k) return &card;
  return nullptr;
}

std::optional<double> card_number(const Header& header, const std::string& key) {
  const HeaderCard* card = find_card(header, key);
  if (!card) return std::nullopt;
  if (const auto* b = std::get_if<bool>(&card->value)) return *b ? 1.0 : 0.0;
  if (const auto* i = std::get_if<std::int64_t>(&card->value)) return static_cast<double>(*i);
  if (const auto* d = std::get_if<double>(&card->value)) return *d;
  return std::nullopt;
}

std::string card_value_text(const HeaderCard& card) {
  if (const auto* b = std::get_if<bool>(&card.value)) return *b ? "T" : "F";
  if (const auto* i = std::get_if<std::int64_t>(&card.value)) return std::to_string(*i);
  if (const auto* d = std::get_if<double>(&card.value)) return real_text(*d);
  std::string text = std::get<std::string>(card.value);
  std::string quoted = "'";
  for (char c : text) {
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';  // FITS text is printable ASCII
    const std::size_t width = c == '\'' ? 2 : 1;
    if (quoted.size() + width > 69) break;  // 68 characters inside the quotes
    quoted += c;
    if (c == '\'') quoted += '\'';
  }
  return quoted + "'";
}

FitsPixel fits_pixel_for(const Image& image) {
  bool integral = true, fits16 = true, fits32 = true;
  for (float v : image.pixels) {
    if (!(std::nearbyint(v) == v)) {
      integral = false;
      break;
    }
    fits16 = fits16 && v >= 0.0f && v <= 32767.0f;
    fits32 = fits32 && v >= -2147483648.0f && v <= 2147483520.0f;
  }
  if (!integral) return FitsPixel::float32;
  if (fits16) return FitsPixel::int16;
  return fits32 ? FitsPixel::int32 : FitsPixel::float32;
}

void write_fits(const std::string& path, const Image& image, const Header& header, FitsPixel pixel) {
  if (image.empty()) throw std::invalid_argument("write_fits: empty image");
  if (!is_fits_path(path)) throw std::invalid_argument("write_fits: \"" + path + "\" is not a .fits path");
  // The cards first: a bad key or a repeated one is refused before any file is made.
  std::vector<std::string> records;
  std::set<std::string> seen;
  for (const auto& card : header) {
    check_key(card.key);
    if (!seen.insert(card.key).second) throw std::invalid_argument("FITS keyword \"" + card.key + "\" appears twice");
    std::string value = card_value_text(card);
    // "KEY     = " takes 10 of the card's 80 characters; a comment follows " / " when it fits (cut otherwise).
    std::string record = card.key + std::string(8 - card.key.size(), ' ') + "= " + std::string(value.size() < 20 ? 20 - value.size() : 0, ' ') + value;
    if (value.front() == '\'') record = card.key + std::string(8 - card.key.size(), ' ') + "= " + value;  // strings start at column 11
    if (!card.comment.empty() && record.size() + 3 < 80) record += " / " + card.comment.substr(0, 80 - record.size() - 3);
    for (char& c : record)
      if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';  // printable ASCII only
    records.push_back(record.substr(0, 80));
  }
  // The rows too, bottom-up in the pixel type: a value the type cannot hold is refused before the file is
  // opened (an exception between fits_create_file and fits_close_file leaked CFITSIO's handle).
  std::vector<std::int16_t> rows16;
  std::vector<std::int32_t> rows32;
  std::vector<float> rows_float;
  switch (pixel) {
    case FitsPixel::int16: rows16 = fits_rows(image, integers<std::int16_t>(image)); break;
    case FitsPixel::int32: rows32 = fits_rows(image, integers<std::int32_t>(image)); break;
    case FitsPixel::float32: rows_float = fits_rows(image, image.pixels); break;
  }
  AtomicFile file(path, "output image");  // written to a temporary, renamed when complete
  int status = 0;
  fitsfile* fits = nullptr;
  const std::string target = "!" + file.temporary_path();  // '!': replace an existing file
  if (fits_create_file(&fits, target.c_str(), &status)) fits_failure("cannot write", path, status);
  // The primary image (BITPIX from the pixel type), then the cards, then the rows; nothing here throws.
  auto write = [&](int bitpix, int datatype, auto& values) {
    long axes[2] = {image.width, image.height};
    fits_create_img(fits, bitpix, 2, axes, &status);
    for (const auto& r : records) fits_write_record(fits, r.c_str(), &status);
    fits_write_img(fits, datatype, 1, static_cast<LONGLONG>(values.size()), values.data(), &status);
  };
  switch (pixel) {
    case FitsPixel::int16: write(SHORT_IMG, TSHORT, rows16); break;
    case FitsPixel::int32: write(LONG_IMG, TINT, rows32); break;
    case FitsPixel::float32: write(FLOAT_IMG, TFLOAT, rows_float); break;
  }
  int closing = 0;
  fits_close_file(fits, &closing);
  if (status || closing) fits_failure("cannot write", path, status ? status : closing);
  file.commit();
}

void write_float_image(const std::string& path, const Image& image, const Header& header) {
  if (image.empty()) throw std::invalid_argument("write_float_image: empty image");
  OIIO::ImageSpec spec(image.width, image.height, 1, OIIO::TypeDesc::FLOAT);
  for (const auto& card : header) spec.attribute("radchain:" + card.key, card_value_text(card));
  auto out = OIIO::ImageOutput::create(path);
  if (!out) oiio_failure("cannot write", path, {});
  AtomicFile file(path, "output image");  // written to a temporary, renamed when complete
  if (!out->open(file.temporary_path(), spec)) oiio_failure("cannot write", path, out->geterror());
  if (!out->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data())) oiio_failure("cannot write", path, out->geterror());
  if (!out->close()) oiio_failure("cannot write", path, out->geterror());
  file.commit();
}

namespace {

// A FITS card's value as typed: 'text' (quotes undone), T/F, an integer, else a real (FITS Standard 4.0 §4.2). An
// integer beyond 64 bits is kept as a real; anything else that is none of these is refused with the card named
// (a std::stoll here once let std::out_of_range escape as an internal error: scene_fits_fuzz).
HeaderCard typed_card(const RawCard& raw, const std::string& path) {
  HeaderCard card{raw.key, std::string(), raw.comment};
  const std::string& v = raw.value;
  auto refuse = [&] {
    throw std::runtime_error("cannot read \"" + path + "\": card " + raw.key + ": value \"" + v +
                             "\" is not a FITS value (a 'text', T or F, an integer or a real)");
  };
  if (v.size() >= 2 && v.front() == '\'') {
    std::string text;
    for (std::size_t i = 1; i + 1 < v.size(); ++i) {
      text += v[i];
      if (v[i] == '\'' && v[i + 1] == '\'') ++i;
    }
    text.erase(text.find_last_not_of(' ') + 1);  // trailing blanks are not significant (FITS 4.0 §4.2.1)
    card.value = text;
  } else if (v == "T" || v == "F") {
    card.value = v == "T";
  } else if (!v.empty()) {
    if (v.find_first_of(".EeDd") == std::string::npos) {
      std::int64_t integer = 0;
      const char* first = v.data() + (v.front() == '+' ? 1 : 0);
      const auto [end, error] = std::from_chars(first, v.data() + v.size(), integer);
      if (error == std::errc() && end == v.data() + v.size()) {
        card.value = integer;
        return card;
      }
      if (error != std::errc::result_out_of_range) refuse();
    }
    std::string number = v;
    std::replace(number.begin(), number.end(), 'D', 'E');  // FITS allows D exponents
    errno = 0;
    char* end = nullptr;
    const double real = std::strtod(number.c_str(), &end);
    if (end != number.c_str() + number.size() || errno == ERANGE || !std::isfinite(real)) refuse();
    card.value = real;
  }
  return card;
}

// The primary header's 80-character cards up to END (FITS Standard 4.0 §4.1), and how many 2880-byte blocks the
// header fills; `ended` is false when the file has no END card.
struct RawHeader {
  std::vector<std::string> cards;
  std::size_t blocks = 0;
  bool ended = false;
};
RawHeader raw_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read \"" + path + "\"");
  RawHeader header;
  std::string block(2880, ' ');
  while (!header.ended && in.read(block.data(), 2880)) {
    ++header.blocks;
    for (std::size_t c = 0; c < 36; ++c) {
      std::string card = block.substr(c * 80, 80);
      if (card.compare(0, 8, "END     ") == 0) {
        header.ended = true;
        break;
      }
      header.cards.push_back(std::move(card));
    }
  }
  return header;
}

// The primary HDU's structure checked before CFITSIO opens the file (FITS Standard 4.0, §3.1: a file is a whole
// number of 2880-byte blocks; §4.4.1.1: SIMPLE, BITPIX, NAXIS, NAXISn are the first cards; the data follow the
// header's END block and fill ⌈|BITPIX|/8 · Π NAXISn / 2880⌉ blocks). A truncated or malformed file is refused here
// with its reason: CFITSIO 4.2 leaks its handle when ffopen fails on such a file (scene_fits_fuzz, seed 1).
// radchain reads the primary image only: a file whose image is in an extension (NAXIS = 0 here) is refused.
// Render's limit on a scene's side: a larger declared size is refused before anything is allocated (a 389 kB PNG
// may declare 20000² pixels).
constexpr long long max_image_side_px = 16384;

void check_fits_structure(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw std::runtime_error("cannot read \"" + path + "\": " + ec.message());
  auto refuse = [&](const std::string& why) { throw std::runtime_error("cannot read \"" + path + "\": " + why); };
  if (size == 0 || size % 2880 != 0)
    refuse(std::to_string(size) + " bytes: not a whole number of 2880-byte FITS blocks (truncated, or not FITS)");
  const RawHeader header = raw_header(path);
  if (!header.ended) refuse("no END card (not a FITS file)");
  // The mandatory cards in order, each "KEY     = " and an integer (SIMPLE: T) right-justified in columns 11-30.
  const char* mandatory[] = {"SIMPLE", "BITPIX", "NAXIS", "NAXIS1", "NAXIS2"};
  long long value[5] = {0, 0, 0, 0, 0};
  for (std::size_t i = 0; i < 5; ++i) {
    if (i >= header.cards.size()) refuse(std::string("the mandatory ") + mandatory[i] + " card is missing (FITS §4.4.1.1)");
    const std::string& card = header.cards[i];
    std::string key = card.substr(0, 8);
    key.erase(key.find_last_not_of(' ') + 1);
    if (key != mandatory[i] || card.compare(8, 2, "= ") != 0)
      refuse("card " + std::to_string(i + 1) + " is \"" + key + "\", expected " + mandatory[i] + " = (FITS §4.4.1.1)");
    const std::string text = card.substr(10, 20);
    if (i == 0) {
      if (text.find_first_not_of(' ') != 19 || text[19] != 'T') refuse("SIMPLE is not T");
      continue;
    }
    std::size_t used = 0;
    try {
      value[i] = std::stoll(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || text.find_first_not_of(' ', used) != std::string::npos) refuse(std::string(mandatory[i]) + " is not an integer");
    // Each refused as soon as it is read: later arithmetic then only sees small, valid numbers.
    const long long bitpix = value[1];
    if (i == 1 && bitpix != 8 && bitpix != 16 && bitpix != 32 && bitpix != 64 && bitpix != -32 && bitpix != -64)
      refuse("BITPIX = " + std::to_string(bitpix) + ": not a FITS pixel type");
    if (i == 2 && value[2] == 0) refuse("the primary HDU holds no image (NAXIS = 0); images in extensions are not read");
    if (i == 2 && value[2] != 2) refuse("not a 2-D image (NAXIS = " + std::to_string(value[2]) + ")");
    if (i >= 3 && (value[i] < 1 || value[i] > max_image_side_px))
      refuse(std::string(mandatory[i]) + " = " + std::to_string(value[i]) + ": 1 to 16384 pixels a side");
  }
  const std::uintmax_t data_bytes = static_cast<std::uintmax_t>(std::llabs(value[1]) / 8) * static_cast<std::uintmax_t>(value[3]) *
                                    static_cast<std::uintmax_t>(value[4]);
  const std::uintmax_t needed = (header.blocks + (data_bytes + 2879) / 2880) * 2880;
  if (size < needed) refuse(std::to_string(size) + " bytes, but its header declares " + std::to_string(needed) + " (truncated)");
}

// A FITS primary image through CFITSIO (see the top of this file): pixels as stored, top row first.
ImageFile read_fits(const std::string& path) {
  check_fits_structure(path);
  int status = 0, bitpix = 0, naxis = 0;
  long axes[2] = {0, 0};
  fitsfile* fits = nullptr;
  if (fits_open_file(&fits, path.c_str(), READONLY, &status)) fits_failure("cannot read", path, status);  // the primary HDU
  fits_get_img_param(fits, 2, &bitpix, &naxis, axes, &status);
  if (!status && (naxis != 2 || axes[0] < 1 || axes[1] < 1)) {
    fits_close_file(fits, &status);
    throw std::runtime_error("cannot read \"" + path + "\": not a 2-D image (NAXIS = " + std::to_string(naxis) + ")");
  }
  ImageFile file;
  file.format = "fits";
  file.pixel_type = bitpix == 8 ? "uint8" : bitpix == 16 ? "int16" : bitpix == 32 ? "int32" : bitpix == 64 ? "int64" : bitpix == -64 ? "double" : "float";
  const int w = static_cast<int>(axes[0]), h = static_cast<int>(axes[1]);
  std::vector<double> values(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  int any_null = 0;
  if (!status) fits_read_img(fits, TDOUBLE, 1, static_cast<LONGLONG>(values.size()), nullptr, values.data(), &any_null, &status);
  int closing = 0;
  fits_close_file(fits, &closing);
  if (status) fits_failure("cannot read", path, status);
  file.image = Image(w, h);
  for (int y = 0; y < h; ++y)  // stored bottom row first
    for (int x = 0; x < w; ++x)
      file.image(x, y) = static_cast<float>(values[static_cast<std::size_t>(h - 1 - y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)]);
  static const std::set<std::string> structural = {"SIMPLE", "BITPIX", "NAXIS", "NAXIS1", "NAXIS2", "EXTEND", "COMMENT", "HISTORY"};
  for (const RawCard& raw : read_fits_header_cards(path))
    if (!structural.count(raw.key)) file.header.push_back(typed_card(raw, path));
  return file;
}

}  // namespace

ImageFile read_image(const std::string& path, PixelValues values) {
  // A FIFO or a device would block or stream without end inside the decoder.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw std::runtime_error("cannot read \"" + path + "\": not a regular file (missing, or a directory, FIFO or device)");
  if (is_fits_path(path)) return read_fits(path);
  auto in = OIIO::ImageInput::open(path);
  if (!in) oiio_failure("cannot read", path, {});
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width < 1 || spec.height < 1 || spec.width > max_image_side_px || spec.height > max_image_side_px ||
      spec.nchannels < 1 || spec.nchannels > 4)
    throw std::runtime_error(fmt::format("cannot read \"{}\": it declares {} × {} pixels of {} channels: 1 to {} pixels a side "
                                         "and 1 to 4 channels are read",
                                         path, spec.width, spec.height, spec.nchannels, max_image_side_px));
  ImageFile file;
  file.format = in->format_name();
  file.pixel_type = spec.format.c_str();
  file.channels = spec.nchannels;
  const int w = spec.width, h = spec.height, nc = spec.nchannels;
  const std::size_t count = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * static_cast<std::size_t>(nc);
  std::vector<double> data(count);
  const OIIO::TypeDesc stored = spec.format;
  const bool integer = stored.basetype != OIIO::TypeDesc::FLOAT && stored.basetype != OIIO::TypeDesc::DOUBLE &&
                       stored.basetype != OIIO::TypeDesc::HALF;
  bool ok = false;
  if (integer && values == PixelValues::as_stored) {
    // OpenImageIO converts integer pixels to float as normalised values; read them as stored and widen here.
    std::vector<unsigned char> raw(count * stored.size());
    ok = in->read_image(0, 0, 0, nc, stored, raw.data());
    for (std::size_t i = 0; ok && i < count; ++i) {
      const unsigned char* p = raw.data() + i * stored.size();
      switch (stored.basetype) {
        case OIIO::TypeDesc::UINT8: data[i] = widened<std::uint8_t>(p); break;
        case OIIO::TypeDesc::INT8: data[i] = widened<std::int8_t>(p); break;
        case OIIO::TypeDesc::UINT16: data[i] = widened<std::uint16_t>(p); break;
        case OIIO::TypeDesc::INT16: data[i] = widened<std::int16_t>(p); break;
        case OIIO::TypeDesc::UINT32: data[i] = widened<std::uint32_t>(p); break;
        case OIIO::TypeDesc::INT32: data[i] = widened<std::int32_t>(p); break;
        default: throw std::runtime_error("cannot read \"" + path + "\": pixel type " + file.pixel_type + " is not supported");
      }
    }
  } else {
    ok = in->read_image(0, 0, 0, nc, OIIO::TypeDesc::DOUBLE, data.data());
  }
  if (!ok) oiio_failure("cannot read", path, in->geterror());
  in->close();
  // Grey: the mean of the colour channels (alpha left out).
  file.image = Image(w, h);
  int colour = 0;
  for (int c = 0; c < nc; ++c) colour += c == spec.alpha_channel ? 0 : 1;
  if (colour == 0) colour = 1;
  for (std::size_t i = 0; i < file.image.size(); ++i) {
    double sum = 0;
    for (int c = 0; c < nc; ++c)
      if (c != spec.alpha_channel || nc == 1) sum += data[i * static_cast<std::size_t>(nc) + static_cast<std::size_t>(c)];
    file.image.pixels[i] = static_cast<float>(sum / colour);
  }
  for (const auto& attribute : spec.extra_attribs) {
    HeaderCard card;
    card.key = upper(attribute.name().string());
    const OIIO::TypeDesc t = attribute.type();
    if (t == OIIO::TypeDesc::INT) card.value = static_cast<std::int64_t>(attribute.get_int());
    else if (t == OIIO::TypeDesc::FLOAT || t == OIIO::TypeDesc::DOUBLE) card.value = static_cast<double>(attribute.get_float());
    else card.value = attribute.get_string();
    file.header.push_back(std::move(card));
  }
  return file;
}

Image read_reflectance_map(const std::string& path) {
  ImageFile file = read_image(path, PixelValues::normalised);
  for (float v : file.image.pixels)
    if (!(v >= 0.0f && v <= 1.0f))
      throw std::invalid_argument("reflectance map \"" + path + "\": values must lie in [0, 1] (found " + std::to_string(v) + ")");
  return std::move(file.image);
}

std::vector<RawCard> read_fits_header_cards(const std::string& path) {
  const RawHeader header = raw_header(path);
  if (!header.ended) throw std::runtime_error("\"" + path + "\": no END card (not a FITS file)");
  std::vector<RawCard> cards;
  for (const std::string& card : header.cards) {
    RawCard raw;
    raw.key = card.substr(0, 8);
    raw.key.erase(raw.key.find_last_not_of(' ') + 1);
    if (card.compare(8, 2, "= ") == 0) {
      std::string rest = card.substr(10);
      std::size_t i = rest.find_first_not_of(' ');
      if (i != std::string::npos && rest[i] == '\'') {
        std::size_t j = i + 1;
        while (j < rest.size()) {
          if (rest[j] == '\'' && (j + 1 >= rest.size() || rest[j + 1] != '\'')) break;
          j += rest[j] == '\'' ? 2 : 1;
        }
        raw.value = rest.substr(i, std::min(j + 1, rest.size()) - i);
        rest = rest.substr(std::min(j + 1, rest.size()));
        const auto slash = rest.find('/');
        if (slash != std::string::npos) raw.comment = rest.substr(slash + 1);
      } else {
        const auto slash = rest.find('/');
        raw.value = rest.substr(0, slash);
        if (slash != std::string::npos) raw.comment = rest.substr(slash + 1);
      }
    } else {
      raw.comment = card.substr(8);
    }
    auto trim = [](std::string& s) {
      s.erase(0, std::min(s.size(), s.find_first_not_of(' ')));
      s.erase(s.find_last_not_of(' ') + 1);
    };
    trim(raw.value);
    trim(raw.comment);
    if (!raw.key.empty()) cards.push_back(std::move(raw));
  }
  return cards;
}

// The median + k σ of a star frame's background (PreviewOptions::black_sigmas).
static double background_level(const Image& image, double k) {
  const double median = percentile(image.pixels, 50.0);
  std::vector<float> deviation(image.pixels.size());
  for (std::size_t i = 0; i < deviation.size(); ++i) deviation[i] = static_cast<float>(std::abs(image.pixels[i] - median));
  double sigma = 1.4826 * percentile(deviation, 50.0);
  if (!(sigma > 0)) {  // quantised noise: most pixels at one DN value
    const double cut = percentile(image.pixels, 99.0);
    double sum = 0, sum2 = 0;
    std::size_t n = 0;
    for (float v : image.pixels)
      if (v <= cut) sum += v, sum2 += static_cast<double>(v) * v, ++n;
    const double mean = n ? sum / n : 0;
    sigma = n > 1 ? std::sqrt(std::max(0.0, (sum2 - n * mean * mean) / (n - 1))) : 0;
  }
  return median + k * sigma;
}

void write_preview(const std::string& path, const Image& image, const PreviewOptions& options) {
  const std::string ext = lower_extension(path);
  const bool png = ext == "png", tiff = ext == "tif" || ext == "tiff";
  if (!png && !tiff) throw std::invalid_argument("preview \"" + path + "\": use a .png or .tif file name");
  if (image.empty()) throw std::invalid_argument("write_preview: empty image");
  const double lo = std::isnan(options.black_sigmas) ? percentile(image.pixels, options.low_percentile)
                                                     : background_level(image, options.black_sigmas);
  double hi = percentile(image.pixels, options.high_percentile);
  if (!(hi > lo)) hi = lo + 1.0;
  const double soft = std::max(options.softening, 1e-6);
  auto display = [&](float v) {
    const double x = std::clamp((static_cast<double>(v) - lo) / (hi - lo), 0.0, 1.0);
    return options.stretch == Stretch::asinh ? std::asinh(x / soft) / std::asinh(1.0 / soft) : x;
  };
  const int up = std::max(1, options.upscale);
  const int w = image.width * up, h = image.height * up;
  const double top = png ? 255.0 : 65535.0;
  std::vector<std::uint16_t> wide(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      wide[static_cast<std::size_t>(y) * w + x] = static_cast<std::uint16_t>(std::lround(display(image(x / up, y / up)) * top));
  auto out = OIIO::ImageOutput::create(path);
  if (!out) oiio_failure("cannot write", path, {});
  AtomicFile file(path, "output image");  // written to a temporary, renamed when complete
  const OIIO::TypeDesc type = png ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
  OIIO::ImageSpec spec(w, h, 1, type);
  spec.attribute("Software", "radchain render");
  if (!out->open(file.temporary_path(), spec)) oiio_failure("cannot write", path, out->geterror());
  bool ok = false;
  if (png) {
    std::vector<std::uint8_t> narrow(wide.begin(), wide.end());
    ok = out->write_image(OIIO::TypeDesc::UINT8, narrow.data());
  } else {
    ok = out->write_image(OIIO::TypeDesc::UINT16, wide.data());
  }
  if (!ok || !out->close()) oiio_failure("cannot write", path, out->geterror());
  file.commit();
}

void write_png16(const std::string& path, const Image& image) {
  if (lower_extension(path) != "png") throw std::invalid_argument("write_png16: \"" + path + "\" is not a .png path");
  std::vector<std::uint16_t> values(image.size());
  for (std::size_t i = 0; i < image.size(); ++i)
    values[i] = static_cast<std::uint16_t>(std::lround(std::clamp(static_cast<double>(image.pixels[i]), 0.0, 1.0) * 65535.0));
  auto out = OIIO::ImageOutput::create(path);
  if (!out) oiio_failure("cannot write", path, {});
  AtomicFile file(path, "output image");  // written to a temporary, renamed when complete
  OIIO::ImageSpec spec(image.width, image.height, 1, OIIO::TypeDesc::UINT16);
  spec.attribute("png:compressionLevel", 9);
  if (!out->open(file.temporary_path(), spec) || !out->write_image(OIIO::TypeDesc::UINT16, values.data()) || !out->close())
    oiio_failure("cannot write", path, out->geterror());
  file.commit();
}

}  // namespace radchain::render
