#!/usr/bin/env bash
# The layering check must fail when a rule is broken: a copy of the sources with core including an imaging
# header, a plugin including a batch header and the Python module including the command line's code (and linking
# it) is refused with every line.
# Usage: check_layers_selftest.sh SOURCE_DIR BINARY_DIR
set -euo pipefail
src=$1 bin=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp -r "$src/framework" "$src/plugins" "$src/python" "$work/"
echo '#include "commands/render_image.hpp"' >>"$work/python/src/module.cpp"
echo 'target_link_libraries(radchain_python PRIVATE radchain_cli_support)' >>"$work/python/CMakeLists.txt"
echo '#include "radchain/imaging/render.hpp"' >>"$work/framework/core/src/chain.cpp"
plugin=$(find "$work/plugins" -name '*.cpp' | sort | head -1)
echo '#include "radchain/batch/sweep.hpp"' >>"$plugin"
if out=$("$src/tests/architecture/check_layers.sh" "$work" "$bin"); then
  echo "selftest: the check passed a tree that breaks four rules"; exit 1
fi
echo "$out"
grep -q "framework/core/src/chain.cpp:.*core must not include batch or imaging" <<<"$out" || { echo "selftest: core rule not reported"; exit 1; }
grep -q "plugins use the core SDK only" <<<"$out" || { echo "selftest: plugin rule not reported"; exit 1; }
grep -q "python/src/module.cpp:.*not the command line's code" <<<"$out" || { echo "selftest: Python include rule not reported"; exit 1; }
grep -q "python/CMakeLists.txt: .*link no command-line code" <<<"$out" || { echo "selftest: Python link rule not reported"; exit 1; }
echo "selftest: every broken rule reported"
