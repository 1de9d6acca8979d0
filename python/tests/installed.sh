#!/usr/bin/env bash
# The installed Python package: `cmake --install` into a scratch prefix, then, with no RADCHAIN_PLUGIN_PATH and
# only the prefix's package on PYTHONPATH, import radchain from there: its plugins come from the prefix, and its run
# of the installed sensor file equals the build tree's `radchain run --format json` of that file, value for value.
# Usage: installed.sh PYTHON SOURCE_DIR BUILD_DIR RADCHAIN_CLI
set -euo pipefail
python=$1 source_dir=$2 build_dir=$3 cli=$4
prefix="$build_dir/test-install-python"
rm -rf "$prefix"
cmake --install "$build_dir" --prefix "$prefix" >/dev/null
package="$prefix/lib/python3/dist-packages"
[ -f "$package/radchain/__init__.py" ] || { echo "no radchain package under $package" >&2; exit 1; }
sensor="$prefix/share/radchain/sensors/msx-sbv.toml"
cd "$prefix"  # (not the build tree's python/, which ctest runs in: "" is first on sys.path)
env -u RADCHAIN_PLUGIN_PATH PYTHONPATH="$package" PYTHONDONTWRITEBYTECODE=1 "$python" - "$prefix" "$sensor" "$cli" <<'PY'
import json, subprocess, sys
import radchain
prefix, sensor, cli = sys.argv[1:]
assert radchain.__file__.startswith(prefix), radchain.__file__
files = list(radchain.plugins()["file"])
assert files and all(f.startswith(prefix + "/lib/radchain/plugins/") for f in files), files[:3]
mine = json.loads(radchain.load(sensor).run().json())
ref = json.loads(subprocess.run([cli, "run", sensor, "--format", "json"], capture_output=True, text=True).stdout)
assert mine == ref, "the installed module and the CLI disagree"
print(f"installed radchain imported from {prefix}: {len(files)} plugins, {mine['sensor']} run equals the CLI")
PY
