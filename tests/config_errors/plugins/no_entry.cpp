// The right ABI number, but no radchain_plugin_info entry.
#include "radchain/version.hpp"
#include <boost/config.hpp>
#include <cstdint>
extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version;
extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version = radchain::plugin_abi_version;
