// CSV spectra (framework/core/include/radchain/spectrum_csv.hpp): every file shipped in spectra/ loads with the unit
// its header states, a few reference values (ASTM E-490 solar constant, CIE V(λ) peak, Vega at 5556 Å), and one
// test per malformed-file rule: each throws InputError naming the file and the offending line.
#include "radchain/error.hpp"
#include "radchain/spectrum_csv.hpp"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace {
namespace fs = std::filesystem;
using namespace radchain;

const std::string spectra_dir = std::string(RADCHAIN_SOURCE_DIR) + "/spectra/";

struct Shipped {
  const char* file;
  const char* si_unit;
};

// The unit each shipped file is read in: dimensional files carry it in the header, relative ones are "1".
const Shipped shipped[] = {
    {"am0_astm_e490_00a.csv", "W m-2 m-1"},
    {"am0_wehrli_1985.csv", "W m-2 m-1"},
    {"atmosphere_modtran_cerro_pachon_airmass1.0.csv", "1"},
    {"ccd_back_illuminated_hamamatsu_S10420-01_qe.csv", "1"},
    {"ccd_back_illuminated_lsst_e2v_qe.csv", "1"},
    {"ccd_front_illuminated_fairchild_relative.csv", "1"},
    {"cie_1924_photopic_V_1nm.csv", "1"},
    {"cie_illuminant_A_1nm.csv", "1"},
    {"cmos_sony_imx428_mono_qe.csv", "1"},
    {"johnson_V_mann_vonbraun_2015.csv", "1"},
    {"johnson_V_stsci_cdbs_johnson_v_004.csv", "1"},
    {"si_absorption_green2008.csv", "m-1"},
    {"vega_alpha_lyr_stis_002.csv", "W m-2 m-1"},
    {"johnson_cousins_B_bessell1990.csv", "1"},
    {"johnson_cousins_V_bessell1990.csv", "1"},
    {"johnson_cousins_R_bessell1990.csv", "1"},
    {"johnson_cousins_I_bessell1990.csv", "1"},
    {"gaia_dr3_G.csv", "1"},
    {"gaia_dr3_BP.csv", "1"},
    {"gaia_dr3_RP.csv", "1"},
    {"sdss_g_doi2010.csv", "1"},
    {"sdss_r_doi2010.csv", "1"},
    {"sdss_i_doi2010.csv", "1"},
    {"lsst_hardware_r_throughputs1.9.csv", "1"},
    {"lsst_atmos_10_throughputs1.9.csv", "1"},
    {"lsst_hardware_g_throughputs1.9.csv", "1"},
    {"lsst_hardware_i_throughputs1.9.csv", "1"},
    {"lsst_atmos_10_300-1150nm_throughputs1.9.csv", "1"},
    {"lsst_hardware_u_throughputs1.9.csv", "1"},
    {"lsst_hardware_z_throughputs1.9.csv", "1"},
    {"lsst_hardware_y_throughputs1.9.csv", "1"},
    {"lsst_m1_throughputs1.9.csv", "1"},
    {"lsst_m2_throughputs1.9.csv", "1"},
    {"lsst_m3_throughputs1.9.csv", "1"},
    {"lsst_lens1_throughputs1.9.csv", "1"},
    {"lsst_lens2_throughputs1.9.csv", "1"},
    {"lsst_lens3_throughputs1.9.csv", "1"},
    {"lsst_filter_r_throughputs1.9.csv", "1"},
    {"lsst_detector_throughputs1.9.csv", "1"},
    {"lsst_darksky_throughputs1.9.csv", "W m-2 sr-1 m-1"},
    {"tess_response_v2.0.csv", "1"},
    {"lsst_atmos_aerosol_X10_throughputs1.9.csv", "1"},
    {"lsst_atmos_aerosol_X15_throughputs1.9.csv", "1"},
    {"lsst_atmos_aerosol_X20_throughputs1.9.csv", "1"},
    {"lsst_atmos_aerosol_X25_throughputs1.9.csv", "1"},
    {"swift_uvot_v_throughput.csv", "1"},
    {"swift_uvot_b_throughput.csv", "1"},
    {"swift_uvot_u_throughput.csv", "1"},
    {"swift_uvot_uvw1_throughput.csv", "1"},
    {"galex_fuv_throughput.csv", "1"},
    {"galex_nuv_throughput.csv", "1"},
    {"roman_wfi_sca01_f062_throughput.csv", "1"},
    {"roman_wfi_sca01_f158_throughput.csv", "1"},
    // Peer cases (validation/): synphot's test data and analytic spectra, m4opt's bandpasses and zodiacal spectrum.
    {"synphot_box_5500A_width1A.csv", "1"},
    {"synphot_gaussian_em_5500A_fwhm250A.csv", "W m-2 m-1"},
    {"synphot_grw_70d5824_stisnic_005.csv", "W m-2 m-1"},
    {"synphot_hst_acs_hrc_f555w.csv", "1"},
    {"synphot_powerlaw_6000A_alpha4.csv", "W m-2 m-1"},
    {"m4opt_stis_zodi_high.csv", "W m-2 m-1 sr-1"},
    {"m4opt_ultrasat_nuv_gaussian.csv", "1"},
    {"m4opt_uvex_fuv_gaussian.csv", "1"},
    {"m4opt_uvex_nuv_gaussian.csv", "1"},
    {"instrupy_blackbody_290K_radiance.csv", "W m-2 sr-1 m-1"},
    {"instrupy_blackbody_291K_radiance.csv", "W m-2 sr-1 m-1"},
    {"instrupy_unit_transmittance.csv", "1"},
};

TEST(SpectrumCsv, EveryShippedFileLoadsInItsUnit) {
  std::size_t count = 0;
  for (const auto& entry : fs::directory_iterator(spectra_dir))
    if (entry.path().extension() == ".csv") ++count;
  EXPECT_EQ(count, std::size(shipped)) << "a spectrum was added to spectra/: list it here with its unit";
  for (const Shipped& s : shipped) {
    SCOPED_TRACE(s.file);
    const SpectrumFile f = load_spectrum_csv(spectra_dir + s.file, s.si_unit);
    EXPECT_EQ(f.spectrum.unit(), s.si_unit);
    // (A measured table has many points; synphot's 1 Å box and a constant transmittance have their two.)
    const bool analytic = s.file == std::string("synphot_box_5500A_width1A.csv") || s.file == std::string("instrupy_unit_transmittance.csv");
    EXPECT_GT(f.spectrum.size(), analytic ? 1 : 8);
    EXPECT_FALSE(f.provenance.empty());
    // Every shipped grid lies between 10 nm (a constant's first node, where the flat SEDs start) and 1 mm (i.e. it
    // was converted from nm to metres).
    EXPECT_GE(f.spectrum.min_wavelength_m(), 10e-9);
    EXPECT_LT(f.spectrum.max_wavelength_m(), 1.0001e-3);
    EXPECT_GE(f.spectrum.value().minCoeff(), 0.0);
  }
}

TEST(SpectrumCsv, RelativeFilesRefuseADimensionalReading) {
  // A relative column has no unit: read as spectral irradiance it must be refused, not silently scaled.
  EXPECT_THROW(load_spectrum_csv(spectra_dir + "cie_1924_photopic_V_1nm.csv", "W m-2 m-1"), InputError);
  // A dimensional column is not relative.
  EXPECT_THROW(load_spectrum_csv(spectra_dir + "am0_astm_e490_00a.csv", "1"), InputError);
}

TEST(SpectrumCsv, Astm490SolarConstant) {
  // ASTM E-490-00a: trapezoid integral over the whole table 1366.09 W m^-2 (file header; standard: 1366.1).
  const SpectrumFile f = load_spectrum_csv(spectra_dir + "am0_astm_e490_00a.csv", "W m-2 m-1");
  EXPECT_EQ(f.value_column, "spectral_irradiance_W_m-2_nm-1");
  EXPECT_NEAR(f.spectrum.integral(), 1366.09, 1366.09 * 1e-3);
  EXPECT_NEAR(f.spectrum.integral(), 1366.09, 0.005);  // the header's figure, to its last digit
  EXPECT_NEAR(f.spectrum.min_wavelength_m(), 119.5e-9, 1e-18);
  EXPECT_NEAR(f.spectrum.max_wavelength_m(), 1e-3, 1e-12);
  // 1697 data rows (file header).
  EXPECT_EQ(f.spectrum.size(), 1697);
  // First row 119.5 nm, 6.19e-5 W m^-2 nm^-1 = 6.19e4 W m^-2 m^-1.
  EXPECT_NEAR(f.spectrum.value()(0), 6.19e4, 6.19e4 * 1e-14);
}

TEST(SpectrumCsv, Wehrli1985Integral) {
  const SpectrumFile f = load_spectrum_csv(spectra_dir + "am0_wehrli_1985.csv", "W m-2 m-1");
  EXPECT_NEAR(f.spectrum.integral(), 1365.2, 0.05);  // file header: 1365.2 W m^-2 over the tabulated range
}

TEST(SpectrumCsv, CiePhotopicPeak) {
  // CIE 1924 V(λ): maximum 1 at 555 nm.
  const SpectrumFile f = load_spectrum_csv(spectra_dir + "cie_1924_photopic_V_1nm.csv", "1");
  EXPECT_EQ(f.spectrum.peak_value(), 1.0);
  EXPECT_NEAR(f.spectrum.peak_wavelength_m(), 555e-9, 1e-15);
  EXPECT_EQ(f.spectrum(555e-9), 1.0);
  EXPECT_EQ(f.spectrum.size(), 471);
  EXPECT_NEAR(f.spectrum.min_wavelength_m(), 360e-9, 1e-18);
  EXPECT_NEAR(f.spectrum.max_wavelength_m(), 830e-9, 1e-18);
}

TEST(SpectrumCsv, VegaAt5556Angstrom) {
  // Vega F_λ(555.6 nm) = 3.44e-9 erg s^-1 cm^-2 Å^-1 (Hayes 1985) = 3.44e-2 W m^-2 m^-1; the STIS CALSPEC
  // spectrum agrees within ~1 %. Tolerance 3 %.
  const SpectrumFile f = load_spectrum_csv(spectra_dir + "vega_alpha_lyr_stis_002.csv", "W m-2 m-1");
  EXPECT_NEAR(f.spectrum(555.6e-9), 3.44e-2, 3.44e-2 * 0.03);
}

TEST(SpectrumCsv, PerCentimetreColumn) {
  // alpha_per_cm is read as 1/(cm): the first row, 1.84e6 cm^-1 at 250 nm, is 1.84e8 m^-1.
  const SpectrumFile f = load_spectrum_csv(spectra_dir + "si_absorption_green2008.csv", "m-1");
  EXPECT_NEAR(f.spectrum.min_wavelength_m(), 250e-9, 1e-21);
  EXPECT_NEAR(f.spectrum.value()(0), 1.84e8, 1.84e8 * 1e-14);
}

TEST(SpectrumCsv, CachedIsReadOnce) {
  const std::string path = spectra_dir + "cie_1924_photopic_V_1nm.csv";
  const SpectrumFile& a = cached_spectrum_csv(path, "1");
  const SpectrumFile& b = cached_spectrum_csv(path, "1");
  EXPECT_EQ(&a, &b);
  const SpectrumFile& clamped = cached_spectrum_csv(path, "1", Extrapolation::clamp);
  EXPECT_NE(&a, &clamped);
  EXPECT_EQ(clamped.spectrum(1e-6), a.spectrum.value()(a.spectrum.size() - 1));
}

// Malformed files, written to a temporary folder.
class SpectrumCsvFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("radchain_csv_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path path = dir_ / name;
    std::ofstream(path) << text;
    return path.string();
  }
  // Loads and returns the error; fails the test when none is thrown.
  static std::string error_of(const std::string& path, const std::string& si_unit) {
    try {
      load_spectrum_csv(path, si_unit);
    } catch (const InputError& error) {
      EXPECT_EQ(error.where().file, path);
      return error.what();
    }
    ADD_FAILURE() << path << " loaded without error";
    return {};
  }
  // what() starts with "<path>:<line>: spectrum file: " and mentions `words`.
  static void expect_error(const std::string& path, int line, const std::string& si_unit, const std::string& words) {
    const std::string what = error_of(path, si_unit);
    const std::string prefix = path + ":" + std::to_string(line) + ": spectrum file: ";
    EXPECT_EQ(what.substr(0, prefix.size()), prefix) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
  fs::path dir_;
};

TEST_F(SpectrumCsvFile, ConvertsUnitsOfBothColumns) {
  const std::string path = write("um.csv",
                                 "# made up for a test, with a comma\n"
                                 "wavelength_um,spectral_irradiance_W_m-2_um-1\n"
                                 "0.5,1000\n"
                                 "0.6,2000\n");
  const SpectrumFile f = load_spectrum_csv(path, "W m-2 m-1");
  EXPECT_EQ(f.provenance, "# made up for a test, with a comma\n");
  EXPECT_EQ(f.value_column, "spectral_irradiance_W_m-2_um-1");
  EXPECT_NEAR(f.spectrum.min_wavelength_m(), 5e-7, 1e-21);
  EXPECT_NEAR(f.spectrum.value()(1), 2e9, 2e9 * 1e-15);  // 2000 W m^-2 µm^-1
  EXPECT_NEAR(f.spectrum.integral(), 0.1e-6 * 1.5e9, 1e-9);
}

TEST_F(SpectrumCsvFile, MissingFile) {
  const std::string path = (dir_ / "not_there.csv").string();
  const std::string what = error_of(path, "1");
  EXPECT_EQ(what, path + ": spectrum file: cannot be read (missing file or no permission)");  // no line to name
}

TEST_F(SpectrumCsvFile, NoProvenanceComment) {
  expect_error(write("a.csv", "wavelength_nm,transmittance\n300,1\n400,1\n"), 1, "1", "no provenance");
}

TEST_F(SpectrumCsvFile, NoUnitHeader) {
  expect_error(write("a.csv", "# test\nwavelength,transmittance\n300,1\n400,1\n"), 2, "1",
               "no unit header: the first column must be named wavelength_<unit>");
  expect_error(write("b.csv", "# test\n300,1\n400,1\n"), 2, "1", "no unit header");
}

TEST_F(SpectrumCsvFile, WavelengthUnitIsNotALength) {
  expect_error(write("a.csv", "# test\nwavelength_s,transmittance\n300,1\n400,1\n"), 2, "1",
               "wavelength column unit \"s\" is not a length");
}

TEST_F(SpectrumCsvFile, DimensionalExpectedButNoUnitInHeader) {
  expect_error(write("a.csv", "# test\n# more\nwavelength_nm,spectral_irradiance\n300,1\n400,1\n"), 3, "W m-2 m-1",
               "no unit in the header's value column \"spectral_irradiance\": expected a spectral irradiance");
}

TEST_F(SpectrumCsvFile, WrongDimension) {
  // An irradiance (W m^-2) where a spectral irradiance (W m^-2 m^-1) is needed.
  expect_error(write("a.csv", "# test\nwavelength_nm,irradiance_W_m-2\n300,1\n400,1\n"), 2, "W m-2 m-1",
               "value column \"irradiance_W_m-2\" is in W m-2: expected a spectral irradiance");
  // A relative quantity must not carry a dimensional unit.
  expect_error(write("b.csv", "# test\nwavelength_nm,quantum_efficiency_W\n300,1\n400,1\n"), 2, "1",
               "expected a dimensionless number");
}

TEST_F(SpectrumCsvFile, NonMonotonicWavelength) {
  expect_error(write("a.csv", "# test\nwavelength_nm,transmittance\n300,1\n400,1\n350,1\n"), 5, "1",
               "wavelengths must be strictly increasing (350 follows a larger or equal one)");
  expect_error(write("b.csv", "# test\nwavelength_nm,transmittance\n300,1\n400,1\n400,1\n"), 5, "1",
               "strictly increasing");
}

TEST_F(SpectrumCsvFile, NonNumericRow) {
  expect_error(write("a.csv", "# test\nwavelength_nm,transmittance\n300,1\n400,abc\n500,1\n"), 4, "1",
               "\"400,abc\" is not two numbers");
  expect_error(write("b.csv", "# test\nwavelength_nm,transmittance\n300,1\n400 nm,1\n"), 4, "1", "is not two numbers");
  expect_error(write("c.csv", "# test\nwavelength_nm,transmittance\n300,1\n400,nan\n"), 4, "1", "non-finite");
}

TEST_F(SpectrumCsvFile, OtherLayoutRules) {
  expect_error(write("a.csv", "# test\nwavelength_nm,transmittance\n300,1,2\n"), 3, "1",
               "expected 2 comma-separated columns, found 3");
  expect_error(write("b.csv", "# test\nwavelength_nm,transmittance\n300,1\n\n400,1\n"), 4, "1", "blank line");
  expect_error(write("c.csv", "# test\nwavelength_nm,transmittance\n300,1\n# late\n400,1\n"), 4, "1",
               "comment after the header line");
  expect_error(write("d.csv", "# test\nwavelength_nm,transmittance\n300,1\n"), 3, "1", "fewer than 2 data rows");
  expect_error(write("e.csv", "# only a comment\n"), 1, "1", "no header line");
}

}  // namespace
