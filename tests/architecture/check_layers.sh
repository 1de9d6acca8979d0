#!/usr/bin/env bash
# The layering rules of docs/architecture.md, checked on the sources and on the built libraries:
#   core      includes no radchain/batch or radchain/imaging header, no TBB / OpenImageIO / FFTW / CLI11,
#             and its library loads none of them;
#   batch     includes no radchain/imaging header and no OpenImageIO / FFTW; its library loads neither;
#   imaging   includes no radchain/batch header and no TBB; its library links neither (OpenImageIO loads TBB);
#   plugins   include only core headers and link only radchain-core (and load no TBB / OpenImageIO / FFTW).
#   python    binds the libraries, never the command line's code: nothing under python/ includes a framework/cli
#             header or links a CLI target; radchain._radchain (every file of python/src but imaging.cpp) uses core and batch (no radchain/imaging
#             header, no TBB / OpenImageIO / FFTW / CLI11 include, and the built module loads no imaging, OpenImageIO
#             or FFTW); radchain._imaging (imaging.cpp, imported by radchain.render) binds core and imaging.
# Usage: check_layers.sh SOURCE_DIR BINARY_DIR. Prints one line per broken rule; exit 1 if any.
set -uo pipefail
src=$1 bin=$2
broken=0
fail() { echo "layering: $*"; broken=1; }

# forbid_includes DIR PATTERN WHAT: no source under DIR includes a header matching PATTERN.
forbid_includes() {
  local dir=$1 pattern=$2 what=$3 hits
  hits=$(grep -rnE --include='*.cpp' --include='*.hpp' "^[[:space:]]*#[[:space:]]*include[[:space:]]*[<\"]($pattern)" "$src/$dir" 2>/dev/null)
  if [ -n "$hits" ]; then
    while IFS= read -r hit; do fail "${hit#"$src"/}: $what"; done <<<"$hits"
  fi
}
forbid_includes framework/core 'radchain/batch/|radchain/imaging/' "core must not include batch or imaging"
forbid_includes framework/core 'tbb/|oneapi/|OpenImageIO/|fftw3|CLI/' "core must not use TBB, OpenImageIO, FFTW or CLI11"
forbid_includes framework/batch 'radchain/imaging/' "batch must not include imaging"
forbid_includes framework/batch 'OpenImageIO/|fftw3' "batch must not use OpenImageIO or FFTW"
forbid_includes framework/imaging 'radchain/batch/' "imaging must not include batch"
forbid_includes framework/imaging 'tbb/|oneapi/' "imaging must not use TBB"
forbid_includes plugins 'radchain/batch/|radchain/imaging/' "plugins use the core SDK only"
forbid_includes plugins 'tbb/|oneapi/|OpenImageIO/|fftw3|CLI/' "plugins use the core SDK only"
for binding in "$src"/python/src/*.cpp "$src"/python/src/*.hpp; do  # radchain._radchain: every file but imaging.cpp
  [ "${binding##*/}" = imaging.cpp ] || forbid_includes "${binding#"$src"/}" 'radchain/imaging/' "radchain._radchain uses core and batch, never imaging"
done
forbid_includes python 'tbb/|oneapi/|OpenImageIO/|fftw3|CLI/' "the Python modules bind radchain's libraries only"
forbid_includes python '(\.\./)*(commands/|options\.hpp|option_schema\.hpp|overrides\.hpp|plot\.hpp|common\.hpp|terminal\.hpp)' \
  "the Python modules bind the libraries, not the command line's code"
cli_use=$(grep -nE 'framework/cli|radchain_cli|radchain_render_support|radchain_imaging_commands' "$src/python/CMakeLists.txt" 2>/dev/null)
[ -z "$cli_use" ] || fail "python/CMakeLists.txt: $(echo "$cli_use" | head -1): the Python modules link no command-line code"

# forbid_loads LIBRARY PATTERN WHAT: ldd of LIBRARY (everything it loads) shows nothing matching PATTERN.
forbid_loads() {
  local lib=$1 pattern=$2 what=$3 hits
  [ -f "$lib" ] || { fail "${lib#"$bin"/}: not built"; return; }
  hits=$(ldd "$lib" | grep -E "$pattern" | awk '{print $1}' | tr '\n' ' ')
  [ -z "$hits" ] || fail "${lib#"$bin"/} loads ${hits% }: $what"
}
core_lib=$(ls "$bin"/lib/libradchain-core.so 2>/dev/null)
forbid_loads "${core_lib:-$bin/lib/libradchain-core.so}" 'libtbb|libOpenImageIO|libfftw3' "core links no TBB, OpenImageIO or FFTW"
forbid_loads "$bin/lib/libradchain-batch.so" 'libOpenImageIO|libfftw3' "batch links no OpenImageIO or FFTW"
# OpenImageIO itself loads TBB, so for imaging the rule is on what it links directly (NEEDED entries).
needed=$(readelf -d "$bin/lib/libradchain-imaging.so" 2>/dev/null | grep -E 'NEEDED.*(libtbb|libradchain-batch)' | sed 's/.*\[\(.*\)\]/\1/' | tr '\n' ' ')
[ -z "$needed" ] || fail "lib/libradchain-imaging.so links ${needed% }: imaging links no TBB and no batch"

for module in "$bin"/python/radchain/_radchain*.so; do
  [ -f "$module" ] || continue  # built only with RADCHAIN_PYTHON (not under sanitizers)
  forbid_loads "$module" 'libOpenImageIO|libfftw3|libradchain-imaging' "the Python module links core and batch only"
done

plugins=$(find "$bin/plugins" -name '*.so' | sort)
[ -n "$plugins" ] || fail "no plugins under $bin/plugins"
for plugin in $plugins; do
  forbid_loads "$plugin" 'libtbb|libOpenImageIO|libfftw3|libradchain-batch|libradchain-imaging' "plugins link radchain::core only"
done

if [ "$broken" = 0 ]; then
  echo "layering: core, batch, imaging and $(echo "$plugins" | wc -l) plugins keep their rules"
fi
exit "$broken"
