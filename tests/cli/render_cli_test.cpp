// `radchain render` / `validate` through the CLI: files written, exit codes, and the options checked against their
// schema (radchain/command_options.hpp) with one located line each (the rendering itself is tested in tests/imaging).
#include "cli_helpers.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include <string>

namespace {
using namespace radchain::test;

const std::string kolobrodov_file = source_dir + "/sensors/kolobrodov-1996-ccd151-computed.toml";

TEST(RenderCli, SpaceFrameWritesFitsAndPreview) {
  Scratch scratch;
  const std::string fits = (scratch / "sbv.fits").string(), png = (scratch / "sbv.png").string();
  const CliResult r = run_cli(scratch, "render '" + sbv_file + "' --focal-length \"45 cm\" --pixel-pitch \"27 um\""
                                       " --width 64 --height 64 --stars 5 --seed 3 --out " + fits + " --png " + png);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(fs::file_size(fits), 2880u);  // at least one FITS block
  EXPECT_TRUE(fs::exists(png));
}

TEST(RenderCli, EarthSceneAsFloatTiffAndBadExtension) {
  Scratch scratch;
  const std::string tif = (scratch / "scene.tif").string();
  const CliResult r = run_cli(scratch, "render '" + kolobrodov_file + "' --out " + tif);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(fs::file_size(tif), 10000u);  // a 256×256 float32 scene at the designed 5 m GSD (compressed)
  EXPECT_EQ(run_cli(scratch, "render '" + kolobrodov_file + "' --out " + (scratch / "x.jpg").string()).exit_code, 2);
}

// A real imager with a datasheet detector and an MTF budget: the scene in electrons through the
// budget, the detector's ADC; validate measures the budget on an edge and the chain's SNR on a flat field.
TEST(RenderCli, DatasheetImagerRendersAndValidates) {
  Scratch scratch;
  const std::string s2 = source_dir + "/sensors/sentinel-2a-msi-b4.toml", fits = (scratch / "s2.fits").string();
  const CliResult r = run_cli(scratch, "render '" + s2 + "' --out " + fits);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("optics MTF budget"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("e- per unit reflectance"), std::string::npos) << r.out;
  EXPECT_GT(fs::file_size(fits), 2880u);
  const CliResult v = run_cli(scratch, "validate '" + s2 + "' --size 128");
  EXPECT_EQ(v.exit_code, 0) << v.out << v.err;
  EXPECT_NE(v.out.find("ok   flat field at the scene's reflectance"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("ok   edge MTF"), std::string::npos) << v.out;
  // A binned, co-added detector is drawn as its native reads summed, and validates against its own chain.
  const std::string binned = " --set detector.binning=2 --set detector.exposures=3";
  const CliResult b = run_cli(scratch, "render '" + s2 + "'" + binned + " --out " + (scratch / "b.fits").string());
  EXPECT_EQ(b.exit_code, 0) << b.err;
  EXPECT_NE(b.out.find("each output pixel sums 2×2 native pixels over 3 frames"), std::string::npos) << b.out;
  const CliResult bv = run_cli(scratch, "validate '" + s2 + "'" + binned + " --size 128");
  EXPECT_EQ(bv.exit_code, 0) << bv.out << bv.err;
  EXPECT_NE(bv.out.find("ok   flat field at the scene's reflectance"), std::string::npos) << bv.out;
  // More native reads than can be drawn: one located line, exit 2, nothing written.
  const CliResult big = run_cli(scratch, "render '" + s2 + "' --set detector.exposures=100000 --out " + (scratch / "big.fits").string());
  EXPECT_EQ(big.exit_code, 2);
  EXPECT_NE(big.err.find("native reads"), std::string::npos) << big.err;
  EXPECT_EQ(std::count(big.err.begin(), big.err.end(), '\n'), 1) << big.err;
  EXPECT_FALSE(fs::exists(scratch / "big.fits"));
  // An output sampling 5000 detector samples wide (a unit slip), refused, not an empty image; so are one of 1e-300 m
  // (an image of NaN) and a map a thousand times finer than the output.
  const CliResult tiny = run_cli(scratch, "render '" + s2 + "' --set detector.binning=2 --gsd '100 km' --scene-sampling '1 m' --out " +
                                              (scratch / "tiny.fits").string());
  EXPECT_EQ(tiny.exit_code, 2) << tiny.err;
  EXPECT_NE(tiny.err.find("output sampling: 1e+05 m is not within a factor 1000 of the detector sample's 19.65 m"),
            std::string::npos) << tiny.err;
  EXPECT_FALSE(fs::exists(scratch / "tiny.fits"));
  const CliResult fine = run_cli(scratch, "render '" + s2 + "' --gsd '1e-300 m' --out " + (scratch / "fine.fits").string());
  EXPECT_EQ(fine.exit_code, 2) << fine.err;
  EXPECT_NE(fine.err.find("output sampling: 1e-300 m is not within a factor 1000"), std::string::npos) << fine.err;
  const CliResult map = run_cli(scratch, "render '" + s2 + "' --gsd '9 km' --scene-sampling '1 m' --out " + (scratch / "map.fits").string());
  EXPECT_EQ(map.exit_code, 2) << map.err;
  EXPECT_NE(map.err.find("input sampling: 1 m is not within a factor 1000 of the output sampling 9000 m"), std::string::npos)
      << map.err;
  // A PSF far wider than the scene (a wavelength in mm) would pad the FFT grid to 24 GB: refused before allocating.
  const CliResult wide = run_cli(scratch, "render '" + s2 + "' --wavelength '2276 um' --out " + (scratch / "wide.fits").string());
  EXPECT_EQ(wide.exit_code, 2) << wide.err;
  EXPECT_EQ(std::count(wide.err.begin(), wide.err.end(), '\n'), 1) << wide.err;
  EXPECT_NE(wide.err.find("wavelength: the PSF at 2276 um reaches"), std::string::npos) << wide.err;
  for (const char* name : {"fine.fits", "map.fits", "wide.fits"}) EXPECT_FALSE(fs::exists(scratch / name)) << name;
}

// A sky (with the dark current) that fills the well saturates every pixel: no frame, exit 2 (1e19 e- wrote a
// black frame, 1e12 e- was an internal error); a typed "nan" magnitude is not "limit".
TEST(RenderCli, AbsurdFrameRequestsAreBadInput) {
  Scratch scratch;
  for (const char* sky : {"1e5 e-", "1e12 e-", "1e19 e-"}) {
    const CliResult r = run_cli(scratch, "render '" + sbv_file + "' --sky '" + sky + "' --out " + (scratch / "sky.fits").string());
    EXPECT_EQ(r.exit_code, 2) << sky << r.err;
    EXPECT_NE(r.err.find("of sky and dark current per pixel fill the 1e+05 e- well: every pixel saturates"), std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(scratch / "sky.fits"));
  }
  const CliResult below = run_cli(scratch, "render '" + sbv_file + "' --sky '5e4 e-' --out " + (scratch / "half.fits").string());
  EXPECT_EQ(below.exit_code, 0) << below.err;
  for (const char* target : {"10,10,nan", "inf", "10,10,-inf"}) {
    const CliResult r = run_cli(scratch, "render '" + sbv_file + "' --target '" + target + "' --out " + (scratch / "t.fits").string());
    EXPECT_EQ(r.exit_code, 2) << target << r.err;
    EXPECT_NE(r.err.find("--target: " + std::string(target) + ": expected x,y,magnitude"), std::string::npos) << r.err;
  }
  // A pixel of 33 zm (a unit slip) made a Gaussian PSF 6e14 pixels wide: refused, not an overflowing stamp.
  for (const char* pitch : {"33 zm", "2 cm"}) {
    const CliResult r = run_cli(scratch, "render '" + sbv_file + "' --psf gaussian --psf-fwhm '20 um' --pixel-pitch '" + pitch +
                                             "' --out " + (scratch / "p.fits").string());
    EXPECT_EQ(r.exit_code, 2) << pitch << r.err;
    EXPECT_NE(r.err.find("pixel pitch: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("a detector pixel lies between 0.1 um and 10 mm"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(scratch / "p.fits"));
  }
}

// Each bad option value: exit 2, nothing on stdout, exactly this one line on stderr.
struct BadOption {
  std::string arguments, message;
};

// PSF-weighted photometry (emva1288 photometry = "psf", the Rubin files): validate measures the matched filter on a
// still target, not a square window that holds only part of the image (it reported FAIL on every Rubin file).
TEST(RenderCli, PsfPhotometryValidatesWithTheMatchedFilter) {
  Scratch scratch;
  const CliResult v = run_cli(scratch, "validate '" + source_dir + "/sensors/rubin-lsst-r-m5.toml' --trials 2000 --size 64");
  EXPECT_EQ(v.exit_code, 0) << v.out << v.err;
  EXPECT_NE(v.out.find("PSF-weighted photometry at the limiting magnitude"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("ok   matched-filter SNR"), std::string::npos) << v.out;
  EXPECT_EQ(v.out.find("window signal"), std::string::npos) << v.out;
  // The bundled 30 s GEO streak (2255 pixels, wider than the default frame) validates on its widened frame.
  const CliResult streak = run_cli(scratch, "validate '" + source_dir + "/examples/rubin-geo-streak.toml' --trials 100 --size 64");
  EXPECT_EQ(streak.exit_code, 0) << streak.out << streak.err;
  EXPECT_NE(streak.out.find("streak of 2255"), std::string::npos) << streak.out;
  // A faint frame (Roman F062 at magnitude 25: 4.3 e- under 5 e- read noise, 1 DN/e-, a 1×1 window) without an ADC
  // pedestal clips its noise at 0 DN: the checks fail and say why; with --offset they pass.
  const std::string roman = "validate '" + source_dir + "/sensors/roman-wfi-f062-zero-point.toml' --trials 2000 --size 64";
  const CliResult clipped = run_cli(scratch, roman);
  EXPECT_EQ(clipped.exit_code, 1) << clipped.out << clipped.err;
  EXPECT_NE(clipped.out.find("note: the rendered frames have no ADC pedestal"), std::string::npos) << clipped.out;
  const CliResult pedestal = run_cli(scratch, roman + " --offset 100");
  EXPECT_EQ(pedestal.exit_code, 0) << pedestal.out << pedestal.err;
  // An Airy core sampled at 0.69 λN (Gaia's 10 µm along-scan pixel at 0.6 µm, f/36.4): the chain's n_eff is the
  // pixel-sampled Airy pattern's (physics::airy_noise_equivalent_area_px), which the renderer's FFT-built frame
  // measures independently (it was the Gaussian of the same FWHM before: 12.5 against the frame's 14.6).
  const CliResult airy = run_cli(scratch, "validate '" + source_dir + "/sensors/gaia-g-zero-point.toml' --trials 2000 "
                                          "--set optics.psf=airy --set 'optics.psf_wavelength=0.6 um' --set detector.photometry=psf --offset 100");
  EXPECT_EQ(airy.exit_code, 0) << airy.out << airy.err;
  EXPECT_NE(airy.out.find("n_eff 14.6 px rendered, 14.6 chain"), std::string::npos) << airy.out;
}

// A scene file that cannot be read (not an image, a truncated FITS, missing) is input refused at --scene: one
// line, exit 2, no output — not an internal error.
TEST(RenderCli, UnreadableSceneIsBadInput) {
  Scratch scratch;
  const std::string fits = (scratch / "garbage.fits").string(), png = (scratch / "garbage.png").string();
  write_text(fits, "SIMPLE  =                    T   but nothing a FITS reader can use");
  write_text(png, "not a PNG");
  for (const std::string& scene : {fits, png, (scratch / "missing.png").string()}) {
    const std::string out = (scratch / "scene.fits").string();
    const CliResult r = run_cli(scratch, "render '" + kolobrodov_file + "' --scene '" + scene +
                                             "' --scene-sampling \"1 m\" --out '" + out + "'");
    EXPECT_EQ(r.exit_code, 2) << scene << ": " << r.err;
    EXPECT_EQ(count_lines(r.err), 1u) << r.err;
    EXPECT_EQ(r.err.rfind("--scene: " + scene + ": cannot read", 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
}

TEST(RenderCli, OptionValuesAreValidatedByTheirSchema) {
  Scratch scratch;
  const std::vector<BadOption> cases = {
      {"render '" + sbv_file + "' --width 0", "radchain render: --width = 0: out of range: accepted in [1, 16384]"},
      {"render '" + sbv_file + "' --height 100000", "radchain render: --height = 100000: out of range: accepted in [1, 16384]"},
      {"render '" + sbv_file + "' --focal-length 45",
       "radchain render: --focal-length = 45: a bare number has no unit: expected a length, e.g. \"45 cm\""},
      {"render '" + sbv_file + "' --pixel-pitch '27 s'",
       "radchain render: --pixel-pitch = \"27 s\": expected a length, e.g. \"27 um\""},
      {"render '" + sbv_file + "' --psf airi",
       "radchain render: --psf = \"airi\": expected one of pixel, airy, gaussian (did you mean \"airy\"?)"},
      {"render '" + sbv_file + "' --no-noise shot,drak",
       "radchain render: --no-noise = [\"shot\", \"drak\"]: expected one of shot, dark, read, saturation, adc, all (did you mean \"dark\"?)"},
      {"render '" + sbv_file + "' --obscuration 1", "radchain render: --obscuration = 1: out of range: accepted in [0, 1)"},
      {"render '" + sbv_file + "' --upscale 17", "radchain render: --upscale = 17: out of range: accepted in [1, 16]"},
      {"render '" + kolobrodov_file + "' --optics-mtf eq8",
       "radchain render: --optics-mtf = \"eq8\": expected one of auto, budget, diffraction, eq7, none (did you mean \"eq7\"?)"},
      {"validate '" + sbv_file + "' --trials 10", "radchain validate: --trials = 10: out of range: accepted in [100, 1e+08]"},
      {"validate '" + sbv_file + "' --max-z -1", "radchain validate: --max-z = -1: out of range: accepted > 0"},
  };
  for (const auto& c : cases) {
    const CliResult r = run_cli(scratch, c.arguments);
    EXPECT_EQ(r.exit_code, 2) << c.arguments;
    EXPECT_EQ(r.out, "") << c.arguments;
    EXPECT_EQ(r.err, c.message + "\n") << c.arguments;
  }
}

TEST(RenderCli, DescribeListsTheOptionsOfRenderAndValidate) {
  Scratch scratch;
  const CliResult render = run_cli(scratch, "describe render");
  ASSERT_EQ(render.exit_code, 0) << render.err;
  EXPECT_NE(render.out.find("--focal-length     quantity [m]"), std::string::npos) << render.out;
  EXPECT_NE(render.out.find("accepted: in [1, 16384]"), std::string::npos) << render.out;
  const CliResult validate = run_cli(scratch, "describe validate");
  ASSERT_EQ(validate.exit_code, 0) << validate.err;
  EXPECT_NE(validate.out.find("--trials"), std::string::npos) << validate.out;
  EXPECT_EQ(validate.out.find("--stretch"), std::string::npos) << validate.out;  // render's only
}

}  // namespace
