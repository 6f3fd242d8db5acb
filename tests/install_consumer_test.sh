#!/usr/bin/env bash
# Installs the build into a fresh prefix, moves the prefix (the package must be relocatable),
# then builds and runs tests/consumer against it.
set -euo pipefail
build=$1 src=$2 work=$3
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
mv "$work/prefix" "$work/moved"
test -x "$work/moved/bin/verifybench"
"$work/moved/bin/verifybench" --version
# No private header is installed, and no installed file names the build or source tree.
if find "$work/moved/include" -path '*/detail/*' | grep -q .; then
  echo "detail/ headers were installed" >&2; exit 1
fi
if grep -rl -e "$src" -e "$build" "$work/moved/lib/cmake" >/dev/null; then
  echo "the exported package names the source or build tree:" >&2
  grep -rl -e "$src" -e "$build" "$work/moved/lib/cmake" >&2; exit 1
fi
# Every installed report script starts from the moved prefix (the modules it imports came with
# it): the programs print their usage, the modules import.
reports="$work/moved/share/verifybench/reports"
for script in "$reports"/*.py; do
  name=$(basename "$script" .py)
  if [ -x "$script" ]; then
    /usr/bin/python3 -B "$script" --help >"$work/script.out" 2>"$work/script.err" &&
      grep -q "usage:" "$work/script.out"
  else
    /usr/bin/python3 -B -c "import sys; sys.path.insert(0, sys.argv[1]); import $name" "$reports" \
      >"$work/script.out" 2>"$work/script.err"
  fi || { echo "installed $name.py does not start:" >&2; cat "$work/script.err" >&2; exit 1; }
done
cmake -S "$src/tests/consumer" -B "$work/consumer" -DCMAKE_PREFIX_PATH="$work/moved" \
      -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$work/consumer" -j2 >/dev/null
"$work/consumer/consumer"
