// FITS through CFITSIO and previews through OpenImageIO 2.4: pixels and header cards round-trip; the cards and the
// data layout are standard FITS (checked byte by byte here, not through the library that wrote them).
#include "radchain/imaging/render.hpp"
#include "render_test_helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <filesystem>

namespace {
using namespace radchain;
using namespace radchain::render;
using radchain::render_tests::load;

std::string temp_path(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "radchain-render-tests";
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

const RawCard* raw_card(const std::vector<RawCard>& cards, const std::string& key) {
  for (const auto& c : cards)
    if (c.key == key) return &c;
  return nullptr;
}

TEST(RenderFits, FrameAndHeaderRoundTrip) {
  auto sbv = load("msx-sbv.toml");
  SpaceFrameOptions o;
  o.width = 40;
  o.height = 24;  // not square: rows and columns stay apart
  o.stars.count = 5;
  const SpaceFrameRenderer r(space_frame_setup(sbv.chain, sbv.report, o));
  const Image frame = r.render(3);
  const Header header = r.header(3);
  ASSERT_EQ(fits_pixel_for(frame), FitsPixel::int16);
  const std::string path = temp_path("frame.fits");
  write_fits(path, frame, header, FitsPixel::int16);

  const ImageFile file = read_image(path);
  EXPECT_EQ(file.format, "fits");
  EXPECT_EQ(file.pixel_type, "int16");
  ASSERT_EQ(file.image.width, 40);
  ASSERT_EQ(file.image.height, 24);
  EXPECT_EQ(file.image.pixels, frame.pixels);  // row 0 stays the top row

  // Every card comes back: text exactly, numbers to float precision, logicals as logicals.
  for (const HeaderCard& card : header) {
    const HeaderCard* back = find_card(file.header, card.key);
    ASSERT_NE(back, nullptr) << card.key;
    if (const auto* text = std::get_if<std::string>(&card.value)) {
      EXPECT_EQ(std::get<std::string>(back->value), *text) << card.key;
    } else if (const auto* flag = std::get_if<bool>(&card.value)) {
      EXPECT_EQ(std::get<bool>(back->value), *flag) << card.key;
    } else {
      const double expected = *card_number(header, card.key);
      const auto got = card_number(file.header, card.key);
      ASSERT_TRUE(got) << card.key;
      EXPECT_NEAR(*got, expected, 1e-6 * std::abs(expected) + 1e-30) << card.key;
    }
  }
  // And exactly, with comments, as other FITS readers see them.
  const std::vector<RawCard> cards = read_fits_header_cards(path);
  ASSERT_GE(cards.size(), 5u);
  EXPECT_EQ(cards[0].key, "SIMPLE");
  EXPECT_EQ(cards[1].key, "BITPIX");
  EXPECT_EQ(cards[1].value, "16");
  EXPECT_EQ(raw_card(cards, "NAXIS1")->value, "40");
  EXPECT_EQ(raw_card(cards, "NAXIS2")->value, "24");
  for (const HeaderCard& card : header) {
    const RawCard* raw = raw_card(cards, card.key);
    ASSERT_NE(raw, nullptr) << card.key;
    EXPECT_EQ(raw->value, card_value_text(card)) << card.key;
    if (!card.comment.empty()) {
      EXPECT_EQ(card.comment.rfind(raw->comment, 0), 0u) << card.key;  // possibly cut
    }
  }
  EXPECT_EQ(raw_card(cards, "GAIN")->value, "24.4140625");  // 1e5 / 4096, all digits
  EXPECT_EQ(raw_card(cards, "GAIN")->comment, "[e-/adu] full well / 2^bits");
  EXPECT_EQ(raw_card(cards, "BUNIT")->value, "'adu'");
  EXPECT_EQ(raw_card(cards, "NADC")->value, "T");
  EXPECT_EQ(raw_card(cards, "SENSFILE")->value, "'msx-sbv.toml'");
  EXPECT_NEAR(std::stod(raw_card(cards, "LIMMAG")->value), sbv.report.value("target.magnitude").value(), 1e-15);
}

// FITS Standard 4.0 read by hand: header blocks of 2880 bytes up to END, then NAXIS1 × NAXIS2 big-endian values,
// the first stored row the bottom of the picture, the file a whole number of 2880-byte blocks. OpenImageIO 2.4
// wrote a blank first row and left the top row past the data (image_io.cpp); this is the check that catches it.
TEST(RenderFits, DataLayoutIsStandard) {
  Image image(5, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) image(x, y) = static_cast<float>(10 * y + x + 1);  // row 0 (top): 1..5
  const std::string path = temp_path("layout.fits");
  write_fits(path, image, {}, FitsPixel::float32);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.size() % 2880, 0u);
  std::size_t end = 0;
  while (bytes.compare(end, 8, "END     ") != 0) end += 80;
  const std::size_t data = (end / 2880 + 1) * 2880;
  auto value = [&](int index) {  // big-endian IEEE float
    std::uint32_t bits = 0;
    for (int b = 0; b < 4; ++b) bits = (bits << 8) | static_cast<unsigned char>(bytes[data + 4 * index + b]);
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
  };
  for (int row = 0; row < 3; ++row)  // stored row k is picture row 2 − k
    for (int x = 0; x < 5; ++x) EXPECT_EQ(value(row * 5 + x), image(x, 2 - row)) << row << "," << x;
  EXPECT_EQ(read_image(path).image.pixels, image.pixels);  // and back, top row first
}

TEST(RenderFits, FloatAndInt32Frames) {
  Image image(7, 5);
  for (std::size_t i = 0; i < image.size(); ++i) image.pixels[i] = static_cast<float>(i) * 1.25f - 3.0f;
  const Header header = {{"EXPTIME", 0.625, "[s] integration time"}, {"NBITS", std::int64_t{16}, ""}, {"FLAG", false, "a logical"}};
  EXPECT_EQ(fits_pixel_for(image), FitsPixel::float32);
  const std::string f = temp_path("float.fits");
  write_fits(f, image, header, FitsPixel::float32);
  const ImageFile back = read_image(f);
  EXPECT_EQ(back.pixel_type, "float");
  EXPECT_EQ(back.image.pixels, image.pixels);
  EXPECT_EQ(read_fits_header_cards(f)[1].value, "-32");

  Image big(3, 2);
  big.pixels = {0, 40000, 65535, 70000, 1, 2};  // beyond int16: int32
  EXPECT_EQ(fits_pixel_for(big), FitsPixel::int32);
  const std::string i32 = temp_path("int32.fits");
  write_fits(i32, big, header, FitsPixel::int32);
  EXPECT_EQ(read_image(i32).image.pixels, big.pixels);
  EXPECT_EQ(read_fits_header_cards(i32)[1].value, "32");
  EXPECT_THROW(write_fits(temp_path("bad16.fits"), big, header, FitsPixel::int16), std::invalid_argument);
}

TEST(RenderFits, CardsAreStandardFits) {
  Image image(2, 2, 1.0f);
  const std::string long_text(100, 'x');
  const Header header = {{"OBJECT", std::string("it's a test"), "quote doubled"},
                         {"LONGTEXT", long_text, "cut to 68 characters"},
                         {"SMALL", 1e-17, ""},
                         {"WHOLE", 5.0, "a real that is whole"}};
  const std::string path = temp_path("cards.fits");
  write_fits(path, image, header);
  const auto cards = read_fits_header_cards(path);
  EXPECT_EQ(raw_card(cards, "OBJECT")->value, "'it''s a test'");
  EXPECT_EQ(raw_card(cards, "LONGTEXT")->value, "'" + std::string(68, 'x') + "'");
  EXPECT_EQ(raw_card(cards, "SMALL")->value, "1E-17");
  EXPECT_EQ(raw_card(cards, "WHOLE")->value, "5.0");
  EXPECT_THROW(write_fits(path, image, {{"TOOLONGKEY", 1.0, ""}}), std::invalid_argument);
  EXPECT_THROW(write_fits(path, image, {{"BITPIX", 1.0, ""}}), std::invalid_argument);
  EXPECT_THROW(write_fits(path, image, {{"A", 1.0, ""}, {"A", 2.0, ""}}), std::invalid_argument);
}

TEST(RenderFits, PreviewsAndScenes) {
  Image ramp(32, 16);
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 32; ++x) ramp(x, y) = static_cast<float>(x);
  const std::string png = temp_path("preview.png"), tif = temp_path("preview.tif");
  write_preview(png, ramp, {Stretch::linear, 0.0, 100.0, 0.02, 2});
  const ImageFile p = read_image(png);
  EXPECT_EQ(p.pixel_type, "uint8");
  EXPECT_EQ(p.image.width, 64);
  EXPECT_EQ(p.image(0, 0), 0.0f);
  EXPECT_EQ(p.image(63, 31), 255.0f);
  write_preview(tif, ramp);
  EXPECT_EQ(read_image(tif).pixel_type, "uint16");
  EXPECT_THROW(write_preview(temp_path("preview.jpg"), ramp), std::invalid_argument);
  // 16-bit PNG reflectance maps come back normalised.
  Image map(8, 8, 0.3f);
  map(3, 4) = 0.303f;
  const std::string scene = temp_path("scene.png");
  write_png16(scene, map);
  const Image back = read_reflectance_map(scene);
  for (std::size_t i = 0; i < map.size(); ++i) EXPECT_NEAR(back.pixels[i], map.pixels[i], 0.5 / 65535.0 + 1e-7);
}

}  // namespace

namespace {
using namespace radchain::render;

std::string bytes_of(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

// The message read_image gives for `bytes` ("" when it reads them).
std::string refusal(const std::string& bytes) {
  const std::string path = temp_path("malformed.fits");
  write_bytes(path, bytes);
  try {
    (void)read_image(path);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// A card: key, "= ", value right-justified to column 30 (FITS fixed format).
std::string card(const std::string& key, const std::string& value) {
  std::string c = key + std::string(8 - key.size(), ' ') + "= " + std::string(20 - value.size(), ' ') + value;
  return c + std::string(80 - c.size(), ' ');
}

// Truncated and malformed FITS files are refused by radchain's structure check with the reason, before CFITSIO
// opens them (FITS Standard 4.0 §3.1, §4.4.1.1; CFITSIO 4.2 leaked its handle on some, found by scene_fits_fuzz):
// a size that is not a whole number of blocks, data shorter than the header declares, mandatory keywords out of
// order, an unknown BITPIX, a cube, a side beyond 16384 pixels, no END.
TEST(RenderFits, TruncatedOrMalformedFilesAreRefusedWithTheReason) {
  Image image(16, 16, 0.25f);
  const std::string good = temp_path("good.fits");
  write_fits(good, image, {}, FitsPixel::float32);
  const std::string whole = bytes_of(good);
  ASSERT_EQ(whole.size(), 2u * 2880u);  // one header block, 1024 data bytes in one block
  EXPECT_EQ(refusal(whole), "");
  EXPECT_NE(refusal(whole.substr(0, 3997)).find("3997 bytes: not a whole number of 2880-byte FITS blocks"), std::string::npos);
  EXPECT_NE(refusal(whole.substr(0, 2880)).find("2880 bytes, but its header declares 5760 (truncated)"), std::string::npos);
  EXPECT_NE(refusal("").find("0 bytes"), std::string::npos);

  auto header = [](std::vector<std::string> cards) {
    std::string h;
    for (const auto& c : cards) h += c;
    h += "END" + std::string(77, ' ');
    h.resize((h.size() + 2879) / 2880 * 2880, ' ');
    return h + std::string(2880 * 400, '\0');
  };
  const std::string simple = card("SIMPLE", "T");
  EXPECT_NE(refusal(header({simple, card("NAXIS", "2"), card("BITPIX", "16")})).find("card 2 is \"NAXIS\", expected BITPIX"),
            std::string::npos);
  EXPECT_NE(refusal(header({simple, card("BITPIX", "12"), card("NAXIS", "2"), card("NAXIS1", "4"), card("NAXIS2", "4")}))
                .find("BITPIX = 12: not a FITS pixel type"),
            std::string::npos);
  EXPECT_NE(refusal(header({simple, card("BITPIX", "8"), card("NAXIS", "3"), card("NAXIS1", "4"), card("NAXIS2", "4"),
                            card("NAXIS3", "4")}))
                .find("not a 2-D image (NAXIS = 3)"),
            std::string::npos);
  EXPECT_NE(refusal(header({simple, card("BITPIX", "8"), card("NAXIS", "2"), card("NAXIS1", "100000"), card("NAXIS2", "4")}))
                .find("NAXIS1 = 100000: 1 to 16384 pixels a side"),
            std::string::npos);
  EXPECT_NE(refusal(header({simple, card("BITPIX", "8"), card("NAXIS", "2"), card("NAXIS1", "4x"), card("NAXIS2", "4")}))
                .find("NAXIS1 is not an integer"),
            std::string::npos);
  EXPECT_NE(refusal(std::string(2880, ' ')).find("no END card"), std::string::npos);
  EXPECT_NE(refusal(header({card("BITPIX", "8")})).find("card 1 is \"BITPIX\", expected SIMPLE"), std::string::npos);
  EXPECT_NE(refusal(header({})).find("the mandatory SIMPLE card is missing"), std::string::npos);
  std::string no_end = simple + card("BITPIX", "8") + card("NAXIS", "2") + card("NAXIS1", "4") + card("NAXIS2", "4");
  no_end.resize(2880, ' ');
  EXPECT_NE(refusal(no_end).find("no END card"), std::string::npos);
  // NAXIS as large as the card allows: refused as read (no arithmetic on it; UBSan ran the old check into overflow)
  EXPECT_NE(refusal(header({simple, card("BITPIX", "8"), card("NAXIS", "9223372036854775807")})).find("not a 2-D image"),
            std::string::npos);
  EXPECT_NE(refusal(header({simple, card("BITPIX", "8"), card("NAXIS", "0")})).find("the primary HDU holds no image (NAXIS = 0)"),
            std::string::npos);
  EXPECT_NE(refusal(header({simple, card("BITPIX", "8"), card("NAXIS", "2"), card("NAXIS1", "4")}))
                .find("the mandatory NAXIS2 card is missing"),
            std::string::npos);
  // Other cards: an integer beyond 64 bits is kept as a real; a value that is no FITS value is refused with the card
  // named (std::stoll's out_of_range escaped as an internal error: scene_fits_fuzz, session 5).
  const std::vector<std::string> mandatory = {simple, card("BITPIX", "8"), card("NAXIS", "2"), card("NAXIS1", "4"), card("NAXIS2", "4")};
  auto with = [&](const std::string& extra) {
    std::vector<std::string> cards = mandatory;
    cards.push_back(extra);
    return header(cards);
  };
  const std::string path = temp_path("bigcard.fits");
  write_bytes(path, with(card("BIGINT", "99999999999999999999")));
  const ImageFile big = read_image(path);
  ASSERT_EQ(big.header.size(), 1u);
  EXPECT_EQ(std::get<double>(big.header[0].value), 1e20);
  EXPECT_NE(refusal(with(card("BAD", "12abc"))).find("card BAD: value \"12abc\" is not a FITS value"), std::string::npos);
  EXPECT_NE(refusal(with(card("HUGE", "1E999"))).find("card HUGE: value \"1E999\" is not a FITS value"), std::string::npos);
}

}  // namespace
