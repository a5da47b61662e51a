#!/usr/bin/env bash
# Installs topomill to a temporary prefix, builds sdk/template out of tree against that prefix
# alone, runs its tests and its example scene through --plugin-path and TOPOMILL_PLUGIN_PATH, and
# checks that the same plugin built for another ABI is refused with its message.
# Usage: run_sdk_consumer.sh SOURCE_DIR BUILD_DIR WORK_DIR [EXTRA_FLAGS]
# EXTRA_FLAGS (e.g. the sanitizers') are used for the template too, as a plugin author would.
set -euo pipefail
src=$1 build=$2 work=$3 extra=${4:-}
rm -rf "$work" && mkdir -p "$work"
prefix=$work/prefix
fail() { echo "FAIL: $*"; exit 1; }

cmake --install "$build" --prefix "$prefix" >/dev/null
[ -x "$prefix/bin/topomill" ] || fail "no installed program"
[ -f "$prefix/lib/cmake/topomill/topomillConfig.cmake" ] || fail "no CMake package"
[ -f "$prefix/include/topomill/plugin.hpp" ] || fail "no public headers"
[ -f "$prefix/lib/topomill/plugins/libtopomill_zmap.so" ] || fail "no built-in plugins"
[ ! -e "$prefix/include/topomill/scene.hpp" ] || fail "host headers leaked into the SDK"

gen=(); command -v ninja >/dev/null && gen=(-G Ninja)
flags=(-DCMAKE_CXX_FLAGS="$extra" -DCMAKE_EXE_LINKER_FLAGS="$extra" -DCMAKE_MODULE_LINKER_FLAGS="$extra")
cmake -S "$src/sdk/template" -B "$work/template" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" "${flags[@]}" >/dev/null
cmake --build "$work/template" >/dev/null
(cd "$work/template" && ctest --output-on-failure >/dev/null) || fail "the template's own tests"

topomill=$prefix/bin/topomill
scene=$src/sdk/template/scenes/example.toml
# Each listing is read whole before it is searched: `grep -q` leaves at its first match, and under
# pipefail the writer's SIGPIPE on the rest of a long listing failed the check at random.
listing=$("$topomill" plugins --plugin-path "$work/template") || fail "plugins exited $?"
grep -q "ball_end_worn" <<<"$listing" || fail "not listed"
schema=$("$topomill" describe ball_end_worn --plugin-path "$work/template") || fail "describe exited $?"
grep -q "wear (number, mm" <<<"$schema" || fail "describe does not show the schema"
"$topomill" run "$scene" -q --plugin-path "$work/template" --out "$work/out1" >/dev/null \
  || fail "run with --plugin-path"
grep -q '"library": "'"$work"'/template/libtopomill_ball_end_worn.so"' "$work/out1/summary.json" \
  || fail "summary does not name the plugin's library"
TOPOMILL_PLUGIN_PATH="$work/template" "$topomill" run "$scene" -q --out "$work/out2" >/dev/null \
  || fail "run with TOPOMILL_PLUGIN_PATH"

# The same plugin built for another ABI is refused, with the library and both versions.
abi=$("$topomill" --version | sed -n 's/.*plugin ABI \([0-9]*\).*/\1/p')
# The package reports the ABI its headers define.
grep -qx "set(TOPOMILL_ABI_VERSION $abi)" "$prefix/lib/cmake/topomill/topomillConfig.cmake" \
  || fail "the CMake package's TOPOMILL_ABI_VERSION is not the program's ABI $abi"
cmake -S "$src/sdk/template" -B "$work/template_abi" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" -DBUILD_TESTING=OFF "${flags[@]}" \
  -DCMAKE_CXX_FLAGS="$extra -DTOPOMILL_PLUGIN_ABI=999u" >/dev/null
cmake --build "$work/template_abi" >/dev/null
set +e
err=$("$topomill" run "$scene" -q --plugin-path "$work/template_abi" --out "$work/out3" 2>&1)
code=$?
set -e
[ $code -eq 2 ] || fail "ABI mismatch: exit $code, expected 2"
echo "$err" | grep -q "libtopomill_ball_end_worn.so' built for topomill plugin ABI 999, this program provides ABI $abi" \
  || fail "ABI mismatch message: $err"
# The Python package, when built: installed beside the core, it finds the core and the built-in
# plugins from there, and a third party's plugin through plugin_paths.
if [ -d "$build/python/topomill" ]; then
  pkg=$(echo "$prefix"/lib/python3.*/dist-packages)
  [ -f "$pkg/topomill/__init__.py" ] || fail "the Python package is not installed"
  PYTHONPATH=$pkg /usr/bin/python3 -B -c "
import sys, topomill
assert topomill.__file__.startswith(sys.argv[1]), topomill.__file__
r = topomill.run(topomill.Scene.load(sys.argv[2], plugin_paths=[sys.argv[3]]))
assert r.summary['plugins']['tool']['model'] == 'ball_end_worn', r.summary['plugins']
" "$pkg" "$scene" "$work/template" || fail "the installed Python package"
fi
echo "sdk consumer: ok"
