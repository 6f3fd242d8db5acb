#!/usr/bin/env bash
# ctest readme_examples: every command of README.md's ```bash blocks, as written, in order, in one
# shell (so K=... carries over), in a scratch copy of the layout the README assumes (build/,
# reports/, scripts/ and ../shared beside it). The long jobs (scripts/peers, scripts/loop,
# scripts/benchmark) run as written with VERIFYBENCH_SMOKE=1 (each script's smallest workload, on
# the build as it is); $KITTI is an official-layout KITTI folder made of balm_realworld (links:
# sequences/05/{velodyne,calib.txt,times.txt}, poses/05.txt). Commands of the kinds below are not
# run here and say why (each is run by CI elsewhere): a README command that fails fails this
# test, naming it.
# usage: readme_examples_test.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -uo pipefail
src=$1 build=$2 work=$3
rm -rf "$work" && mkdir -p "$work/repo"
ln -s "$build" "$work/repo/build"
ln -s "$src/reports" "$work/repo/reports"
ln -s "$src/scripts" "$work/repo/scripts"
for f in CMakeLists.txt pyproject.toml setup.py; do ln -s "$src/$f" "$work/repo/$f"; done  # pip install .
mkdir -p "$work/home"  # ~ in the commands (~/vb, ~/vb-venv)
if [ -d "$src/../shared" ]; then ln -s "$(cd "$src/../shared" && pwd)" "$work/shared"; fi
skip_reason() {  # why a command is not run here, or nothing
  case "$1" in
    scripts/run*|scripts/test*) echo "the two commands: .ci/run runs both" ;;
    cmake\ -S*|cmake\ --build*) echo "a build: CI builds" ;;
    'cmake --install build'|'cmake --install build --prefix /'*) echo "an install into the system: ctest install_consumer installs the same tree into a scratch prefix" ;;
    '~/vb-venv/bin/pip install'*) echo "a first build from scratch (11 min): the next command is the same install on the built tree" ;;
    scripts/parallel-sweep*|scripts/slurm-sweep*) echo "a cluster job: ctest cluster_parallel and cluster_slurm" ;;
    *'$KITTI'*) [ -d "$work/shared/data/balm_realworld" ] || echo "needs ../shared/data" ;;
    *../shared/*) [ -d "$work/shared" ] || echo "needs ../shared/data" ;;
  esac
}
# The commands: comments dropped, continued lines joined; a for ... done block is one command.
awk '/^```bash/{f=1; next} /^```/{f=0} f' "$src/README.md" |
  sed -e 's/[[:space:]]#.*$//' -e 's/^#.*$//' -e 's/[[:space:]]*$//' |
  awk '{ if (sub(/\\$/, "")) { buf = buf $0 " " } else { print buf $0; buf = "" } }' |
  awk 'NF { if (loop) { cmd = cmd "\n" $0; if ($0 ~ /done/) { print cmd; print "\x1e"; loop = 0 } }
            else if ($1 == "for") { cmd = $0; loop = 1 } else { print; print "\x1e" } }' \
  > "$work/commands"
balm=$work/shared/data/balm_realworld
if [ -d "$balm" ]; then  # $KITTI: the official odometry layout, poses outside the sequence
  mkdir -p "$work/kitti/sequences/05" "$work/kitti/poses"
  for f in velodyne calib.txt times.txt; do ln -s "$balm/$f" "$work/kitti/sequences/05/$f"; done
  ln -s "$balm/poses.txt" "$work/kitti/poses/05.txt"
fi
cd "$work/repo"
ran=0 skipped=0 failed=0
script=$work/session.sh
: > "$script"
echo "export KITTI='$work/kitti' HOME='$work/home'" >> "$script"
while IFS= read -r -d $'\x1e' cmd; do
  cmd=${cmd#$'\n'}
  cmd=${cmd%$'\n'}
  [ -z "${cmd// }" ] && continue
  why=$(skip_reason "$cmd")
  if [ -n "$why" ]; then
    echo "skip: $cmd ($why)"
    skipped=$((skipped + 1))
    continue
  fi
  ran=$((ran + 1))
  run="( $cmd )"
  [[ "$cmd" =~ ^[A-Za-z_][A-Za-z0-9_]*=[^[:space:]]*$ ]] && run=$cmd  # an assignment carries over
  case "$cmd" in scripts/peers*|scripts/loop*|scripts/benchmark*) run="( export VERIFYBENCH_SMOKE=1; $cmd )" ;; esac
  printf '%s\n' "echo \"run: \$(cat <<'VB_CMD'" "$cmd" "VB_CMD" ")\"" "SECONDS=0" \
    "$run >/dev/null 2>\"$work/stderr\" || { echo \"FAILED: \$(tail -3 $work/stderr)\"; failed=\$((failed + 1)); }" \
    "echo \"  \$SECONDS s\"" >> "$script"
done < "$work/commands"
# Then each ```python block, as a script, on Debian's interpreter with the build's module (as the
# block's first comment says), in the same folder.
awk '/^```python/{f=1; n++; next} /^```/{f=0} f{print > (dir "/block" n ".py")}' dir="$work" "$src/README.md"
for py in "$work"/block*.py; do
  [ -e "$py" ] || continue
  ran=$((ran + 1))
  printf '%s\n' "echo \"run: python $(basename "$py")\"" \
    "PYTHONPATH=build/python /usr/bin/python3 '$py' >/dev/null 2>\"$work/stderr\" || { echo \"FAILED: \$(tail -3 $work/stderr)\"; failed=\$((failed + 1)); }" \
    >> "$script"
done
echo 'exit $failed' >> "$script"
bash -c "failed=0; source '$script'"
rc=$?
echo "readme_examples: $ran commands run, $skipped not run here (reasons above), $rc failed"
[ "$rc" -eq 0 ]
