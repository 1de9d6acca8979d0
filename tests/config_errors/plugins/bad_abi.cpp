// A plugin built for another ABI: the host must refuse it before calling anything in it.
#include <boost/config.hpp>
#include <cstdint>
extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version;
extern "C" BOOST_SYMBOL_EXPORT const std::uint32_t radchain_plugin_abi_version = 999;
