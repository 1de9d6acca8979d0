#pragma once
#include <cstdint>

namespace radchain {
// Bumped whenever PluginInfo, Stage, Context, Params or any type they expose changes layout or meaning.
inline constexpr std::uint32_t plugin_abi_version = 8;  // 5: Stage::power_law_in_signal(); 6: Context remembers misses,
                                                        // Context::set_in_spectral_phase(), read_in_spectral_phase();
                                                        // 7: Context remembers the term of each declaration;
                                                        // 8: Light::tables (the tables the light went through)
inline constexpr const char* framework_version = "0.1.0";
}  // namespace radchain
