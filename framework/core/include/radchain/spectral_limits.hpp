#pragma once
// One rule for every table a band crosses (an SED, a source's spectrum, an atmosphere's transmittance table, an
// optics transmittance curve, a QE curve): past an end where the table has fallen to 0 (a filter's or a QE curve's
// edge, measured down to nothing) it is 0, as the table itself says; past an end where it has not, nothing is known,
// and a band that reaches there is refused by the table's name. Counting 0 there would report a fraction of the
// light as all of it, with no sign of the loss.
#include "radchain/light.hpp"
#include "radchain/schema.hpp"

#include <string>
#include <string_view>

namespace radchain {

// "470.0-700.0 nm": a wavelength range as messages show it.
std::string nm_range(double lo_m, double hi_m);
std::string nm_range(const Spectrum& s);

// Records that the stage of `params` multiplied its table `key` (a spectrum parameter) into the light. A table
// that holds its end values beyond its grid (clamp extrapolation) limits nothing and is not recorded.
void note_table(Light& light, const Params& params, std::string_view key);
// The same for a table that is not a parameter (a source's built-in spectrum): `what` names it.
void note_table(Light& light, const Spectrum& table, std::string what);

// Refuses, at `lo_key` or `hi_key` of `params`, a band [lo, hi] that reaches past a table the light went through
// (light.tables), or past the zero-extrapolated `spectrum` itself (a table no stage recorded).
void require_band_inside_tables(const Params& params, const Light& light, const Spectrum& spectrum, double lo_m,
                                double hi_m, const std::string& lo_key = "band_min", const std::string& hi_key = "band_max");
// The same for one of the stage's own tables (a QE curve), if it has `key`.
void require_band_inside_own_table(const Params& params, std::string_view key, double lo_m, double hi_m,
                                   const std::string& lo_key = "band_min", const std::string& hi_key = "band_max");

}  // namespace radchain
