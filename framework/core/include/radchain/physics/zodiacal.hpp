#pragma once
// Zodiacal light seen from near the Earth (1 AU), from Leinert et al. 1998, "The 1997 reference of diffuse night
// sky brightness", A&AS 127, 1, Table 17: the brightness at 500 nm versus helioecliptic longitude λ − λ⊙
// (0-180°) and ecliptic latitude β (0-90°), in 10⁻⁸ W m⁻² sr⁻¹ µm⁻¹. The table here is the one shipped by
// EXOSIMS (github.com/dsavransky/EXOSIMS @ e04cd29e182f9d7c35ebe7d1920b3f7f0fd2b640 :
// EXOSIMS/ZodiacalLight/Leinert98_table17.txt, BSD-3-Clause; grid in EXOSIMS/Prototypes/ZodiacalLight.py
// load_zodi_spatial_data), copied; its 1e6 entries mark where Leinert gives no value (too near the Sun).
// Units: S10 (one V = 10 solar-type star per square degree) is 1.28e-8 W m⁻² sr⁻¹ µm⁻¹ at 500 nm (Leinert
// 1998 §2.1), so the ecliptic pole's 77e-8 is 60 S10, i.e. V = 10 + 2.5 lg(3600²) − 2.5 lg 60 = 23.3 mag/arcsec².
#include <array>
#include <cmath>
#include <optional>

namespace radchain::physics {

inline constexpr std::array<double, 19> leinert_longitudes_deg = {0,  5,  10, 15, 20,  25,  30,  35,  40, 45,
                                                                  60, 75, 90, 105, 120, 135, 150, 165, 180};
inline constexpr std::array<double, 11> leinert_latitudes_deg = {0, 5, 10, 15, 20, 25, 30, 45, 60, 75, 90};
inline constexpr double leinert_no_value = 1e6;
// Rows: λ − λ⊙ as above; columns: β as above; 10⁻⁸ W m⁻² sr⁻¹ µm⁻¹ at 500 nm.
inline constexpr double leinert_table17[19][11] = {
    {1e6, 1e6, 1e6, 3140, 1610, 985, 640, 275, 150, 100, 77},
    {1e6, 1e6, 1e6, 2940, 1540, 945, 625, 271, 150, 100, 77},
    {1e6, 1e6, 4740, 2470, 1370, 865, 590, 264, 148, 100, 77},
    {11500, 6780, 3440, 1860, 1110, 755, 525, 251, 146, 100, 77},
    {6400, 4480, 2410, 1410, 910, 635, 454, 237, 141, 99, 77},
    {3840, 2830, 1730, 1100, 749, 545, 410, 223, 136, 97, 77},
    {2480, 1870, 1220, 845, 615, 467, 365, 207, 131, 95, 77},
    {1650, 1270, 910, 680, 510, 397, 320, 193, 125, 93, 77},
    {1180, 940, 700, 530, 416, 338, 282, 179, 120, 92, 77},
    {910, 730, 555, 442, 356, 292, 250, 166, 116, 90, 77},
    {505, 442, 352, 292, 243, 209, 183, 134, 104, 86, 77},
    {338, 317, 269, 227, 196, 172, 151, 116, 93, 82, 77},
    {259, 251, 225, 193, 166, 147, 132, 104, 86, 79, 77},
    {212, 210, 197, 170, 150, 133, 119, 96, 82, 77, 77},
    {188, 186, 177, 154, 138, 125, 113, 90, 77, 74, 77},
    {179, 178, 166, 147, 134, 122, 110, 90, 77, 73, 77},
    {179, 178, 165, 148, 137, 127, 116, 96, 79, 72, 77},
    {196, 192, 179, 165, 151, 141, 131, 104, 82, 72, 77},
    {230, 212, 195, 178, 163, 148, 134, 105, 83, 72, 77},
};

// 1 S10 in W m⁻² sr⁻¹ m⁻¹ at 500 nm (Leinert et al. 1998 §2.1: 1.28e-8 W m⁻² sr⁻¹ µm⁻¹).
inline constexpr double s10_W_m2_sr_m = 1.28e-8 * 1e6;

// Surface brightness in mag/arcsec² of `s10` S10 units: one 10th-magnitude star per deg² = (3600)² arcsec².
inline double s10_to_mag_per_arcsec2(double s10) { return 10.0 + 2.5 * std::log10(3600.0 * 3600.0) - 2.5 * std::log10(s10); }

// Leinert Table 17 at (λ − λ⊙, β) in degrees, bilinear between the grid nodes, in W m⁻² sr⁻¹ m⁻¹ at 500 nm.
// Longitude folded into 0-180° (the table is symmetric about the Sun-antisun line), latitude |β|. Empty where a
// node needed is one Leinert gives no value for (within ~15-30° of the Sun).
inline std::optional<double> leinert_zodiacal_radiance_500nm(double helioecliptic_longitude_deg, double latitude_deg) {
  double lon = std::fmod(std::fabs(helioecliptic_longitude_deg), 360.0);
  if (lon > 180.0) lon = 360.0 - lon;
  const double lat = std::fabs(latitude_deg);
  if (lat > 90.0) return std::nullopt;
  auto cell = [](const auto& grid, double x) {
    std::size_t i = 0;
    while (i + 2 < grid.size() && x > grid[i + 1]) ++i;
    return i;
  };
  const std::size_t i = cell(leinert_longitudes_deg, lon), j = cell(leinert_latitudes_deg, lat);
  const double u = (lon - leinert_longitudes_deg[i]) / (leinert_longitudes_deg[i + 1] - leinert_longitudes_deg[i]);
  const double v = (lat - leinert_latitudes_deg[j]) / (leinert_latitudes_deg[j + 1] - leinert_latitudes_deg[j]);
  double sum = 0;
  for (int di = 0; di < 2; ++di)
    for (int dj = 0; dj < 2; ++dj) {
      const double w = (di ? u : 1 - u) * (dj ? v : 1 - v);
      const double value = leinert_table17[i + di][j + dj];
      if (w > 0 && value >= leinert_no_value) return std::nullopt;
      sum += w * value;
    }
  return sum * 1e-8 * 1e6;  // 10⁻⁸ W m⁻² sr⁻¹ µm⁻¹ → W m⁻² sr⁻¹ m⁻¹
}

}  // namespace radchain::physics
