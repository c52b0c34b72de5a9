#!/usr/bin/env bash
# Tests of bench/run, the benchmarks' driver, without running any engine: a fake dem and fake
# LIGGGHTS and LAMMPS print the lines bench/run reads, with loop times the test chooses, and the
# scene "dense" is copied into a scratch bench/ (bench/run writes its outputs beside itself).
# Checks: the medians of --repeat (odd and even counts), the ratio and speed-up drawn from them, a
# run of other counts left out of the ratio, the options refused with exit status 2; and the
# pours' generator's refusals.
# usage: tests/bench/bench_run_test.sh SOURCE_DIR
set -uo pipefail
src="${1:?usage: bench_run_test.sh SOURCE_DIR}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/bench" "$tmp/bin"
cp "$src/bench/run" "$tmp/bench/run"
cp -r "$src/bench/dense" "$src/bench/terrain" "$tmp/bench/"
failures=0
fail() { echo "FAIL: $*" >&2; failures=$((failures + 1)); }

# Each fake takes its next loop time (and atom count) from a list file, one line per run.
cat > "$tmp/bin/dem" <<'FAKE'
#!/usr/bin/env bash
threads=1; out=""
while [ $# -gt 0 ]; do case "$1" in --threads) threads="$2"; shift 2 ;; --out) out="$2"; shift 2 ;; *) shift ;; esac; done
list="$FAKES/dem-$threads.times"
t="$(head -n 1 "$list")"; sed -i 1d "$list"
mkdir -p "$out"
echo "done: steps=5000 particles=32000 loop_seconds=$t particle_steps_per_second=1 neighbor_builds=1"
FAKE
for peer in liggghts lmp; do
  cat > "$tmp/bin/$peer" <<FAKE
#!/usr/bin/env bash
read -r t atoms < <(head -n 1 "\$FAKES/$peer.times"); sed -i 1d "\$FAKES/$peer.times"
echo "Loop time of \$t on 1 procs for 5000 steps with \${atoms:-32000} atoms"
FAKE
done
chmod +x "$tmp/bin/"*
export FAKES="$tmp" DEM="$tmp/bin/dem" PATH="$tmp/bin:$PATH"
times() { printf '%s\n' "${@:2}" > "$tmp/$1.times"; }

# odd count: medians 2 (dem, one thread), 1 (two threads), 5 (LAMMPS), 8 (LIGGGHTS)
times dem-1 3 1 2; times dem-2 1 1 5; times lmp 4 6 5; times liggghts 9 8 7
out="$("$tmp/bench/run" dense --repeat 3 2>"$tmp/err")"; rc=$?
[ "$rc" -eq 0 ] || fail "--repeat 3: exit $rc: $(cat "$tmp/err")"
grep -qx 'dem-1thread: particle_steps_per_second=8e+07 loop_seconds=2 particles=32000 steps=5000' <<<"$out" ||
  fail "--repeat 3: dem-1thread's median is not 2: $out"
grep -qx 'lammps: particle_steps_per_second=3.2e+07 loop_seconds=5 particles=32000 steps=5000' <<<"$out" ||
  fail "--repeat 3: lammps' median is not 5: $out"
grep -qx 'speedup_2_threads: 2.000' <<<"$out" || fail "--repeat 3: speed-up: $out"
grep -qx 'ratio_vs_best_peer: 2.500' <<<"$out" || fail "--repeat 3: ratio against LAMMPS (5 s): $out"
[ "$(grep -c 'loop_seconds=' "$tmp/err")" -eq 12 ] || fail "--repeat 3: not every run's line on stderr: $(cat "$tmp/err")"

# even count: the mean of the middle two
times dem-1 1 2; times lmp 3 5
out="$("$tmp/bench/run" dense --repeat 2 --codes dem-1thread,lammps 2>/dev/null)"
grep -q '^dem-1thread: .* loop_seconds=1.5 ' <<<"$out" || fail "--repeat 2: median of 1 and 2 is not 1.5: $out"
grep -qx 'ratio_vs_best_peer: 2.667' <<<"$out" || fail "--repeat 2: ratio 4/1.5: $out"

# a peer that ran other counts than the scene's: warned, exit 1, and not the best peer
times dem-1 2; times lmp 4; times liggghts "1 31999"
out="$("$tmp/bench/run" dense --codes dem-1thread,liggghts,lammps 2>"$tmp/err")"; rc=$?
[ "$rc" -eq 1 ] || fail "wrong counts: exit $rc, expected 1"
grep -q 'WARNING: liggghts ran 31999 particles, expected 32000' "$tmp/err" || fail "wrong counts: no warning: $(cat "$tmp/err")"
grep -qx 'ratio_vs_best_peer: 2.000' <<<"$out" || fail "wrong counts: the ratio took LIGGGHTS' run: $out"

# refused with exit status 2, each naming what is wrong
refused() {  # EXPECTED-TEXT ARGS...
  local said rc
  said="$("$tmp/bench/run" "${@:2}" 2>&1 >/dev/null)"; rc=$?
  [ "$rc" -eq 2 ] || fail "bench/run ${*:2}: exit $rc, expected 2"
  grep -qF -- "$1" <<<"$said" || fail "bench/run ${*:2}: said '$said', expected '$1'"
}
refused "no code 'lamps'" dense --codes dem-1thread,lamps
refused "no code ' lammps'" dense --codes "dem-1thread, lammps"
refused "names no code" dense --codes ""
refused "from 1 to 999 (got '0')" dense --repeat 0
refused "from 1 to 999 (got '1000')" dense --repeat 1000
refused "from 1 to 999 (got '1.5')" dense --repeat 1.5
refused "a scene is the name of a folder of bench/" ../bench/dense
refused "no scene 'nosuch'" nosuch
refused "takes neither --codes nor --repeat" terrain --repeat 3
refused "unknown option --fast" dense --fast

# bench/pour/make-scene, the pours' generator: a bad RATIO or OUT is named, not a Python traceback
make_scene_refuses() {  # EXPECTED-TEXT ARGS...
  local said rc
  said="$(/usr/bin/python3 "$src/bench/pour/make-scene" "${@:2}" 2>&1)"; rc=$?
  [ "$rc" -eq 1 ] || fail "make-scene ${*:2}: exit $rc, expected 1"
  grep -qF -- "$1" <<<"$said" && ! grep -q Traceback <<<"$said" || fail "make-scene ${*:2}: said '$said', expected '$1'"
}
touch "$tmp/a-file"
make_scene_refuses "RATIO is a number from 1 to 100" "$tmp/s" x
make_scene_refuses "RATIO is a number from 1 to 100" "$tmp/s" inf
make_scene_refuses "RATIO is a number from 1 to 100" "$tmp/s" 0.5
make_scene_refuses "OUT is empty" "" 4
make_scene_refuses "is a file, not a folder" "$tmp/a-file" 4
make_scene_refuses "Not a directory" "$tmp/a-file/s" 4

[ "$failures" -eq 0 ] && echo "bench_run_test: all checks passed"
exit "$((failures > 0))"
