#!/usr/bin/env bash
# The installed Python package: `cmake --install --component python` into a fresh prefix, the
# prefix moved (relocatable), then imported from there only, in a clean environment with Debian's
# /usr/bin/python3: a small solve against a known motion, the version, the stubs and py.typed.
# The default prefix is checked through DESTDIR (nothing is written outside the work folder).
# Usage: python_install_test.sh BUILD WORK SITE_DIR DEFAULT_PREFIX VERSION
set -euo pipefail
build=$1 work=$2 site=$3 default_prefix=$4 version=$5
rm -rf "$work"
mkdir -p "$work"

cmake --install "$build" --component python --prefix "$work/prefix" >/dev/null
mv "$work/prefix" "$work/moved"
pkg=$work/moved/$site/verifybench
for f in __init__.py __init__.pyi _core.pyi py.typed; do
  test -f "$pkg/$f" || { echo "not installed: $pkg/$f" >&2; exit 1; }
done
ls "$pkg"/_core.*.so >/dev/null || { echo "no compiled module in $pkg" >&2; exit 1; }
# The python component installs the package and nothing else.
extra=$(cd "$work/moved" && find . -type f ! -path "./$site/verifybench/*")
[ -z "$extra" ] || { echo "the python component installed more: $extra" >&2; exit 1; }
if readelf -d "$pkg"/_core.*.so | grep -q -e RPATH -e RUNPATH; then
  echo "the installed module keeps an RPATH:" >&2; readelf -d "$pkg"/_core.*.so | grep PATH >&2; exit 1
fi

env -i PATH=/usr/bin:/bin PYTHONPATH="$work/moved/$site" PYTHONDONTWRITEBYTECODE=1 \
    VB_PREFIX="$work/moved" VB_VERSION="$version" /usr/bin/python3 -s - <<'EOF'
import os
import numpy as np
import verifybench as vb

prefix = os.path.realpath(os.environ["VB_PREFIX"]) + os.sep
assert os.path.realpath(vb.__file__).startswith(prefix), vb.__file__
assert os.path.realpath(vb._core.__file__).startswith(prefix), vb._core.__file__
assert vb.__version__ == os.environ["VB_VERSION"], vb.__version__
assert "clique" in vb.solvers(), vb.solvers()
assert callable(vb.load_report)

# 20 inliers of a known motion (30 deg about z, then a translation), 8 outliers.
rng = np.random.default_rng(3)
src = rng.uniform(-2.0, 2.0, size=(28, 3))
a = np.radians(30.0)
R = np.array([[np.cos(a), -np.sin(a), 0.0], [np.sin(a), np.cos(a), 0.0], [0.0, 0.0, 1.0]])
t = np.array([0.5, -1.0, 2.0])
dst = src @ R.T + t
dst[20:] = rng.uniform(-6.0, 6.0, size=(8, 3))
r = vb.solve("clique", src, dst, eps=0.05)
assert list(r["inliers"]) == list(range(20)), r["inliers"]
assert r["accepted"], r
T = np.asarray(r["T"])
assert T.shape == (4, 4), T.shape
assert np.allclose(T[:3, :3], R, atol=1e-6) and np.allclose(T[:3, 3], t, atol=1e-6), T
print("verifybench", vb.__version__, "from", os.path.dirname(vb.__file__), ": ok")
EOF

# The default prefix (the build's CMAKE_INSTALL_PREFIX), staged under DESTDIR.
DESTDIR="$work/dest" cmake --install "$build" --component python >/dev/null
case $site in
  /*) staged=$work/dest$site/verifybench ;;
  *) staged=$work/dest$default_prefix/$site/verifybench ;;
esac
test -f "$staged/py.typed" || { echo "not installed under the default prefix: $staged" >&2; exit 1; }
rm -rf "$work"
