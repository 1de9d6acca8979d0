#!/usr/bin/env bash
# Installs radchain into a scratch prefix, builds examples/out-of-tree-plugin against it with
# find_package(radchain CONFIG), and checks that the installed CLI loads and describes the plugin.
set -euo pipefail
source_dir=$1 build_dir=$2
prefix="$build_dir/test-install"
rm -rf "$prefix" "$build_dir/test-oot"
cmake --install "$build_dir" --prefix "$prefix" >/dev/null
cmake -S "$source_dir/examples/out-of-tree-plugin" -B "$build_dir/test-oot" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$build_dir/test-oot" >/dev/null
out=$(env -u RADCHAIN_PLUGIN_PATH "$prefix/bin/radchain" --plugin-path "$build_dir/test-oot/plugins" describe pinhole)
echo "$out" | grep -q 'pinhole — optics plugin' || { echo "describe pinhole failed: $out" >&2; exit 1; }
echo "$out" | grep -q 'optics.collecting_area' || { echo "describe pinhole shows no publishes: $out" >&2; exit 1; }
# the installed plugins are found from the install prefix, without any path given
installed=$(env -u RADCHAIN_PLUGIN_PATH "$prefix/bin/radchain" plugins)
for plugin in optics/telescope criterion/snr_threshold detector/ccd_frame source/sun; do
  echo "$installed" | grep -q "$prefix/lib/radchain/plugins/$plugin.so" || { echo "no $plugin.so installed: $installed" >&2; exit 1; }
done
echo "out-of-tree plugin built and loaded from $prefix"
