#pragma once
// The subcommands of the `radchain` executable. main.cpp parses the command line into the option structs
// (options.hpp); each command calls one library function (radchain::batch, radchain::core) and prints, and
// returns the exit code: 0 ok, 1 a failed check, 2 bad input. Bad input is thrown as InputError and printed
// by main as one line. render, validate and mtf run in the imaging module (imaging_module.hpp), loaded only
// for them: the executable does not link OpenImageIO or FFTW.
#include "options.hpp"

#include <string>

namespace radchain::cli {

int run(const RunCommand& options);
int catalogue(const CatalogueCommand& options);
int compare(const CompareCommand& options);
int sweep(const SweepCommand& options);
int merge(const MergeCommand& options);
int plugins();
int describe(const std::string& name);

// Through the imaging module (imaging_loader.cpp); exit 2 with one line when it cannot be loaded.
int render(const RenderCommand& options);
int validate(const ValidateCommand& options);
int mtf(const MtfCommand& options);

}  // namespace radchain::cli
