#include "imaging_common.hpp"

#include "radchain/error.hpp"

namespace radchain::cli {

void bad_option(const std::string& option, const std::string& value, const std::string& problem) {
  throw InputError(SourceLocation{option, 0, 0}, "", value, problem);
}

}  // namespace radchain::cli
