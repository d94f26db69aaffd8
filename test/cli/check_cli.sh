#!/usr/bin/env bash
# Command-line checks of the feps program: exit statuses, help and version, a mesh-only
# input, the main job's outputs, and that bad input leaves no result file behind.
# FEPS and FEPS_TESTER name other builds of the program and the test runner to check (as
# test/cli/check_runtime.sh does with its sanitized build); by default, fpm's default build.
# FEPS_FUZZ_MEMORY_GB, FEPS_FUZZ_TIMEOUT: the fuzzer's address-space limit (default 4 GB;
# AddressSanitizer's shadow memory needs more than 16 TB) and time (default 60 s) per case.
set -uo pipefail
cd "$(dirname "$0")/../.."
fpm build >/dev/null 2>&1 || { echo "check_cli: build failed" >&2; exit 1; }
feps=${FEPS:-$(fpm run --runner echo 2>/dev/null | tail -n 1)}
feps=${feps#"$PWD/"}    # relative when inside the package (the relative-FEPS campaign check below)
case $feps in /*) feps_abs=$feps ;; *) feps_abs=$PWD/$feps ;; esac
[ -x "$feps" ] || { echo "check_cli: cannot find the feps executable" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0
# each check's time (since the check before it ended) goes to $tmp/timings; the slowest are
# listed at the end, so CI's time can be traced to its checks
last=${EPOCHREALTIME/./}
timed() { local now=${EPOCHREALTIME/./}; echo "$(((now - last) / 1000000)).$(printf '%06d' $(((now - last) % 1000000))) ${1:0:90}" >>"$tmp/timings"; last=$now; }
ok() { pass=$((pass + 1)); echo "  ok   $1"; timed "$1"; }
bad() { fail=$((fail + 1)); echo "  FAIL $1"; timed "$1"; }

expect_status() {  # name expected-status command...
  local name=$1 want=$2; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  if [ "$got" -eq "$want" ]; then ok "$name (exit $got)"; else bad "$name: exit $got, expected $want: $(head -c 300 "$tmp/err")"; fi
}

expect_status "--help" 0 "$feps" --help
grep -q "usage: feps DECK" "$tmp/out" && ok "--help shows usage" || bad "--help shows usage"
expect_status "--version" 0 "$feps" --version
grep -q "^feps [0-9]" "$tmp/out" && ok "--version prints the version" || bad "--version prints the version"
# issue 28: the BLAS, the kernels it chose for this CPU and its threads (solves on one thread)
grep -Eq "^blas (OpenBLAS [0-9.]+, [A-Za-z0-9]+ kernels, [0-9]+ threads? \(solves on 1\)|not OpenBLAS)" "$tmp/out" \
  && ok "--version names the BLAS, its kernels and threads: $(sed -n 2p "$tmp/out")" || bad "--version's BLAS line: $(cat "$tmp/out")"
# An OpenBLAS that takes this CPU for an old one (forced here to Prescott) is named with the
# kernels the CPU runs, from its flags as /proc/cpuinfo lists them.
want=$(awk '/^flags/ {for (i = 2; i <= NF; i++) f[$i] = 1; exit} END {
  if (f["avx512f"] && f["avx512bw"] && f["avx512vl"] && f["avx512dq"] && f["avx512cd"]) print "SkylakeX";
  else if (f["avx2"] && f["fma"]) print "Haswell"; else print "none" }' /proc/cpuinfo)
line=$(OPENBLAS_CORETYPE=Prescott "$feps" --version | sed -n 2p)
case $line in
  "blas not OpenBLAS"*) ok "--version with another BLAS: nothing to advise" ;;
  *) if [ "$want" = none ]; then
       echo "$line" | grep -q "OPENBLAS_CORETYPE=" && bad "--version advises kernels this CPU lacks: $line" \
         || ok "--version: Prescott kernels are right for this CPU"
     else
       echo "$line" | grep -q "Prescott kernels, .*this CPU runs $want kernels: OPENBLAS_CORETYPE=$want" \
         && ok "--version names the $want kernels an OpenBLAS taking this CPU for a Prescott misses" \
         || bad "--version with OPENBLAS_CORETYPE=Prescott (this CPU: $want): $line"
     fi ;;
esac
# An OpenBLAS that took this CPU for a Prescott by itself (a stand-in library, preloaded, that
# says Prescott until OPENBLAS_CORETYPE asks for other kernels): feps starts again, with its
# arguments, on the kernels the CPU runs, and says so; a user's OPENBLAS_CORETYPE stands.
if [ "$want" != none ] && "$feps" --version | grep -q "^blas OpenBLAS" && command -v cc >/dev/null; then
  cat >"$tmp/prescott.c" <<'CEOF'
#include <stdlib.h>
char *openblas_get_corename(void) { char *k = getenv("OPENBLAS_CORETYPE"); return k != NULL ? k : "Prescott"; }
CEOF
  cc -shared -fPIC -o "$tmp/prescott.so" "$tmp/prescott.c"
  line=$(env -u OPENBLAS_CORETYPE -u FEPS_BLAS_KERNELS_REPLACED LD_PRELOAD="$tmp/prescott.so" \
         "$feps" test/data/cube.dat --output "$tmp/kern.h5" --fields displacement | grep "^blas")
  echo "$line" | grep -q "$want kernels (chosen by feps; OpenBLAS chose Prescott)" && [ -s "$tmp/kern.h5" ] \
    && [ "$(h5dump -a /summary/blas "$tmp/kern.h5" 2>/dev/null | grep -c "chosen by feps")" -ge 1 ] \
    && ok "an OpenBLAS that took this CPU for a Prescott: feps starts again on $want kernels, arguments kept" \
    || bad "start again on better kernels: $line"
  line=$(OPENBLAS_CORETYPE=Prescott LD_PRELOAD="$tmp/prescott.so" "$feps" --version | sed -n 2p)
  echo "$line" | grep -q "Prescott kernels, .*OPENBLAS_CORETYPE=$want" \
    && ok "the user's OPENBLAS_CORETYPE stands (no new start)" || bad "the user's OPENBLAS_CORETYPE: $line"
fi
OPENBLAS_NUM_THREADS=1 "$feps" --version | grep -Eq "^blas (OpenBLAS .*, 1 thread \(|not OpenBLAS)" \
  && ok "--version counts the BLAS threads OPENBLAS_NUM_THREADS sets" || bad "--version with OPENBLAS_NUM_THREADS=1: $(OPENBLAS_NUM_THREADS=1 "$feps" --version)"
# The factorization's threads: every core up to 4, three quarters above (measured on 16 cores,
# docs/performance.md), never more than --threads N or OMP_NUM_THREADS.
cores=$(nproc)
want_threads=$((cores <= 4 ? cores : 3 * cores / 4))
env -u OPENBLAS_NUM_THREADS -u GOTO_NUM_THREADS -u OMP_NUM_THREADS "$feps" --version | grep -Eq "^blas (OpenBLAS .*, $want_threads threads? \(|not OpenBLAS)" \
  && ok "the factorization gets $want_threads BLAS threads on $cores cores" || bad "BLAS threads on $cores cores (want $want_threads): $("$feps" --version | sed -n 2p)"
# (the summary to a file first: grep -q stops reading at its match, and under pipefail feps's
# SIGPIPE would fail the check)
env -u OPENBLAS_NUM_THREADS -u GOTO_NUM_THREADS "$feps" test/data/cube.dat --threads 1 --output "$tmp/th.h5" >"$tmp/th.out"
grep -Eq "^blas +(OpenBLAS .*, 1 thread \(|not OpenBLAS)" "$tmp/th.out" \
  && ok "--threads 1 holds the BLAS to one thread" || bad "--threads 1 and the BLAS threads"
# The element loops' and solves' threads (issue 28 item 2): --threads N as given; by default
# the cores no other process runs on at start, so with every core taken by a busy loop one
# thread, never a thread that would wait for a taken core.
grep -Eq "^threads +1 of $cores cores \(element loops, solves\)$" "$tmp/th.out" \
  && ok "--threads 1: the summary's threads line" || bad "--threads 1's threads line: $(grep '^threads' "$tmp/th.out")"
busy=()
for _ in $(seq "$cores"); do
  (while :; do :; done) &
  busy+=("$!")
done
sleep 0.3
env -u OMP_NUM_THREADS "$feps" test/data/cube.dat --output "$tmp/thb.h5" >"$tmp/thb.out"
kill "${busy[@]}"
wait "${busy[@]}" 2>/dev/null || true
grep -Eq "^threads +1 of $cores cores " "$tmp/thb.out" \
  && ok "every core busy: the default is one thread" || bad "every core busy, the default threads: $(grep '^threads' "$tmp/thb.out")"
OMP_NUM_THREADS=3 "$feps" test/data/cube.dat --output "$tmp/tho.h5" >"$tmp/tho.out"
grep -Eq "^threads +3 of $cores cores " "$tmp/tho.out" \
  && ok "OMP_NUM_THREADS=3 stands" || bad "OMP_NUM_THREADS=3's threads line: $(grep '^threads' "$tmp/tho.out")"
expect_status "no deck" 2 "$feps"
# A deck that cannot be read is bad input (the user fixes the command or the file): exit 2, one
# line naming the file, no result file; results that cannot be written are a failed run: exit 1.
expect_status "missing deck" 2 "$feps" "$tmp/no_such_deck.dat" --output "$tmp/nd.h5"
[ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "^feps: error: $tmp/no_such_deck.dat: cannot open file" "$tmp/err" \
  && [ ! -e "$tmp/nd.h5" ] && [ ! -e "$tmp/nd.h5.part" ] && ok "the missing deck is named in one line, no result file" \
  || bad "the missing deck is named in one line, no result file: $(head -c 300 "$tmp/err")"
expect_status "missing deck with --check" 2 "$feps" "$tmp/no_such_deck.dat" --check
# The thesis's Newton-Raphson cannot follow the non-dilatant joint from zero (its step-start
# tangent is elastic in every iteration, and cut-backs cannot help): the stop names full Newton.
expect_status "newton-raphson on the psi = 0 joint stops" 1 "$feps" test/data/joint_psi0.dat --method newton-raphson \
  --output "$tmp/psi0.h5"
grep -q "step 1, .*10 cut-backs.*METHOD=full-newton-raphson" "$tmp/err" && [ ! -e "$tmp/psi0.h5" ] \
  && ok "... and its message names full-newton-raphson" || bad "newton-raphson stop names full Newton: $(head -c 400 "$tmp/err")"
# A later stage that reverses the misalignment starts from the sliding points' non-symmetric
# tangents, which the thesis's Newton-Raphson replaces by the interface's symmetric stand-in: with
# 3 iterations and no cut-back it stops, and the message names the two remedies.
sed 's/^DISPLACE, top, X=0.785405$/&\nSTAGE, back, STEPS=2, LOAD=0, METHOD=newton-raphson, MAXIT=3, CUTBACKS=0, OUTPUT=1\nDISPLACE, top, X=-0.5/' \
  test/data/joint_psi0.dat >"$tmp/psi0_back.dat"
expect_status "newton-raphson reversing the psi = 0 joint stops" 1 "$feps" "$tmp/psi0_back.dat" --output "$tmp/psi0b.h5"
grep -q "stage back, step 1, .*only a symmetric stand-in was factorized: try STAGE ..., METHOD=full-newton-raphson (exact tangent, LU) or METHOD=initial-stiffness, ACCELERATION=bfgs, MAXIT=400" "$tmp/err" \
  && [ ! -e "$tmp/psi0b.h5" ] && ok "... and its message names the stand-in's two remedies" \
  || bad "the stand-in's stop names both remedies: $(head -c 600 "$tmp/err")"
# Result paths are checked before the run: a missing folder is the user's to fix (exit 2).
expect_status "results into a missing folder" 2 "$feps" test/data/cube.dat --output "$tmp/no_such_folder/cube.h5"
[ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "^feps: error: results file .*cannot create it: no folder" "$tmp/err" \
  && ok "the unwritable results file is named in one line" \
  || bad "the unwritable results file is named in one line: $(head -c 300 "$tmp/err")"

# Issue 24: hostile input and machine faults. Each gives exit 1 or 2 within seconds, one line
# "feps: error: ...", no .h5, .h5.part, .xmf or .xmf.part of its stem, and nothing of the user's
# removed (fpm test holds the library's side: test_bad_input, test_results_file, test_datain).
hostile() {  # name want-status stem command...: the command's stderr is one line, no stem.* left
  local name=$1 want=$2 stem=$3; shift 3
  timeout 60 "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  local left; left=$(ls -d "$stem".h5 "$stem".h5.part "$stem".xmf "$stem".xmf.part "$stem".meshio.xdmf \
    "$stem".meshio.xdmf.part 2>/dev/null | tr '\n' ' ')
  if [ "$got" -eq "$want" ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "^feps: error: " "$tmp/err" && [ -z "$left" ]; then
    ok "$name (exit $got): $(head -c 160 "$tmp/err")"
  else
    bad "$name: exit $got (want $want), $(wc -l <"$tmp/err") lines, left: $left: $(head -c 300 "$tmp/err")"
  fi
}
for opt in --output --method --solver --maxit --steps --tolerance --fields; do
  hostile "$opt '' is refused" 2 "$tmp/empty" "$feps" test/data/cube.dat "$opt" '' --output "$tmp/empty.h5"
done
hostile "an option given twice is refused" 2 "$tmp/twice" "$feps" test/data/cube.dat --output "$tmp/twice.h5" -o "$tmp/twice2.h5"
hostile "--maxit 2147483647 is refused like MAXIT=2147483647" 2 "$tmp/maxit" "$feps" test/data/cube.dat --maxit 2147483647 \
  --output "$tmp/maxit.h5"
mkdir -p "$tmp/userdir" "$tmp/xdir.xmf" && echo keep >"$tmp/userdir/keep" && echo keep >"$tmp/xdir.xmf/keep"
hostile "--output an existing directory: refused at once" 2 "$tmp/userdir" "$feps" input/modelB/SE1.dat --output "$tmp/userdir"
[ -f "$tmp/userdir/keep" ] && ok "... and the directory is kept with its file" || bad "the user's directory was removed"
hostile "the XDMF name an existing directory: refused at once" 2 "$tmp/xdir_results" "$feps" test/data/cube.dat \
  --output "$tmp/xdir.h5"
[ -f "$tmp/xdir.xmf/keep" ] && [ ! -e "$tmp/xdir.h5" ] && [ ! -e "$tmp/xdir.h5.part" ] \
  && ok "... no results written, and that directory is kept" || bad "the user's .xmf directory was removed, or results written"
rm -rf "$tmp/userdir" "$tmp/xdir.xmf"   # (later checks read every $tmp/*.xmf as an XDMF file)
mkfifo "$tmp/fifo.datain" "$tmp/fifo.dat"
printf 'INCLUDE, fifo.datain\n' >"$tmp/inc_fifo.dat"
hostile "INCLUDE of a FIFO: refused, not waited on" 2 "$tmp/incf" "$feps" "$tmp/inc_fifo.dat" --output "$tmp/incf.h5"
hostile "a FIFO as the deck: refused" 2 "$tmp/fifod" "$feps" "$tmp/fifo.dat" --output "$tmp/fifod.h5"
hostile "/dev/zero as the deck: refused" 2 "$tmp/zero" "$feps" /dev/zero --output "$tmp/zero.h5"
python3 -c "print('TITLE, ' + 'x' * 1000000)" >"$tmp/long_line.dat"
start=$(date +%s)
hostile "a line of 1 MB: refused at its limit" 2 "$tmp/longl" "$feps" "$tmp/long_line.dat" --output "$tmp/longl.h5"
[ $(( $(date +%s) - start )) -le 5 ] && ok "... within 5 s" || bad "a line of 1 MB took $(( $(date +%s) - start )) s"
python3 -c "
import sys
sys.stdout.write('NODE, 1, 0.,\n' + '0.,\n' * 500000)" >"$tmp/long_record.dat"
start=$(date +%s)
hostile "a record continued over 500 000 lines: read in linear time" 2 "$tmp/longr" "$feps" "$tmp/long_record.dat" \
  --output "$tmp/longr.h5"
[ $(( $(date +%s) - start )) -le 10 ] && ok "... within 10 s" || bad "500 000 continuation lines took $(( $(date +%s) - start )) s"
# Memory: a mesh of a million nodes in a 1 GB address space is refused before anything is
# allocated or written (it died in an allocation with a backtrace and left its .h5.part).
sed -e 's/^%, 3, 5., 0., 0.,$/%, 101, 0.1, 0., 0.,/; s/^%, 3, 0., 5., 0.,$/%, 101, 0., 0.1, 0.,/' \
    -e 's/^%, 3, 0., 0., 5.,$/%, 101, 0., 0., 0.1,/' -e 's/^A, 8, 1, 2, 5, 4, 10, 11, 14, 13,$/A, 8, 1, 2, 103, 102, 10202, 10203, 10304, 10303,/' \
    -e 's/^%, 2, \*, 8, 1,$/%, 100, *, 8, 1,/; s/^%, 2, \*, 8, 3,$/%, 100, *, 8, 101,/; s/^%, 2, \*, 8, 9,$/%, 100, *, 8, 10201,/' \
    test/data/cube.dat >"$tmp/million.dat"
hostile "a million-node mesh under ulimit -v 1 GB: refused with the memory it needs" 1 "$tmp/million" \
  bash -c "ulimit -v 1000000; exec \"\$0\" \"\$@\"" "$feps_abs" "$tmp/million.dat" --output "$tmp/million.h5"
grep -q "needs about .* GiB at least" "$tmp/err" && ok "... naming the GiB it needs" || bad "the memory message: $(head -c 300 "$tmp/err")"
# The factor: a 50k-DOF pipe mesh whose mesh fits in 400 MB of address space but whose CHOLMOD
# analysis or factor does not: one line naming the memory, exit 1, nothing left (before, CHOLMOD's
# out-of-memory status came out as "analysis failed (CHOLMOD status -2)").
python3 scripts/make_pipe_mesh.py --preset 50k -o "$tmp/pipe50k.dat" >/dev/null
hostile "a 50k-DOF mesh whose factor does not fit in 400 MB: one line, exit 1" 1 "$tmp/pipe50k" \
  bash -c "ulimit -v 400000; exec \"\$0\" \"\$@\"" "$feps_abs" "$tmp/pipe50k.dat" --output "$tmp/pipe50k.h5"
grep -q "fit in the memory this process may use\|more than the .* GiB this process may use" "$tmp/err" \
  && ok "... saying it does not fit in the memory" || bad "the factor's memory message: $(head -c 300 "$tmp/err")"
# FE1 under 350 MB of address space: its factor fits, OpenBLAS's 128 MiB work buffer does not,
# and OpenBLAS 0.3.21 retries that allocation forever (the run hung in dpotrf): refused before
# the factorization, counting what the process has mapped already and the BLAS's buffers.
hostile "FE1 under ulimit -v 350 MB: refused before the factorization, not a hang" 1 "$tmp/fe1mem" \
  bash -c "ulimit -v 350000; exec \"\$0\" \"\$@\"" "$feps_abs" input/modelB/FE1.dat --output "$tmp/fe1mem.h5"
grep -q "more than the .* GiB this process may use" "$tmp/err" \
  && ok "... saying what is left of the address space" || bad "FE1's memory message: $(head -c 300 "$tmp/err")"
# Just above that check, the factorization used to start and then hang or crash: OpenBLAS's
# buffer taken at the first level-3 call (dpotrf), one more for each thread of the solves, the
# threads CHOLMOD starts (libgomp ended the run: "Thread creation failed"). The check now counts
# them and the buffers are taken right after it: refused with one line, or run.
hostile "FE1 on one thread under ulimit -v 450 MB (hung in dpotrf): refused" 1 "$tmp/fe1mem1" \
  bash -c "ulimit -v 450000; exec \"\$0\" \"\$@\"" "$feps_abs" input/modelB/FE1.dat --threads 1 --output "$tmp/fe1mem1.h5"
hostile "FE1 on two threads under ulimit -v 600 MB (hung in the solves): refused" 1 "$tmp/fe1mem2" \
  bash -c "ulimit -v 600000; exec \"\$0\" \"\$@\"" "$feps_abs" input/modelB/FE1.dat --threads 2 --output "$tmp/fe1mem2.h5"
# Disk full while the results are written, at several points (the mesh, a step, the XDMF file):
# a small tmpfs where this machine allows mounting, else a file-size limit (ulimit -f: EFBIG).
"$feps" input/modelB/SE1.dat --quiet --output "$tmp/se1full.h5" >/dev/null 2>&1
h5kb=$(( $(stat -c %s "$tmp/se1full.h5") / 1024 )); rm -f "$tmp/se1full".*
mkdir -p "$tmp/full"
if mount -t tmpfs -o size=64k tmpfs "$tmp/full" 2>/dev/null; then
  umount "$tmp/full"
  for kb in 64 $(( h5kb / 2 )) $(( h5kb + 4 )); do
    mount -t tmpfs -o size=${kb}k tmpfs "$tmp/full"
    hostile "disk full (a ${kb} kB tmpfs) while writing model B SE1's results" 1 "$tmp/full/se1" \
      "$feps" input/modelB/SE1.dat --quiet --output "$tmp/full/se1.h5"
    umount "$tmp/full"
  done
else
  for kb in 64 $(( h5kb / 2 )) $(( h5kb + 4 )); do
    hostile "file-size limit (ulimit -f ${kb} kB) while writing model B SE1's results" 1 "$tmp/full/se1" \
      bash -c "ulimit -f $kb; exec \"\$0\" \"\$@\"" "$feps_abs" input/modelB/SE1.dat --quiet --output "$tmp/full/se1.h5"
  done
fi
expect_status "unknown option" 2 "$feps" --frobnicate input/modelB.dat
expect_status "bad --solver" 2 "$feps" test/data/cube.dat --solver lu
expect_status "bad --method" 2 "$feps" test/data/cube.dat --method newton
grep -q "full-newton-raphson" "$tmp/err" && ok "bad --method lists the methods" || bad "bad --method lists the methods"
# A deck asking for LINESEARCH=energy run by a method it does not apply to: exit 2, the field named.
expect_status "--method modified-newton-raphson on a LINESEARCH=energy deck" 2 "$feps" test/data/friction_pull.dat \
  --method modified-newton-raphson --output "$tmp/fp.h5"
[ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "^feps: error: --method modified-newton-raphson: LINESEARCH=energy.*friction_pull.dat:" "$tmp/err" \
  && [ ! -e "$tmp/fp.h5" ] && ok "... names the line search and where it was asked, no result file" \
  || bad "--method against LINESEARCH=energy: $(head -c 300 "$tmp/err")"
# The cohesionless joint (c = 0) from zero load with full Newton: every step converges.
expect_status "--method full-newton-raphson" 0 "$feps" test/data/joint_c0.dat --method full-newton-raphson \
  --output "$tmp/jc0.h5"
grep -q "method full-newton-raphson" "$tmp/out" && grep -q "0 cut-backs, 0 steps not converged\|0 cut-backs)" "$tmp/out" \
  && ok "full Newton: no cut-back, every step converged" || bad "full Newton: no cut-back, every step converged: $(grep analysis "$tmp/out")"
# The XDMF file goes beside the results as <name>.xmf: a results name ending in .xmf would lose it.
for opt in --output -o; do
  expect_status "$opt FILE.xmf" 2 "$feps" test/data/cube.dat $opt "$tmp/cube.xmf"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "^feps: error: $opt .*cube.xmf.* must not end in .xmf" "$tmp/err" \
    && [ ! -e "$tmp/cube.xmf" ] && [ ! -e "$tmp/cube.xmf.part" ] \
    && ok "$opt FILE.xmf: one line naming the option, no file" || bad "$opt FILE.xmf: $(head -c 300 "$tmp/err")"
done
expect_status "bad --maxit" 2 "$feps" test/data/cube.dat --maxit many
grep -q "\-\-maxit takes a whole number" "$tmp/err" && ok "bad --maxit says what it takes" || bad "bad --maxit says what it takes"
expect_status "bad --threads" 2 "$feps" test/data/cube.dat --threads 0
grep -q "\-\-threads takes a whole number from 1" "$tmp/err" && ok "bad --threads says what it takes" \
  || bad "bad --threads says what it takes: $(cat "$tmp/err")"
# --threads 2 gives the bits of one thread (issue 28 item 3; fpm test's threads suite checks it
# too), the BLAS held at one thread: its thread count changes the factorization at round-off.
OPENBLAS_NUM_THREADS=1 "$feps" test/data/friction_pull.dat --quiet --threads 1 --output "$tmp/t1.h5" \
  && OPENBLAS_NUM_THREADS=1 "$feps" test/data/friction_pull.dat --quiet --threads 2 --output "$tmp/t2.h5" \
  && python3 -c "
import sys, h5py
a, b = h5py.File(sys.argv[1]), h5py.File(sys.argv[2])
names = []
a.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
assert names and all(a[n][...].tobytes() == b[n][...].tobytes() for n in names)
" "$tmp/t1.h5" "$tmp/t2.h5" && ok "--threads 2: every dataset bit-identical to one thread's" || bad "--threads 2 differs from one thread"
# --steps N and --tolerance X override every stage's STEPS (arc-length stages keep theirs) and
# DELTA1: the same bits as the deck edited so (and not those of --steps alone: at DELTA1 = 1e-3
# full Newton stops sooner than at the deck's 1e-9); bad values are one line, exit 2, no file.
sed 's/STAGE, press, STEPS=1, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-9/STAGE, press, STEPS=3, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-3/; s/STAGE, pull, STEPS=10, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-9/STAGE, pull, STEPS=3, METHOD=full-newton-raphson, MAXIT=50, DELTA1=1e-3/' \
  test/data/friction_pull.dat >"$tmp/friction_pull_3.dat"
"$feps" "$tmp/friction_pull_3.dat" --quiet --output "$tmp/fp_deck.h5" \
  && "$feps" test/data/friction_pull.dat --quiet --steps 3 --tolerance 1e-3 --output "$tmp/fp_flags.h5" \
  && "$feps" test/data/friction_pull.dat --quiet --steps 3 --output "$tmp/fp_steps.h5" \
  && python3 -c "
import sys, h5py
a, b, c = (h5py.File(f) for f in sys.argv[1:4])
names = []
a.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) else None)
assert sorted(a['steps']) == sorted(b['steps']) and len(a['steps']) == 6
assert names and all(a[n][...].tobytes() == b[n][...].tobytes() for n in names)
assert any(a[n][...].tobytes() != c[n][...].tobytes() for n in names)
" "$tmp/fp_deck.h5" "$tmp/fp_flags.h5" "$tmp/fp_steps.h5" \
  && ok "--steps 3 --tolerance 1e-3: every dataset bit-identical to the deck with STEPS=3, DELTA1=1e-3" \
  || bad "--steps 3 --tolerance 1e-3 against the deck edited so"
"$feps" input/modelB.dat --check --method full-newton-raphson --steps 1 --tolerance 1e-6 >"$tmp/out" 2>&1 \
  && grep -q "^stage load: 1 steps, full-newton-raphson, at most 50 iterations per step, to a relative residual of 1.00E-06;" \
     "$tmp/out" && ok "--check shows --steps 1 --tolerance 1e-6 in the stage line" \
  || bad "--check with --steps 1 --tolerance 1e-6: $(grep '^stage' "$tmp/out")"
"$feps" test/data/crack_bar_arc.dat --quiet --steps 2 --output "$tmp/arc_steps.h5" \
  && python3 -c 'import sys, h5py; sys.exit(len(h5py.File(sys.argv[1])["steps"]) != 30)' "$tmp/arc_steps.h5" \
  && ok "--steps 2: an arc-length stage keeps its 30 steps" || bad "--steps 2 on an arc-length stage"
for v in 0 many 10000001; do
  expect_status "--steps $v" 2 "$feps" test/data/cube.dat --steps "$v" --output "$tmp/st.h5"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q -- "--steps takes a whole number from 1 to 10000000, not \"$v\"" "$tmp/err" \
    && [ ! -e "$tmp/st.h5" ] && ok "--steps $v: one line saying what it takes, no result file" \
    || bad "--steps $v: $(head -c 300 "$tmp/err")"
done
expect_status "--steps beyond the steps of all stages" 2 "$feps" test/data/slide_1dof_support_change.dat --steps 5000001 \
  --output "$tmp/st.h5"
[ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q -- "--steps 5000001: the stages would take more than 10000000 steps" "$tmp/err" \
  && [ ! -e "$tmp/st.h5" ] && ok "--steps over two stages past 10000000: one line, no result file" \
  || bad "--steps over two stages: $(head -c 300 "$tmp/err")"
for v in -1e-6 nan 1e-320 tight; do
  expect_status "--tolerance $v" 2 "$feps" test/data/cube.dat --tolerance "$v" --output "$tmp/tol.h5"
  [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q -- "--tolerance takes a number from 0 up .*not \"$v\"" "$tmp/err" \
    && [ ! -e "$tmp/tol.h5" ] && ok "--tolerance $v: one line saying what it takes, no result file" \
    || bad "--tolerance $v: $(head -c 300 "$tmp/err")"
done
# --fields replaces the deck's FIELDS; a misspelt name is one line, exit 2, no result file.
expect_status "bad --fields" 2 "$feps" test/data/cube.dat --fields displacement,stresses --output "$tmp/f.h5"
[ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q -- '--fields: unknown field "stresses"' "$tmp/err" && [ ! -e "$tmp/f.h5" ] \
  && ok "bad --fields names the option and the field, no result file" \
  || bad "bad --fields: $(head -c 300 "$tmp/err")"
"$feps" test/data/cube.dat --fields all,nodal_principal --output "$tmp/f.h5" --quiet \
  && python3 -c 'import sys, h5py; f = h5py.File(sys.argv[1]); s = f["steps/0001"]; sys.exit(0 if "nodal_principal" in s and "stress" in s and "nodal_stress" not in s else 1)' "$tmp/f.h5" \
  && ok "--fields all,nodal_principal adds the nodal principal stresses to the default fields" \
  || bad "--fields all,nodal_principal"
# --maxit overrides the deck's MAXIT=200 both ways: 3 iterations cannot follow the unzipping
# of test/data/unzip.dat (stop, exit 1, the message names --maxit, no result file), 200 can.
expect_status "--maxit 3 stops at the unzipping" 1 "$feps" test/data/unzip.dat --maxit 3 --output "$tmp/u3.h5"
grep -q "feps --maxit 400" "$tmp/err" && [ ! -e "$tmp/u3.h5" ] && [ ! -e "$tmp/u3.h5.part" ] \
  && ok "the stop names --maxit and leaves no result file" || bad "the stop names --maxit and leaves no result file: $(head -c 300 "$tmp/err")"
expect_status "--maxit 200 follows the unzipping" 0 "$feps" test/data/unzip.dat --maxit 200 --output "$tmp/u200.h5"

# Every example of the manuals (README.md, docs/*.md) runs and says what feps does: decks and
# records accepted, error messages as printed, the HDF5 layout table, commands (test/cli/check_docs.py,
# driven by the <!-- check: ... --> markers; a fenced block without one fails).
python3 test/cli/check_docs.py --feps "$feps" >"$tmp/out" 2>&1 \
  && ok "docs' examples: $(tail -n 1 "$tmp/out")" || bad "docs' examples: $(grep -v '^  ok' "$tmp/out" | head -c 1500)"
# A file holding only a DATAIN mesh: report it, write /mesh with --output.
expect_status "Table 2.1 mesh-only" 0 "$feps" ../shared/benchmarks/table2_1.datain --output "$tmp/t21.h5"
grep -q "nodes *3375" "$tmp/out" && grep -q "elements *2496" "$tmp/out" && ok "Table 2.1 counts reported" \
  || bad "Table 2.1 counts reported"
grep -q "min Jacobian" "$tmp/out" && ok "smallest Jacobian reported" || bad "smallest Jacobian reported"
# A bare mesh with a block of 4-node elements: typed nodes4 and written, without an XDMF cell
# (docs/output-format.md); it used to stop as an unsupported element type.
"$feps" test/data/mesh_mixed.datain --output "$tmp/mixed.h5" >"$tmp/out" 2>&1
python3 - "$tmp/mixed.h5" "$tmp/out" <<'PY' && ok "mesh-only with a nodes4 block: written, no XDMF cell for it" \
  || bad "mesh-only with a nodes4 block: $(head -c 300 "$tmp/out")"
import re, sys, h5py
assert re.search(r"^min Jacobian +1.25000E-01$", open(sys.argv[2]).read(), re.M)   # the hex8 block's
f = h5py.File(sys.argv[1])
t = {g: f[f"mesh/groups/{g}"].attrs["element_type"] for g in f["mesh/groups"]}
assert t == {"block1": b"nodes4", "block2": b"hex8"} or t == {"block1": "nodes4", "block2": "hex8"}, t
assert list(f["xdmf"]) == ["block2"] and f["mesh/groups/block1/connectivity"].shape == (2, 4)
assert 'Grid Name="block1"' not in open(sys.argv[1][:-3] + ".xmf").read()
PY
# A model of bars only has no solid Jacobian: --check says so instead of printing huge().
"$feps" input/verification/table2_2_bar3.dat --check >"$tmp/out" 2>&1 \
  && grep -q "^min Jacobian *none (no solid element)$" "$tmp/out" && ok "bars only: min Jacobian none" \
  || bad "bars only: min Jacobian none: $(grep -i jacobian "$tmp/out")"
python3 - "$tmp/t21.h5" <<'PY' && ok "mesh-only HDF5: /mesh, /xdmf, /summary (program, input_file) and the .xmf, as documented" \
  || bad "mesh-only HDF5: /mesh, /xdmf, /summary (program, input_file) and the .xmf, as documented"
import os, sys, h5py
f = h5py.File(sys.argv[1])
assert f["mesh/coordinates"].shape == (3375, 3)
assert f["mesh/groups/block1/connectivity"].shape == (2496, 8)
assert list(f["mesh/groups/block1/connectivity"][0]) == [1, 2, 7, 6, 126, 127, 132, 131]
# docs/output-format.md: exactly these groups and summary attributes, and the XDMF file beside it
assert sorted(f) == ["mesh", "summary", "xdmf"], sorted(f)
assert sorted(f["summary"].attrs) == ["input_file", "program"], sorted(f["summary"].attrs)
g = f["mesh/groups/block1"].attrs
assert g["element_type"] in (b"hex8", "hex8") and g["material"] in (b"", "", b"\0"), dict(g)
assert (f["xdmf/block1/topology"][...] == f["mesh/groups/block1/connectivity"][...] - 1).all()
assert os.path.exists(os.path.splitext(sys.argv[1])[0] + ".xmf")
PY

# Every bad deck: exit status 2, a one-line error naming the file, no result file.
for deck in test/data/bad/*.dat; do
  name=$(basename "$deck" .dat)
  out="$tmp/$name.h5"
  "$feps" "$deck" --output "$out" >"$tmp/out" 2>"$tmp/err"; got=$?
  lines=$(wc -l <"$tmp/err")
  if [ "$got" -eq 2 ] && [ "$lines" -eq 1 ] && grep -q "$name" "$tmp/err" && [ ! -e "$out" ] && [ ! -e "$out.part" ]; then
    ok "bad input $name: $(cat "$tmp/err")"
  else
    bad "bad input $name: exit $got, $lines stderr lines, files: $(ls "$tmp" | grep "^$name" | tr '\n' ' ')"
  fi
  # --check finds the same error (the rigid-body mode through its factorization) and writes nothing
  cp "$tmp/err" "$tmp/err_run"
  "$feps" "$deck" --check --output "$out" >"$tmp/out" 2>"$tmp/err"; got=$?
  if [ "$got" -eq 2 ] && cmp -s "$tmp/err" "$tmp/err_run" && [ ! -e "$out" ] && [ ! -e "$out.part" ]; then
    ok "--check on $name: the same error"
  else
    bad "--check on $name: exit $got, $(head -c 300 "$tmp/err")"
  fi
done

# docs/output-format.md: a deck refused before its first step (exit 2) leaves the results an
# earlier run wrote under the same name alone (22 of these decks, refused once the results file
# was begun, used to remove them); a run that fails removes them (fpm test, bad_input suite).
"$feps" test/data/cube.dat --quiet --output "$tmp/earlier.h5" >/dev/null 2>&1
lost=""
for deck in test/data/bad/*.dat; do
  cp "$tmp/earlier.h5" "$tmp/stale.h5" && cp "$tmp/earlier.xmf" "$tmp/stale.xmf" \
    && cp "$tmp/earlier.meshio.xdmf" "$tmp/stale.meshio.xdmf"
  "$feps" "$deck" --output "$tmp/stale.h5" >/dev/null 2>&1
  { [ -e "$tmp/stale.h5" ] && [ -e "$tmp/stale.xmf" ] && [ -e "$tmp/stale.meshio.xdmf" ] \
    && [ ! -e "$tmp/stale.h5.part" ]; } || lost="$lost $(basename "$deck")"
done
[ -z "$lost" ] && ok "every bad deck leaves an earlier run's results and XDMF file alone" \
  || bad "bad decks that removed an earlier run's results:$lost"

# A three-digit exponent keeps its E in the summary (es12.5 would print 1.08628+303), and the
# largest displacement, whose squares overflow, is the closed form p l / E sqrt(1 + 2 nu^2).
sed 's/E=200000\./E=1e-300/' test/data/cube.dat >"$tmp/cube_soft.dat"
expect_status "cube with E = 1e-300" 0 "$feps" "$tmp/cube_soft.dat" --output "$tmp/soft.h5"
python3 - "$tmp/out" <<'PY' && ok "summary numbers with three-digit exponents read as numbers" || bad "summary numbers with three-digit exponents: $(grep -E "displacement|force" "$tmp/out")"
import math, sys
lines = {l[:16].strip(): l[16:].split() for l in open(sys.argv[1])}
u = float(lines["max displacement"][0])
assert abs(u / (100 * 10 / 1e-300 * math.sqrt(1 + 2 * 0.3**2)) - 1) < 1e-5, u
assert [float(x) for x in lines["applied force"]] == [0.0, 0.0, -1e4], lines["applied force"]
PY

# Finite loads, a displacement beyond double precision: exit 1, one error line naming the stage
# (after the warning that E = 1e-300 MPa is no physical modulus), no result file of NaN.
expect_status "solution beyond double precision" 1 "$feps" test/data/overflow_solution.dat --output "$tmp/ovf.h5"
[ "$(grep -c "^feps: error: " "$tmp/err")" -eq 1 ] && [ "$(grep -vc "^feps: warning: .*E = 1.000E-300 MPa is below 1 MPa" "$tmp/err")" -eq 1 ] \
  && grep -q "stage stage1: the solution is not finite" "$tmp/err" \
  && [ ! -e "$tmp/ovf.h5" ] && [ ! -e "$tmp/ovf.h5.part" ] && [ ! -e "$tmp/ovf.xmf" ] \
  && ok "the overflow names the stage and leaves no result file" \
  || bad "the overflow names the stage and leaves no result file: $(head -c 300 "$tmp/err")"

# Mutated decks (fixed seeds): a clear answer every time, never a crash, a hang or a runaway
# allocation (test/cli/fuzz_input.py; longer campaigns in docs/verification.md).
python3 test/cli/fuzz_input.py --feps "$feps" --memory-gb "${FEPS_FUZZ_MEMORY_GB:-4}" --timeout "${FEPS_FUZZ_TIMEOUT:-60}" --cases 150 --seed 1 --out "$tmp/fuzz" >"$tmp/out" 2>&1 \
  && ok "fuzz --check: $(tail -n 1 "$tmp/out")" || bad "fuzz --check: $(grep FAIL "$tmp/out" | head -3)"
python3 test/cli/fuzz_input.py --feps "$feps" --memory-gb "${FEPS_FUZZ_MEMORY_GB:-4}" --timeout "${FEPS_FUZZ_TIMEOUT:-60}" --cases 40 --seed 2 --run --out "$tmp/fuzz" >"$tmp/out" 2>&1 \
  && ok "fuzz --run: $(tail -n 1 "$tmp/out")" || bad "fuzz --run: $(grep FAIL "$tmp/out" | head -3)"
# Issue 24's classes (--hostile): integer limits, control bytes and bytes that are not UTF-8, long
# lines, INCLUDE of /dev/zero, a FIFO or a directory, and machine faults (file-size and
# address-space limits, a directory as the results): a fixed-seed slice of about 40 s.
python3 test/cli/fuzz_input.py --feps "$feps" --memory-gb "${FEPS_FUZZ_MEMORY_GB:-4}" --timeout "${FEPS_FUZZ_TIMEOUT:-60}" --hostile --cases 300 --seed 3 --out "$tmp/fuzz" >"$tmp/out" 2>&1 \
  && ok "fuzz --hostile --check: $(tail -n 1 "$tmp/out")" || bad "fuzz --hostile --check: $(grep FAIL "$tmp/out" | head -3)"
python3 test/cli/fuzz_input.py --feps "$feps" --memory-gb "${FEPS_FUZZ_MEMORY_GB:-4}" --timeout "${FEPS_FUZZ_TIMEOUT:-60}" --hostile --run --cases 100 --seed 4 --out "$tmp/fuzz" >"$tmp/out" 2>&1 \
  && ok "fuzz --hostile --run: $(tail -n 1 "$tmp/out")" || bad "fuzz --hostile --run: $(grep FAIL "$tmp/out" | head -3)"
# ... and the fuzzer does fail on a program that crashes (exit 134) or hangs
printf '#!/bin/sh\necho "Program received signal SIGSEGV" >&2\nexit 134\n' >"$tmp/crash" && chmod +x "$tmp/crash"
printf '#!/bin/sh\nsleep 30\n' >"$tmp/hang" && chmod +x "$tmp/hang"
python3 test/cli/fuzz_input.py --feps "$tmp/crash" --cases 2 --out "$tmp/fuzzc" >"$tmp/out" 2>&1; got=$?
[ "$got" -eq 1 ] && grep -q "exit 134" "$tmp/out" && [ "$(ls "$tmp/fuzzc" | wc -l)" -eq 2 ] \
  && ok "fuzz flags a crash and keeps the mutants" || bad "fuzz flags a crash: exit $got, $(head -c 300 "$tmp/out")"
python3 test/cli/fuzz_input.py --feps "$tmp/hang" --cases 1 --timeout 1 --out "$tmp/fuzzh" >"$tmp/out" 2>&1; got=$?
[ "$got" -eq 1 ] && grep -q "no answer within 1 s" "$tmp/out" && ok "fuzz flags a hang" || bad "fuzz flags a hang: exit $got, $(head -c 300 "$tmp/out")"
# With --run, a run past --timeout that keeps writing progress lines is slow, not hung (it gets up
# to 3 x --timeout); one that stops writing them for 15 s is a hang.
printf '#!/bin/sh
for i in 1 2 3 4; do echo "stage 1  step $i/4"; sleep 1; done
' >"$tmp/slow" && chmod +x "$tmp/slow"
printf '#!/bin/sh
echo "stage 1  step 1/4"
sleep 60
' >"$tmp/stall" && chmod +x "$tmp/stall"
python3 test/cli/fuzz_input.py --feps "$tmp/slow" --cases 1 --timeout 2 --run --out "$tmp/fuzzs" >"$tmp/out" 2>&1 \
  && ok "fuzz --run: a slow run still stepping past --timeout is not a hang" \
  || bad "fuzz --run: a slow run still stepping past --timeout: $(head -c 300 "$tmp/out")"
python3 test/cli/fuzz_input.py --feps "$tmp/stall" --cases 1 --timeout 1 --run --out "$tmp/fuzzst" >"$tmp/out" 2>&1; got=$?
[ "$got" -eq 1 ] && grep -q "no new progress line for 15 s" "$tmp/out" && ok "fuzz --run flags a run that stalls after a step" \
  || bad "fuzz --run flags a run that stalls: exit $got, $(head -c 300 "$tmp/out")"

# --check: the whole model checked and factorized once, no step taken, no file written.
expect_status "--check input/modelB.dat" 0 "$feps" input/modelB.dat --check --output "$tmp/chk.h5"
grep -q "^checked " "$tmp/out" && grep -q "^dofs  *15049$" "$tmp/out" && grep -q "nonlinear: 1 stage(s), 400 steps" "$tmp/out" \
  && grep -q "^stage load: 400 steps, initial-stiffness, at most 10 iterations per step, to a relative residual of 1.00E-04; load increment" "$tmp/out" \
  && [ ! -e "$tmp/chk.h5" ] && [ ! -e "$tmp/chk.h5.part" ] && [ ! -e "$tmp/chk.xmf" ] \
  && ok "--check reports the model and writes no file" || bad "--check reports the model and writes no file: $(cat "$tmp/out")"

# Model B SE1 (linear) with both solvers: results file, XDMF beside it, quiet mode prints nothing.
for solver in cholmod skyline; do
  expect_status "model B SE1 with $solver" 0 "$feps" input/modelB/SE1.dat --solver "$solver" --output "$tmp/b_$solver.h5"
  [ -s "$tmp/b_$solver.h5" ] && [ -s "$tmp/b_$solver.xmf" ] && ok "model B $solver wrote .h5 and .xmf" \
    || bad "model B $solver wrote .h5 and .xmf"
done
"$feps" input/modelB/SE1.dat --quiet --output "$tmp/q.h5" >"$tmp/out" 2>&1
[ ! -s "$tmp/out" ] && ok "--quiet prints nothing" || bad "--quiet prints nothing"
# The main job (FE1): progress lines and the deflection angle beside the thesis's value.
expect_status "main job input/modelB.dat" 0 "$feps" input/modelB.dat --output "$tmp/main.h5"
grep -q "step 400/400" "$tmp/out" && ok "progress lines shown" || bad "progress lines shown"
grep -q "rotation deflection .*:  *0\.0492[0-9]* deg; thesis   0\.050200 deg" "$tmp/out" \
  && ok "deflection angle printed beside the thesis (README: 0.0492 deg against 0.0502)" \
  || bad "deflection angle printed beside the thesis (README: 0.0492 deg against 0.0502): $(grep rotation "$tmp/out")"
python3 - "$tmp/b_cholmod.h5" "$tmp/b_skyline.h5" <<'PY' && ok "HDF5 layout (SPEC 10) and solvers agree" || bad "HDF5 layout (SPEC 10) and solvers agree"
import sys, h5py, numpy as np
a, b = (h5py.File(p) for p in sys.argv[1:3])
n = a["mesh/coordinates"].shape[0]
assert a["steps/0001/displacement"].shape == (n, 3)
assert a["steps/0001/displacement"].attrs["components"] in (b"ux uy uz", "ux uy uz")
s = a["steps/0001/stress/pipe"]
assert s.shape[1] == 6 and s.attrs["points_per_element"] == 8
assert a["mesh/groups/pipe"].attrs["element_type"] in (b"hex8", "hex8")
for k in ("load_factor", "iterations", "residual"):
    assert k in a["steps/0001"].attrs
for k in ("program", "input_file", "wall_time", "solver", "dofs", "factor_nonzeros"):
    assert k in a["summary"].attrs, k
ua, ub = a["steps/0001/displacement"][...], b["steps/0001/displacement"][...]
assert np.abs(ua - ub).max() <= 1e-9 * np.abs(ua).max()
# the materials as the deck gave them, and each group's material
assert a["mesh/groups/pipe"].attrs["material"] in (b"concrete", "concrete")
c = a["materials/concrete"].attrs
assert c["kind"] in (b"elastic", "elastic") and c["e"] == 40000.0 and c["nu"] == 0.2, dict(c)
PY
# Step names have at least 4 digits ('0001' ... '9999', '10000'): readers order them by number. The
# bar of stage_supports_incremental.dat pulled in 10001 steps, written every 5000: u_top = 2 mm at
# the end, 2 * 5000 / 10001 at step 5000.
sed -n '1,/^FORCE, top/p' test/data/stage_supports_incremental.dat \
  | sed 's/^STAGE, pull, STEPS=1$/STAGE, pull, STEPS=10001, OUTPUT=5000/' >"$tmp/many_steps.dat"
"$feps" "$tmp/many_steps.dat" --quiet --output "$tmp/many.h5" >/dev/null 2>&1
python3 - "$tmp/many.h5" <<'PY' && ok "10001 steps: feps_results orders steps by number" || bad "10001 steps: feps_results orders steps by number"
import sys
sys.path.insert(0, "scripts")
import feps_results as fr
with fr.open_result(sys.argv[1]) as f:
    assert fr.steps(f) == ["5000", "10000", "10001"], fr.steps(f)
    assert fr.last_step(f) == "10001" and fr.pick_step(f) == "10001" and fr.pick_step(f, 10000) == "10000"
    top = fr.coordinates(f)[:, 2] == 200.0
    for step, u in ((None, 2.0), (5000, 2.0 * 5000 / 10001)):
        uz = f[f"steps/{fr.pick_step(f, step)}/displacement"][:, 2][top]
        assert abs(uz - u).max() < 1e-9 * u, (step, uz, u)
PY
# feps_results.gauss_points() for the element types beyond hex8/hex20 and the quad/tri interfaces:
# the rows of each Gauss-point dataset against fields computed independently at the reader's
# points, which fails if a point is misplaced or out of feps's order (the fields vary within the
# elements). hex8b: the Lame cylinder, stresses from the nodal displacements with the B-bar
# strain; tri6 and tri6-6: the 2D contact under a linearly varying pressure, plane-strain stresses
# from the nodal displacements; interface-line2/line3 (Gauss and -nodal): the relative
# displacement (upper minus lower) interpolated at the points has the length of the stored one;
# bars: straight bars of equally spaced nodes, where the points are x1 + (1 + g) (xn - x1) / 2 for
# the n - 1 Gauss-Legendre points g in ascending order.
sed 's/TYPE=hex8,/TYPE=hex8b,/' test/data/lame_hex8.dat >"$tmp/gp_hex8b.dat"
sed 's/^PRESSURE, top, VALUE=1\.$/PRESSURE, top, VALUE=1., VARY=X, ZERO=-10., PEAK=10./' test/data/contact_2d.dat \
  >"$tmp/gp_line3.dat"
sed 's/TYPE=interface-line3,/TYPE=interface-line3-nodal,/' "$tmp/gp_line3.dat" >"$tmp/gp_line3n.dat"
sed -e 's/TYPE=tri6,/TYPE=tri6-6,/; s/TYPE=interface-line3,/TYPE=interface-line2,/' \
  -e '/^GROUP, joint/,/^E,/{s/^A, 6, 21, 23, 22, 26, 28, 27,/A, 4, 21, 22, 26, 27,/; s/^%, 2, \*, 6, 2,/%, 4, *, 4, 1,/}' \
  "$tmp/gp_line3.dat" >"$tmp/gp_line2.dat"
sed 's/TYPE=interface-line2,/TYPE=interface-line2-nodal,/' "$tmp/gp_line2.dat" >"$tmp/gp_line2n.dat"
cat >"$tmp/gp_bars.dat" <<'DECK'
TITLE, straight bars of 2 to 5 nodes in a row along x, nodes 10 mm apart
A, 2, 0., 0., 0.,
%, 11, 10., 0., 0.,
E,
GROUP, b2, TYPE=bar2, MATERIAL=steel
A, 2, 1, 2,
E,
GROUP, b3, TYPE=bar3, MATERIAL=steel
A, 3, 2, 3, 4,
E,
GROUP, b4, TYPE=bar4, MATERIAL=steel
A, 4, 4, 5, 6, 7,
E,
GROUP, b5, TYPE=bar5, MATERIAL=steel
A, 5, 7, 8, 9, 10, 11,
E,
E,
MATERIAL, steel, BAR, E=200000., A=10.
NSET, all, X=0.:100.
NSET, start, X=0.
NSET, tip, X=100.
FIX, all, Y, Z
FIX, start, X
FORCE, tip, X=100.
DECK
for d in gp_hex8b gp_line3 gp_line3n gp_line2 gp_line2n gp_bars; do
  "$feps" "$tmp/$d.dat" --quiet --output "$tmp/$d.h5" >"$tmp/out" 2>&1 || echo "    $d.dat: $(cat "$tmp/out")" >&2
done
python3 - "$tmp" <<'PY' && ok "gauss_points: hex8b, tri6, tri6-6, interface-line2/3 (-nodal), bar2-bar5 in feps's order" \
  || bad "gauss_points: hex8b, tri6, tri6-6, interface-line2/3 (-nodal), bar2-bar5 in feps's order"
import math, sys
import numpy as np
sys.path.insert(0, "scripts")
sys.path.insert(0, "test/reference")
import feps_results as fr
import element_rules as er
tmp = sys.argv[1]
seen = set()


def rows(f, kind, group):
    """A Gauss-point dataset of the last step; its points lie in their elements (lower layer)."""
    ds = f[f"steps/{fr.last_step(f)}/{kind}/{group}"]
    xg = fr.gauss_points(f, group, ds)                  # raises for a type it does not know
    ppe = int(ds.attrs["points_per_element"])
    x = fr.coordinates(f)[fr.connectivity(f, group)]
    half = x.shape[1] // 2 if kind.startswith("interface") else x.shape[1]
    lo, hi = x[:, :half].min(axis=1), x[:, :half].max(axis=1)
    xe = xg.reshape(-1, ppe, 3)
    assert np.all(xe >= lo[:, None] - 1e-9) and np.all(xe <= hi[:, None] + 1e-9), f"{group}: a point outside"
    seen.add(fr.element_type(f, group))
    return ds[...], ppe


def stresses(f, group, eps):
    """Isotropic elastic stresses [sxx syy szz syz sxz sxy] of strains (npts, 3, 3)."""
    material = fr.text(f[f"mesh/groups/{group}"].attrs["material"])
    m = f[f"materials/{material}"].attrs
    lam, mu = m["e"] * m["nu"] / ((1 + m["nu"]) * (1 - 2 * m["nu"])), m["e"] / (2 * (1 + m["nu"]))
    s = 2 * mu * eps + lam * np.trace(eps, axis1=1, axis2=2)[:, None, None] * np.eye(3)
    return s[:, [0, 1, 2, 1, 0, 0], [0, 1, 2, 2, 2, 1]]


def check_solid(f, group, dn, dims):
    """Stored stresses against those of the nodal displacements at the reader's points; dn(xi)
    gives the (nodes, dims) shape-function derivatives; hex8b takes the mean dilatation."""
    stored, ppe = rows(f, "stress", group)
    etype = fr.element_type(f, group)
    xi, _ = er.integration_points(etype, ppe)
    conn = fr.connectivity(f, group)
    x = fr.coordinates(f)[conn][:, :, :dims]
    u = f[f"steps/{fr.last_step(f)}/displacement"][...][conn][:, :, :dims]
    eps = np.zeros((len(conn), ppe, 3, 3))
    vol = np.zeros((len(conn), ppe))
    for g in range(ppe):
        d = dn(xi[g])                                    # (nodes, dims)
        jac = np.einsum("ena,nb->eab", x, d)             # dx_a / dxi_b
        grad = np.einsum("ena,nb,ebc->eac", u, d, np.linalg.inv(jac))
        eps[:, g, :dims, :dims] = 0.5 * (grad + grad.transpose(0, 2, 1))
        vol[:, g] = np.linalg.det(jac)
    if etype == "hex8b":                                 # B-bar: the element's mean dilatation
        tr = np.trace(eps, axis1=2, axis2=3)
        mean = (tr * vol).sum(axis=1) / vol.sum(axis=1)
        eps += ((mean[:, None] - tr) / 3.0)[:, :, None, None] * np.eye(3)
    expected = stresses(f, group, eps.reshape(-1, 3, 3))
    scale = np.abs(stored).max()
    err = np.abs(stored - expected).max()
    spread = np.abs(np.diff(stored.reshape(-1, ppe, 6), axis=1)).max()
    assert err < 1e-8 * scale and spread > 1e-3 * scale, (group, etype, err, spread, scale)


def hex8_dn(xi):
    c = er.HEX8_XI
    f = 1.0 + c * xi
    return np.column_stack([c[:, k] * np.prod(np.delete(f, k, axis=1), axis=1) for k in range(3)]) / 8.0


def tri6_dn(s):
    l1, l2, l3 = 1.0 - s[0] - s[1], s[0], s[1]
    return np.array([[1 - 4 * l1, 1 - 4 * l1], [4 * l2 - 1, 0], [0, 4 * l3 - 1],
                     [4 * (l1 - l2), -4 * l2], [4 * l3, 4 * l2], [-4 * l3, 4 * (l1 - l3)]])


with fr.open_result(f"{tmp}/gp_hex8b.h5") as f:
    check_solid(f, "wall", hex8_dn, 3)
for name in ("gp_line3", "gp_line3n", "gp_line2", "gp_line2n"):
    with fr.open_result(f"{tmp}/{name}.h5") as f:
        for group in ("lower", "upper"):
            check_solid(f, group, tri6_dn, 2)
        stored, ppe = rows(f, "interface_strain", "joint")
        etype = fr.element_type(f, "joint")
        shapes, nodes = er.integration_shapes(etype, ppe)
        conn = fr.connectivity(f, "joint")
        u = f[f"steps/{fr.last_step(f)}/displacement"][...]
        du = np.einsum("gn,enk->egk", shapes, u[conn[:, nodes:]] - u[conn[:, :nodes]]).reshape(-1, 3)
        err = np.abs(np.linalg.norm(stored, axis=1) - np.linalg.norm(du, axis=1)).max()
        scale = np.linalg.norm(du, axis=1).max()
        spread = np.ptp(np.linalg.norm(stored, axis=1).reshape(-1, ppe), axis=1).max()
        assert err < 1e-9 * scale and spread > 1e-3 * scale, (name, etype, err, spread, scale)
root = {3: math.sqrt(3 / 7 - 2 / 7 * math.sqrt(1.2)), 4: math.sqrt(3 / 7 + 2 / 7 * math.sqrt(1.2))}
legendre = {1: [0.0], 2: [-1 / math.sqrt(3), 1 / math.sqrt(3)], 3: [-math.sqrt(0.6), 0.0, math.sqrt(0.6)],
            4: [-root[4], -root[3], root[3], root[4]]}
with fr.open_result(f"{tmp}/gp_bars.h5") as f:
    for group in ("b2", "b3", "b4", "b5"):
        stored, ppe = rows(f, "bar", group)
        n = int(group[1])
        x = fr.coordinates(f)[fr.connectivity(f, group)]
        g = np.array(legendre[n - 1])
        expected = x[:, :1] + (1.0 + g)[None, :, None] / 2 * (x[:, -1:] - x[:, :1])
        assert ppe == n - 1 and np.abs(fr.gauss_points(f, group) - expected.reshape(-1, 3)).max() < 1e-12, group
        assert np.abs(stored - 100.0).max() < 1e-9, (group, stored)   # the tip force in every bar
want = {"hex8b", "tri6", "tri6-6", "interface-line2", "interface-line2-nodal", "interface-line3",
        "interface-line3-nodal", "bar2", "bar3", "bar4", "bar5"}
assert seen >= want, want - seen
PY
# A word-valued material parameter (TENSION) is stored as a string.
"$feps" test/data/beam_tension_cap.dat --quiet --output "$tmp/beam.h5" >/dev/null 2>&1
python3 - "$tmp/beam.h5" <<'PY' && ok "/materials holds TENSION as a string" || bad "/materials holds TENSION as a string"
import sys, h5py
c = h5py.File(sys.argv[1])["materials/concrete"].attrs
assert c["kind"] in (b"matsuoka", "matsuoka") and c["tension"] in (b"closest-point", "closest-point")
assert c["phi"] == 54.9 and c["ft"] == 5.0, dict(c)
PY
# PARAMETERS values are numbers only when written as one and finite; '100-1' (which a
# list-directed read takes as 10) and '1e400' are labels, kept as written.
sed 's/^TITLE, cube under pressure$/&\nPARAMETERS, a=2.5, b=100-1, c=1e400, d=S1/' test/data/cube.dat >"$tmp/params.dat"
"$feps" "$tmp/params.dat" --quiet --output "$tmp/params.h5" >/dev/null 2>&1
python3 - "$tmp/params.h5" <<'PY' && ok "PARAMETERS: numbers as reals, anything else as written" || bad "PARAMETERS: numbers as reals, anything else as written"
import sys, h5py
a = h5py.File(sys.argv[1])["summary"].attrs
assert a["parameter_a"] == 2.5, dict(a)
for k, v in (("b", "100-1"), ("c", "1e400"), ("d", "S1")):
    assert a["parameter_" + k] in (v, v.encode()), (k, a["parameter_" + k])
PY
# A prestressed group records its prestress; --check names it in its stage line.
"$feps" test/data/prestress_block.dat --quiet --output "$tmp/ps.h5" >/dev/null 2>&1
python3 - "$tmp/ps.h5" <<'PY' && ok "PRESTRESS: tendon force and /mesh/groups attribute" || bad "PRESTRESS: tendon force and /mesh/groups attribute"
import sys, h5py
f = h5py.File(sys.argv[1])
assert f["mesh/groups/tendons"].attrs["prestress"] == 10.0
assert "prestress" not in f["mesh/groups/block"].attrs
n = f["steps"][sorted(f["steps"], key=int)[-1]]["bar/tendons"][:, 0]
assert abs(n - 10.0 * 10000 / 10080).max() < 1e-9, n   # N0 k_b / (k_b + 4 k_t)
PY
"$feps" test/data/prestress_block.dat --check >"$tmp/out" 2>&1 && grep -q "born: tendons; prestress tendons 1.000E+01 N" "$tmp/out" \
  && ok "--check names the prestress" || bad "--check names the prestress: $(cat "$tmp/out")"
"$feps" test/data/prestress_post.dat --check >"$tmp/out" 2>&1 \
  && grep -q "post-tension tendons 1.000E+01 N (bonded next stage)" "$tmp/out" && grep -q "stage more: .*born: tendons" "$tmp/out" \
  && ok "--check names the post-tension and the bonding stage" || bad "--check names the post-tension: $(cat "$tmp/out")"

# The CalculiX exporter reads only the results file (the deck's supports are in /constraints):
# a thesis deck's run (its PARAMETERS are labels), any load feps applied (the results file's
# applied_force: a bilinear pressure too); it refuses, with the deck's line, what it cannot
# write (prescribed displacements, supports in a cylindrical system).
python3 scripts/export_inp.py "$tmp/b_cholmod.h5" -o "$tmp/se1.inp" >"$tmp/out" 2>&1 \
  && grep -q "^\*STEP" "$tmp/se1.inp" && grep -q "^\*BOUNDARY" "$tmp/se1.inp" \
  && ok "export_inp.py writes model B SE1" || bad "export_inp.py writes model B SE1: $(cat "$tmp/out")"
python3 - "$tmp/se1.inp" <<'PY' && ok "export_inp.py: SE1's supports are its FIX records' sets and directions" \
  || bad "export_inp.py: SE1's supports are not its FIX records' sets and directions"
import sys
import h5py
sys.path.insert(0, "scripts")
import feps_results as fr
# independent of the exporter: the deck's own FIX lines (model B SE1: soil_outer X Y, symmetry Y,
# anchor Z, all in the global system) and the node sets the run resolved
dofs = {"soil_outer": (1, 2), "symmetry": (2,), "anchor": (3,)}
with h5py.File(sys.argv[1].replace("se1.inp", "b_cholmod.h5")) as h:
    want = {(int(n), d) for s, ds in dofs.items() for n in h[f"sets/nodes/{s}"][...].ravel() for d in ds}
got, on = set(), False
for line in open(sys.argv[1]):
    if line.startswith("*"):
        on = line.startswith("*BOUNDARY")
    elif on:
        n, d = line.split(",")[:2]
        got.add((int(n), int(d)))
sys.exit(0 if got == want and want else 1)
PY
python3 scripts/make_model_b.py --outdir "$tmp/wedge" --cases SE1 --element wedge6 >/dev/null 2>&1
"$feps" "$tmp/wedge/SE1_wedge6_r1.dat" --output "$tmp/se1_wedge6.h5" --quiet >/dev/null 2>&1
python3 scripts/export_inp.py "$tmp/se1_wedge6.h5" -o "$tmp/se1_wedge6.inp" >"$tmp/out" 2>&1 \
  && [ "$(grep -c '^\*ELEMENT, TYPE=C3D6,' "$tmp/se1_wedge6.inp")" -eq 2 ] && ! grep -q "TYPE=C3D8" "$tmp/se1_wedge6.inp" \
  && ok "export_inp.py writes a wedge6 mesh as C3D6 (the group's abaqus_type)" \
  || bad "export_inp.py writes a wedge6 mesh as C3D6: $(cat "$tmp/out")"
"$feps" test/data/bilinear_load.dat --output "$tmp/bl.h5" --quiet >/dev/null 2>&1
python3 scripts/export_inp.py "$tmp/bl.h5" -o "$tmp/bl.inp" >"$tmp/out" 2>&1 \
  && grep -q "resultant 0 0 -900 N" "$tmp/out" && grep -q "^14, 3, -" "$tmp/bl.inp" \
  && ok "export_inp.py writes the bilinear pressure's forces" || bad "export_inp.py writes the bilinear pressure: $(cat "$tmp/out")"
python3 scripts/export_inp.py "$tmp/bl.h5" test/data/bilinear_load.dat -o "$tmp/bl2.inp" >/dev/null 2>&1 \
  && cmp -s "$tmp/bl.inp" "$tmp/bl2.inp" && ok "export_inp.py: a deck after the results file (the older form) changes nothing" \
  || bad "export_inp.py: the older form with a deck writes another file"
sed '/^PRESSURE/d' test/data/cube.dat >"$tmp/displace.dat"
printf 'NSET, top_nodes, Z=10.\nDISPLACE, top_nodes, Z=-0.01\n' >>"$tmp/displace.dat"
"$feps" "$tmp/displace.dat" --output "$tmp/cube_d.h5" --quiet >/dev/null 2>&1
line=$(grep -n "^DISPLACE" "$tmp/displace.dat" | cut -d: -f1)
python3 scripts/export_inp.py "$tmp/cube_d.h5" -o "$tmp/d.inp" >"$tmp/out" 2>&1; got=$?
[ "$got" -eq 1 ] && grep -q "displace.dat:$line: DISPLACE (prescribed displacements) is not exported" "$tmp/out" \
  && [ ! -e "$tmp/d.inp" ] \
  && ok "export_inp.py refuses DISPLACE naming the line" || bad "export_inp.py refuses DISPLACE naming the line: $(cat "$tmp/out")"
"$feps" test/data/lame_hex20.dat --output "$tmp/lame_x.h5" --quiet >/dev/null 2>&1
python3 scripts/export_inp.py "$tmp/lame_x.h5" -o "$tmp/l.inp" >"$tmp/out" 2>&1; got=$?
line=$(grep -n "^FIX" test/data/lame_hex20.dat | head -1 | cut -d: -f1)
[ "$got" -eq 1 ] && grep -q "lame_hex20.dat:$line: FIX in a cylindrical or nodal system is not exported" "$tmp/out" \
  && [ ! -e "$tmp/l.inp" ] \
  && ok "export_inp.py refuses a FIX in a cylindrical system naming the line" \
  || bad "export_inp.py refuses a cylindrical FIX: $(cat "$tmp/out")"

# A campaign with a bad deck stops before running anything (feps --check on every deck first).
camp="check_cli_$$"
FEPS="$feps_abs" bash scripts/campaign.sh "$camp" test/data/cube.dat test/data/bad/rigid_body_mode.dat \
  >"$tmp/out" 2>"$tmp/err"; got=$?
[ "$got" -eq 2 ] && grep -q "rigid_body_mode.dat: the stiffness matrix is singular" "$tmp/err" \
  && [ ! -e "results/$camp/cube" ] && ok "campaign.sh with a bad deck: exit 2, nothing run" \
  || bad "campaign.sh with a bad deck: exit 2, nothing run: exit $got, $(head -c 300 "$tmp/err")"
rm -rf "results/$camp"

# Parametric decks (scripts/make_model_b.py, make_model_c.py): a grid over the thesis's values
# writes the thesis's decks, bad parameters exit 2 naming the parameter, and a deck off the
# thesis grid carries its parameter into the run.
python3 scripts/make_model_c.py --outdir "$tmp/mc_grid" --Gp 300,900 --nup 0.1,0.4,-0.3 --beta 0.09,0.27 >/dev/null \
  && diff -r input/modelC "$tmp/mc_grid" >/dev/null \
  && ok "model C grid over the thesis's values = input/modelC" || bad "model C grid over the thesis's values = input/modelC"
# The mesh study's decks (--wall-elements, --z-refine) are valid meshes of the counted size:
# 61 theta node lines x (4 + 5 soil/wall rings) x 39 z layers below the joint, 61 x 5 x (4 + 62 + 1)
# above it.
python3 scripts/make_model_c.py --outdir "$tmp/mc_fine" --cases C_G300_nu0.1_b0.09 --wall-elements 4 --z-refine 2 \
  >/dev/null && "$feps" "$tmp/mc_fine/C_G300_nu0.1_b0.09.dat" --check >"$tmp/out" 2>&1 \
  && grep -q "^nodes *$((61 * 9 * 39 + 61 * 5 * 67))$" "$tmp/out" \
  && ok "model C with 4 wall elements and z cut in 2: $((61 * 9 * 39 + 61 * 5 * 67)) nodes, --check passes" \
  || bad "model C with 4 wall elements and z cut in 2: $(grep -E '^nodes|error' "$tmp/out")"
# The speed-accuracy study builds the deck of every scene (it once broke when a generator's
# signature changed, and nothing ran it).
python3 - <<'PY' && ok "study_tradeoff.py builds every scene's deck" || bad "study_tradeoff.py builds every scene's deck"
import sys
sys.path.insert(0, "scripts")
import study_tradeoff as t
plans = t.plans(quick=False)
for name, sc in t.scenes().items():
    for element, n, method, steps, tol, solver in plans[name][:1] + plans[name][-1:]:
        assert "STAGE" in sc["deck"](element, n, steps, tol or 1e-6, method), name
PY
python3 scripts/make_chapter9.py --outdir "$tmp/c9" >/dev/null && diff -r input/chapter9 "$tmp/c9" >/dev/null \
  && ok "make_chapter9.py's defaults = input/chapter9" || bad "make_chapter9.py's defaults = input/chapter9"
# The other generators write the committed thesis decks byte for byte.
python3 scripts/make_joint_2d.py --outdir "$tmp/j2d" >/dev/null && diff -r input/joint2d "$tmp/j2d" >/dev/null \
  && ok "make_joint_2d.py's defaults = input/joint2d" || bad "make_joint_2d.py's defaults = input/joint2d"
python3 scripts/make_model_a.py --outdir "$tmp/ma" >/dev/null && diff -r input/modelA "$tmp/ma" >/dev/null \
  && ok "make_model_a.py's defaults = input/modelA" || bad "make_model_a.py's defaults = input/modelA"
python3 scripts/make_model_b.py --outdir "$tmp/mb" >/dev/null && diff -r input/modelB "$tmp/mb" >/dev/null \
  && python3 -c 'import sys; sys.path.insert(0, "scripts"); import make_model_b as m
sys.exit(m.deck("FE1").replace("OUTPUT, modelB_FE1.h5", "OUTPUT, modelB.h5") != open("input/modelB.dat").read())' \
  && ok "make_model_b.py's defaults = input/modelB and input/modelB.dat" \
  || bad "make_model_b.py's defaults = input/modelB and input/modelB.dat"
# make_pipe_joint.py and its presets: test/cli/check_pipe_joint.py, run by .ci/run on the release build.
# The model B mesh study's decks (make_model_b.py --refine, --element): a lattice of
# (4k + 1 + 1 + 8k) r x (54k + 1) theta x (48k + 1) z nodes for hex20:k with interfaces, the same
# lattice as hex8:2k; both pass --check.
for m in "1 hex20" "2 hex8"; do
  set -- $m
  python3 scripts/make_model_b.py --outdir "$tmp/mb_study" --cases FE1 --refine $1 --element $2 >/dev/null \
    && "$feps" "$tmp/mb_study/FE1_$2_r$1.dat" --check >"$tmp/out" 2>&1 \
    && grep -q "^nodes *$((14 * 55 * 49))$" "$tmp/out" \
    && ok "model B FE1 --refine $1 --element $2: $((14 * 55 * 49)) nodes, --check passes" \
    || bad "model B FE1 --refine $1 --element $2: $(grep -E '^nodes|error' "$tmp/out")"
done
# Model B SE1 meshed with wedges (make_model_b.py --element wedge15: every hex20 cut in two along
# its (r, theta) diagonal, on the same nodes) against hex20: the deflection angle at z = 2500 and
# the largest displacement agree to 1e-3 (measured 2.7e-4 and 3.3e-4; docs/verification.md,
# "Tetrahedra and wedges"), and FE1's wedge deck, with its interfaces on the wedges' quadrilateral
# faces, passes --check.
python3 scripts/make_model_b.py --outdir "$tmp/mb_wedge" --cases SE1 --element wedge15 >/dev/null \
  && python3 scripts/make_model_b.py --outdir "$tmp/mb_wedge" --cases SE1 --element hex20 >/dev/null \
  && python3 scripts/make_model_b.py --outdir "$tmp/mb_wedge" --cases FE1 --element wedge15 >/dev/null \
  && "$feps" "$tmp/mb_wedge/FE1_wedge15_r1.dat" --check >/dev/null 2>&1 \
  && "$feps" "$tmp/mb_wedge/SE1_wedge15_r1.dat" --quiet --output "$tmp/mb_wedge/w.h5" >/dev/null 2>&1 \
  && "$feps" "$tmp/mb_wedge/SE1_hex20_r1.dat" --quiet --output "$tmp/mb_wedge/h.h5" >/dev/null 2>&1 \
  && python3 -c 'import sys, numpy as np; sys.path.insert(0, "scripts"); import feps_results as fr
w, h = fr.open_result(sys.argv[1]), fr.open_result(sys.argv[2])
angle = [fr.summary(f)["rotation_deflection_deg"] for f in (w, h)]
umax = [np.abs(f["steps/" + fr.last_step(f) + "/displacement"][...]).max() for f in (w, h)]
assert fr.element_type(w, "pipe") == "wedge15" and fr.element_type(h, "pipe") == "hex20"
sys.exit(not (abs(angle[0] / angle[1] - 1) < 1e-3 and abs(umax[0] / umax[1] - 1) < 1e-3))' \
  "$tmp/mb_wedge/w.h5" "$tmp/mb_wedge/h.h5" \
  && ok "model B SE1 in wedge15 against hex20: deflection angle and largest displacement within 1e-3" \
  || bad "model B SE1 in wedge15 against hex20: deflection angle and largest displacement within 1e-3"
# tet4 (make_model_b.py --element tet4: six tetrahedra per hex8, Kuhn's split) meshes SE1 with every
# Jacobian positive (the run passes the mesh check) and refuses kind F, whose quadrilateral
# interfaces its triangular faces cannot take, before writing any deck.
python3 scripts/make_model_b.py --outdir "$tmp/mb_tet" --cases SE1 --element tet4 >/dev/null \
  && "$feps" "$tmp/mb_tet/SE1_tet4_r1.dat" --quiet --output "$tmp/mb_tet/t.h5" >/dev/null 2>&1 \
  && [ "$(python3 -c 'import sys, h5py; f = h5py.File(sys.argv[1]); print(f["mesh/groups/pipe/connectivity"].shape[0])' \
          "$tmp/mb_tet/t.h5")" -eq $((6 * 1296)) ] \
  && ok "model B SE1 in tet4: six tetrahedra per hexahedron, every Jacobian positive" \
  || bad "model B SE1 in tet4 does not run"
# The round trip through CalculiX's format: the tet4 run exported (export_inp.py), read back
# (import_mesh.py) and run again gives the same displacements bit for bit (the same mesh, the
# applied forces written as the shortest text that reads back as the same double).
python3 scripts/export_inp.py "$tmp/mb_tet/t.h5" -o "$tmp/mb_tet/t.inp" >/dev/null 2>&1 \
  && python3 scripts/import_mesh.py "$tmp/mb_tet/t.inp" -o "$tmp/mb_tet/rt.dat" --feps "$feps" >/dev/null 2>&1 \
  && "$feps" "$tmp/mb_tet/rt.dat" --quiet --output "$tmp/mb_tet/rt.h5" >/dev/null 2>&1 \
  && python3 -c 'import sys, h5py, numpy as np
u = [h5py.File(p)["steps/0001/displacement"][...] for p in sys.argv[1:3]]
sys.exit(not (u[0].shape == u[1].shape and np.array_equal(u[0], u[1]) and np.abs(u[0]).max() > 0))' \
    "$tmp/mb_tet/t.h5" "$tmp/mb_tet/rt.h5" \
  && ok "SE1 in tet4 through export_inp.py and import_mesh.py: the same displacements bit for bit" \
  || bad "SE1 in tet4 through export_inp.py and import_mesh.py: different displacements"
python3 scripts/make_model_b.py --outdir "$tmp/mb_tet_f" --cases SE1,FE1 --element tet4 >"$tmp/out" 2>"$tmp/err"; got=$?
[ "$got" -eq 2 ] && grep -q "quadrilateral interfaces do not fit" "$tmp/err" && ! grep -q Traceback "$tmp/err" \
  && [ ! -e "$tmp/mb_tet_f" ] && ok "make_model_b.py --element tet4 with kind F: exit 2 naming the reason, no deck written" \
  || bad "make_model_b.py --element tet4 with kind F: exit $got: $(head -c 300 "$tmp/err")"
# The study reads its quantities from a run: on the decks' own mesh the peak nodal tension is at
# its point A (r 600, theta 110, z 0), so the two columns must agree. Both ends carry the same
# load, so the mirror point at z = 2500 has the same peak to rounding and may come out first.
python3 scripts/study_mesh_modelB.py --cases SE1 --meshes hex8:1 --feps "$feps" --out "$tmp/mb_mesh" >/dev/null 2>"$tmp/err" \
  && python3 -c 'import csv, sys; r = next(csv.DictReader(open(sys.argv[1])))
peak, at_a = float(r["node_s1_max"]), float(r["s1@A"])
sys.exit(not (r["node_s1_max_at"] in ("600.0/110.00/0.0", "600.0/110.00/2500.0") and abs(at_a - peak) <= 1e-12 * peak
              and peak > 7))' \
  "$tmp/mb_mesh/results.csv" \
  && ok "study_mesh_modelB.py on SE1's own mesh: peak nodal s1 at point A" \
  || bad "study_mesh_modelB.py on SE1's own mesh: $(head -c 300 "$tmp/err") $(tail -1 "$tmp/mb_mesh/results.csv" 2>/dev/null | head -c 300)"
# Each thesis deck carries its own case's values (SPEC section 8 and thesis chapters 3-6, 9, typed
# here independently of the generators): a generator that mixed up cases would still be byte-stable.
python3 - <<'PY' >"$tmp/out" 2>&1 && ok "every thesis deck carries its case's materials, loads and steps (SPEC 8)" \
  || bad "every thesis deck carries its case's materials, loads and steps: $(tail -c 400 "$tmp/out")"
import glob, math, os, re
def records(path):
    out = []
    for line in open(path):
        line = line.split("!")[0].strip()
        if line:
            f = [x.strip() for x in line.split(",")]
            out.append((f[0].upper(), f[1:], {k.upper(): v for k, eq, v in (x.partition("=") for x in f[1:]) if eq}))
    return out
def one(recs, key, *first):
    hits = [kv for k, args, kv in recs if k == key and list(args[:len(first)]) == list(first)]
    assert len(hits) == 1, (key, first, len(hits))
    return hits[0]
def num(kv, k): return float(kv[k])
bad = []
def check(cond, what):
    if not cond: bad.append(what)
# model C: G_p x nu_p x beta (SPEC 8: steps 250/300 at 0.09, 400/500 at 0.27 for G_p 300/900)
steps_c = {(0.09, 300): 250, (0.09, 900): 300, (0.27, 300): 400, (0.27, 900): 500}
for path in sorted(glob.glob("input/modelC/*.dat")):
    G, nu, beta = (float(v) for v in re.match(r"C_G([\d.]+)_nu([-\d.]+)_b([\d.]+)\.dat", os.path.basename(path)).groups())
    r = records(path); pk = one(r, "MATERIAL", "packing"); it = one(r, "MATERIAL", "pipe_packing")
    check(num(pk, "G") == G and num(pk, "NU") == nu, f"{path}: packing")
    check((num(it, "KN"), num(it, "KS"), num(it, "PHI"), num(it, "PSI"), num(it, "C")) == (800, 400, 20, 20, 0.05), f"{path}: interface")
    c = one(r, "MATERIAL", "concrete"); s = one(r, "MATERIAL", "soil")
    check((num(c, "E"), num(c, "NU"), num(s, "E"), num(s, "NU")) == (40000, 0.2, 144, 0.2), f"{path}: concrete/soil")
    check(abs(num(one(r, "DISPLACE", "top_end_nodes"), "X") - 2500 * math.tan(math.radians(beta))) < 1e-4, f"{path}: delta")
    s1, s2 = one(r, "STAGE", "s1"), one(r, "STAGE", "s2")
    check((num(s1, "STEPS"), num(s1, "LOAD"), num(s2, "LOAD")) == (1, 0.2, 0.8), f"{path}: stage 1/2 split")
    check(num(s2, "STEPS") == steps_c[(beta, G)], f"{path}: stage 2 steps")
    check(num(one(r, "PRESSURE", "top_end"), "VALUE") == 10, f"{path}: q")
# model B: soil 1 typical, 2 soft, 3 stiff (E_s; Ks, Kn of the interface); P = 1000 kN per end
soils = {"1": (144, 50, 100), "2": (14.4, 5, 10), "3": (1440, 500, 1000)}
for path in sorted(glob.glob("input/modelB/*.dat")) + ["input/modelB.dat"]:
    case = os.path.basename(path)[:-4].replace("modelB", "FE1")
    kind, load, n = case
    es, ks, kn = soils[n]; r = records(path); s = one(r, "MATERIAL", "soil")
    check(num(s, "E") == es and num(s, "NU") == 0.2, f"{path}: soil")
    soil_kind = [a for k, a, kv in r if k == "MATERIAL" and a[0] == "soil"][0][1].upper()
    check(soil_kind == ("MATSUOKA" if kind == "P" else "ELASTIC"), f"{path}: soil model")
    if kind == "P":
        check((num(s, "PHI"), num(s, "PSI"), num(s, "C")) == (15, 15, 0.05), f"{path}: Matsuoka soil")
    if kind == "F":
        it = one(r, "MATERIAL", "pipe_soil")
        check((num(it, "KN"), num(it, "KS"), num(it, "PHI"), num(it, "PSI"), num(it, "C")) == (kn, ks, 15, 15, 0.05), f"{path}: interface")
    c = one(r, "MATERIAL", "concrete"); check((num(c, "E"), num(c, "NU")) == (40000, 0.2), f"{path}: concrete")
    hi, lo = one(r, "PRESSURE", "end_high"), one(r, "PRESSURE", "end_low")
    check((num(hi, "TOTAL"), num(hi, "ZERO"), num(hi, "PEAK")) == (1e6, -220, -715), f"{path}: upper end load")
    sign = 1 if load == "E" else -1
    check((num(lo, "TOTAL"), num(lo, "ZERO"), num(lo, "PEAK")) == (1e6, -220 * sign, -715 * sign), f"{path}: lower end load")
    st = one(r, "STAGE", "load")
    if kind == "S":
        check(num(st, "STEPS") == 1, f"{path}: linear")
    else:
        check((num(st, "STEPS"), st["METHOD"], num(st, "MAXIT")) == (400 if load == "E" else 500, "initial-stiffness", 10), f"{path}: steps")
# model A: r_i 75 / 85.7, E = 31700, nu = 0.2, P = 5 kN on each end
for path in sorted(glob.glob("input/modelA/*.dat")):
    r = records(path); c = one(r, "MATERIAL", "concrete")
    check((num(c, "E"), num(c, "NU")) == (31700, 0.2), f"{path}: concrete")
    first = [a for k, a, kv in r if k == "A"][0]
    check(float(first[1]) == (75 if "thick" in path else 85.7), f"{path}: inner radius")
    loads = [kv for k, a, kv in r if k == "PRESSURE"]
    check(len(loads) == 2 and all(num(kv, "TOTAL") == 5000 for kv in loads), f"{path}: P")
# chapter 3: G_p x nu_p x beta (x stiff interface), q = 30, delta = 150 tan(beta), 400 modified Euler steps
for path in sorted(glob.glob("input/joint2d/*.dat")):
    m = re.match(r"G([\d.]+)_nu([-\d.]+)_b([\d.]+)(_stiff)?\.dat", os.path.basename(path))
    G, nu, beta = (float(v) for v in m.groups()[:3]); stiff = bool(m.group(4)); r = records(path)
    pk, it, c = one(r, "MATERIAL", "packer"), one(r, "MATERIAL", "joint"), one(r, "MATERIAL", "concrete")
    check(num(pk, "G") == G and num(pk, "NU") == nu and (num(c, "G"), num(c, "NU")) == (40000, 0.2), f"{path}: solids")
    check((num(it, "KN"), num(it, "KS"), num(it, "PHI"), num(it, "PSI")) == ((8000, 4000) if stiff else (800, 400)) + (20, 20), f"{path}: interface")
    check(abs(num(one(r, "DISPLACE", "top"), "X") - 150 * math.tan(math.radians(beta))) < 1e-6, f"{path}: delta")
    st = one(r, "STAGE", "load"); check((num(st, "STEPS"), st["METHOD"]) == (400, "modified-euler"), f"{path}: steps")
    check(num(one(r, "PRESSURE", "top_face"), "VALUE") == 30, f"{path}: q")
# chapter 9: Matsuoka concrete, 50 kN on the quarter, 400 modified NR steps; hoop bars; band
for path in sorted(glob.glob("input/chapter9/*.dat")):
    case = os.path.basename(path)[:-4]; r = records(path); c = one(r, "MATERIAL", "concrete")
    check((num(c, "E"), num(c, "NU"), num(c, "PHI"), num(c, "PSI"), num(c, "FT")) == (31700, 0.22, 54.9, 54.9, 5), f"{path}: concrete")
    check(num(one(r, "PRESSURE", "top"), "TOTAL") == 50000 and one(r, "CONTROLS")["METHOD"] == "modified-newton-raphson", f"{path}: load/method")
    check(num(one(r, "STAGE", "load"), "STEPS") == 400, f"{path}: steps")
    if case.startswith("RE"):
        b = one(r, "MATERIAL", "hoop_bar"); check((num(b, "E"), num(b, "A")) == (200000, 6.28), f"{path}: bars")
    if case.startswith("PR"):
        check(num(one(r, "PRESSURE", "band"), "VALUE") == {"PR1": 5, "PR2": 1}[case], f"{path}: q")
        check(num(one(r, "STAGE", "prestress"), "STEPS") == 50, f"{path}: stage 1 steps")
        check((num(one(r, "MATERIAL", "band_edge"), "A"), num(one(r, "MATERIAL", "band_middle"), "A")) == (4.5, 9), f"{path}: band")
assert not bad, bad
print("checked", len(glob.glob("input/*/*.dat")) + 1, "decks")
PY
# CR with the continuous tension rule in 5 full-Newton steps: every step converged, no cut-back
python3 scripts/make_chapter9.py --outdir "$tmp/c9cp" --steps 5 --tension closest-point \
  --method full-newton-raphson >/dev/null
"$feps" "$tmp/c9cp/CR.dat" --output "$tmp/c9cp.h5" >"$tmp/out" 2>&1 \
  && grep -q "nonlinear: 5 steps, 17 iterations, .* 0 cut-backs, 0 steps not converged" "$tmp/out" \
  && ok "CR, TENSION=closest-point: 5 full-Newton steps converge in 17 iterations (README)" \
  || bad "CR, TENSION=closest-point: 5 full-Newton steps converge: $(grep analysis "$tmp/out")"
# A list that starts with a negative ratio (auxetic packing, the thesis's -0.3) is a list, not an option.
python3 scripts/make_model_c.py --outdir "$tmp/mc_neg" --Gp 300 --nup -0.3,0.4 --beta 0.09 >/dev/null 2>"$tmp/err" \
  && [ -f "$tmp/mc_neg/C_G300_nu-0.3_b0.09.dat" ] && [ -f "$tmp/mc_neg/C_G300_nu0.4_b0.09.dat" ] \
  && ok "make_model_c.py --nup -0.3,0.4 writes both decks" || bad "make_model_c.py --nup -0.3,0.4: $(head -c 300 "$tmp/err")"
expect_status "make_model_c.py --nup 0.5" 2 python3 scripts/make_model_c.py --outdir "$tmp/x" --nup 0.5
grep -q "nu_p = 0.5" "$tmp/err" && ok "the error names nu_p" || bad "the error names nu_p: $(head -c 300 "$tmp/err")"
# The joint interface's dilation angle: psi = 20 is the thesis's deck, any other is named
# _psi<psi> and differs from it only in PSI (and its name, comments and PARAMETERS).
python3 scripts/make_model_c.py --outdir "$tmp/mc_psi" --Gp 900 --nup 0.4 --beta 0.27 --psi 0,20 >/dev/null \
  && cmp -s input/modelC/C_G900_nu0.4_b0.27.dat "$tmp/mc_psi/C_G900_nu0.4_b0.27.dat" \
  && diff <(grep -v '^!\|^TITLE\|^PARAMETERS\|^REPORT\|^OUTPUT' input/modelC/C_G900_nu0.4_b0.27.dat | sed 's/PSI=20\./PSI=0./') \
          <(grep -v '^!\|^TITLE\|^PARAMETERS\|^REPORT\|^OUTPUT' "$tmp/mc_psi/C_G900_nu0.4_b0.27_psi0.dat") >/dev/null \
  && grep -q "^PARAMETERS, .*, psi_joint=0$" "$tmp/mc_psi/C_G900_nu0.4_b0.27_psi0.dat" \
  && python3 -c "import sys; sys.path.insert(0, 'scripts'); import make_model_c as m
assert m.parse_case('C_G900_nu0.4_b0.27_Es1440_psi0') == (900, 0.4, 0.27, 1440, 0)
for bad in ('C_G900_nu0.4_b0.27_psi0_Es1440', 'C_G900_nu0.4_b0.27_psi0_psi5', 'C_G900_nu0.4_b0.27_x1'):
    try: m.parse_case(bad)
    except ValueError: pass
    else: raise SystemExit(bad)" \
  && ok "make_model_c.py --psi 0,20: the thesis's deck and one with PSI=0. only; case names parse" \
  || bad "make_model_c.py --psi 0,20: the thesis's deck and one with PSI=0. only; case names parse"
expect_status "make_model_c.py --psi 25" 2 python3 scripts/make_model_c.py --outdir "$tmp/x" --psi 25
grep -q "psi = 25" "$tmp/err" && ok "the error names psi" || bad "the error names psi: $(head -c 300 "$tmp/err")"
expect_status "make_model_b.py --psi above --phi" 2 python3 scripts/make_model_b.py --outdir "$tmp/x" --soil-E 144 \
  --phi 10 --psi 20
python3 scripts/make_model_b.py --outdir "$tmp/mb_grid" --kinds F,S --loads E --soil-E 144,50 >/dev/null
model_lines() { grep -v '^!\|^TITLE\|^REPORT\|^OUTPUT' "$1"; }
diff <(model_lines input/modelB/FE1.dat) <(model_lines "$tmp/mb_grid/FE_Es144_phi15.dat") >/dev/null \
  && ok "model B grid: FE_Es144_phi15 is FE1's model" || bad "model B grid: FE_Es144_phi15 is FE1's model"
# Soil stiffness lowers the pipe's peak tension (thesis 5.3.1: SE2 > SE1 > SE3): E_s = 50 lies
# between E_s = 14.4 (SE2) and 144 (SE1).
for c in SE1 SE2; do "$feps" input/modelB/$c.dat --output "$tmp/p_$c.h5" --quiet >/dev/null 2>&1; done
"$feps" "$tmp/mb_grid/SE_Es50.dat" --output "$tmp/p_SE50.h5" --quiet >/dev/null 2>&1
python3 - "$tmp/p_SE2.h5" "$tmp/p_SE50.h5" "$tmp/p_SE1.h5" <<'PY' && ok "SE_Es50's peak tension lies between SE2's and SE1's; its PARAMETERS are in /summary" \
  || bad "SE_Es50's peak tension lies between SE2's and SE1's; its PARAMETERS are in /summary"
import sys, h5py
def peak(p):
    with h5py.File(p) as f:
        return f["steps"][sorted(f["steps"], key=int)[-1]]["principal/pipe"][:, 0].max()
soft, mid, typical = (peak(p) for p in sys.argv[1:4])
print(f"    peak s1: E_s = 14.4 {soft:.3f}, 50 {mid:.3f}, 144 {typical:.3f} MPa")
assert soft > mid > typical
with h5py.File(sys.argv[2]) as f:       # the deck's PARAMETERS record, in /summary
    a = f["summary"].attrs
    assert float(a["parameter_E_s"]) == 50.0 and a["parameter_kind"] in (b"S", "S"), dict(a)
PY

# A parametric campaign end to end: decks with PARAMETERS, campaign.sh's CSV has their columns,
# plot_campaign.py draws the trend (and names a column the CSV lacks).
camp="check_cli_sweep_$$"
FEPS="$feps_abs" JOBS=2 bash scripts/campaign.sh "$camp" "$tmp/mb_grid/SE_Es144.dat" "$tmp/mb_grid/SE_Es50.dat" \
  >"$tmp/out" 2>&1
python3 - "results/$camp/summary.csv" <<'PY' && ok "campaign.sh: one column per PARAMETERS value" \
  || bad "campaign.sh: one column per PARAMETERS value: $(cat "results/$camp/summary.csv" 2>/dev/null | head -3)"
import csv, sys
rows = {r["case"]: r for r in csv.DictReader(open(sys.argv[1]))}
assert rows["SE_Es50"]["E_s"] == "50" and rows["SE_Es144"]["kind"] == "S", rows
assert float(rows["SE_Es50"]["peak_tensile_pipe_MPa"]) > float(rows["SE_Es144"]["peak_tensile_pipe_MPa"])
PY
python3 scripts/plot_campaign.py "results/$camp/summary.csv" --x E_s --y peak_tensile_pipe_MPa -o "$tmp/trend.png" \
  >"$tmp/out" 2>&1 && [ -s "$tmp/trend.png" ] && ok "plot_campaign.py draws the trend" || bad "plot_campaign.py draws the trend: $(cat "$tmp/out")"
python3 scripts/plot_campaign.py "results/$camp/summary.csv" --x E_s --y nu_p -o "$tmp/none.png" >"$tmp/out" 2>&1; got=$?
[ "$got" -ne 0 ] && grep -q "no column(s) \['nu_p'\]" "$tmp/out" && [ ! -e "$tmp/none.png" ] \
  && ok "plot_campaign.py names a missing column" || bad "plot_campaign.py names a missing column: $(cat "$tmp/out")"
rm -rf "results/$camp"

# The prestress study end to end, 2 steps: CR and a q = 1 MPa band built both ways (PRESTRESS for
# the pretensioned one); the band lowers the external layer's peak tension (thesis 9.3, PR2).
camp="check_cli_prestress_$$"
FEPS="$feps_abs" JOBS=2 python3 scripts/study_prestress.py --q 1 --steps 2 --name "$camp" >"$tmp/out" 2>&1
python3 - "results/$camp/prestress.csv" <<'PY' && [ -s "results/$camp/prestress.png" ] \
  && ok "study_prestress.py: a q = 1 band, both ways, against CR" || bad "study_prestress.py: $(tail -5 "$tmp/out")"
import csv, sys
rows = {r["case"]: r for r in csv.DictReader(open(sys.argv[1]))}
cr = float(rows["CR"]["max_s1_external"])
for band in ("pressure", "pretensioned"):
    assert float(rows[f"PR_{band}_q1"]["max_s1_external"]) < cr, rows
PY
rm -rf "results/$camp"

# The scripts: an ordinary mistake is one line on stderr ('prog: ...') and a non-zero exit (2 for
# bad arguments), never a traceback; argparse's own errors exit 2 with its usage line.
expect_line() {  # name expected-status pattern command...: that status, one stderr line matching pattern
  local name=$1 want=$2 pat=$3; shift 3
  "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  if [ "$got" -eq "$want" ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q -- "$pat" "$tmp/err"; then
    ok "$name (exit $got, one line)"
  else
    bad "$name: exit $got, expected $want and one line matching '$pat': $(head -c 300 "$tmp/err")"
  fi
}
expect_arg_error() {  # name pattern command...: argparse's exit 2 naming the problem, no traceback
  local name=$1 pat=$2; shift 2
  "$@" >"$tmp/out" 2>"$tmp/err"; local got=$?
  if [ "$got" -eq 2 ] && grep -q -- "$pat" "$tmp/err" && ! grep -q Traceback "$tmp/err"; then ok "$name (exit 2)"
  else bad "$name: exit $got, expected 2 and '$pat': $(head -c 300 "$tmp/err")"; fi
}
for s in campaign campaign_modelB campaign_modelC; do
  bash scripts/$s.sh --help >"$tmp/out" 2>&1 && grep -q "^Exit status\|exit status" "$tmp/out" && ! grep -q "^set -\|ROOT=" "$tmp/out" \
    && ok "$s.sh --help prints the header, exit 0" || bad "$s.sh --help: $(head -c 300 "$tmp/out")"
done
# campaign.sh with FEPS a relative path (each case runs in its own folder) and a case that fails:
# the CSV is gathered, the failed case named, exit 1.
sed 's/MAXIT=200/MAXIT=3/' test/data/unzip.dat >"$tmp/unzip3.dat"
camp="check_cli_fail_$$"
FEPS="$feps" JOBS=1 bash scripts/campaign.sh "$camp" test/data/cube.dat "$tmp/unzip3.dat" >"$tmp/out" 2>"$tmp/err"; got=$?
[ "$got" -eq 1 ] && grep -q "^cube,ok," "results/$camp/summary.csv" && grep -q "^unzip3,failed,1," "results/$camp/summary.csv" \
  && grep -q "campaign: 1 of 2 cases not finished: unzip3 (failed)" "$tmp/err" \
  && ok "campaign.sh, relative FEPS: a failed case gives exit 1 after the CSV" \
  || bad "campaign.sh, relative FEPS, a failed case: exit $got, $(head -c 300 "$tmp/err")"
rm -rf "results/$camp"
# campaign_modelC.sh --feps with a relative path, from another folder: a stand-in feps that passes
# --check and writes a (non-HDF5) result; the case runs, the post-processing refuses the file in
# one line, and the campaign exits 1.
mkdir -p "$tmp/fake"
cat >"$tmp/fake/feps" <<'SH'
#!/bin/sh
out=""
while [ $# -gt 0 ]; do case "$1" in --check) exit 0 ;; --output) out=$2; shift ;; esac; shift; done
echo "not HDF5" >"$out"; echo "results $out"
SH
chmod +x "$tmp/fake/feps"
(cd "$tmp" && bash "$OLDPWD/scripts/campaign_modelC.sh" -o "$tmp/mcfake" --cases C_G300_nu0.1_b0.09 --feps fake/feps) \
  >"$tmp/out" 2>"$tmp/err"; got=$?
[ "$got" -eq 1 ] && grep -q "C_G300_nu0.1_b0.09 .* exit 0" "$tmp/mcfake/C_G300_nu0.1_b0.09/time.txt" \
  && grep -q "postprocess_model_c: .*not an HDF5 file" "$tmp/err" && ! grep -q Traceback "$tmp/err" \
  && ok "campaign_modelC.sh --feps RELATIVE runs the case; a failed post-processing gives exit 1" \
  || bad "campaign_modelC.sh --feps RELATIVE: exit $got, $(head -c 300 "$tmp/err")"
expect_line "study_tradeoff.py --feps that does not exist" 2 "^study_tradeoff: --feps" \
  python3 scripts/study_tradeoff.py --quick --feps "$tmp/no_feps" --out "$tmp/trade"
[ ! -e "$tmp/trade" ] && ok "  ... and writes nothing" || bad "  ... and writes nothing"
expect_arg_error "study_tradeoff.py --scenes bogus" "invalid choice: 'bogus'" python3 scripts/study_tradeoff.py --scenes bogus
expect_line "study_tradeoff.py --compare a missing folder" 2 "no folder" \
  python3 scripts/study_tradeoff.py --compare "$tmp/no_such_dir"
expect_line "postprocess_model_c.py, a missing file" 2 "^postprocess_model_c: no result file" \
  python3 scripts/postprocess_model_c.py "$tmp/no.h5"
expect_line "postprocess_model_c.py, a model B result" 1 "not a model C result" \
  python3 scripts/postprocess_model_c.py "$tmp/b_cholmod.h5"
mkdir -p "$tmp/empty"
expect_line "postprocess_model_c.py --statics on an empty folder" 1 "no model C results in" \
  python3 scripts/postprocess_model_c.py --statics "$tmp/empty"
expect_line "postprocess_model_c.py --table without the benchmarks" 2 "no benchmarks folder .*FEPS_BENCHMARKS" \
  env FEPS_BENCHMARKS="$tmp/no_bench" python3 scripts/postprocess_model_c.py --table "$tmp/empty"
expect_line "compare_thesis.py without the benchmarks" 2 "no benchmarks folder .*FEPS_BENCHMARKS" \
  env FEPS_BENCHMARKS="$tmp/no_bench" python3 scripts/compare_thesis.py table2.2
expect_line "plot_stress_maps.py --group bogus" 2 "no solid group 'bogus' (the file has: pipe, soil)" \
  python3 scripts/plot_stress_maps.py --h5 "$tmp/b_cholmod.h5" --group bogus --out "$tmp/m.png"
expect_line "plot_stress_maps.py, a missing --h5" 2 "no result file" \
  python3 scripts/plot_stress_maps.py --h5 "$tmp/no.h5" --out "$tmp/m.png"
expect_arg_error "plot_stress_maps.py --norm 0" "argument --norm" \
  python3 scripts/plot_stress_maps.py --h5 "$tmp/b_cholmod.h5" --norm 0 --out "$tmp/m.png"
# --source nodes: the nodal_interface field; under a linear pressure its sigma_n reaches the
# edge's -p = -1.5 MPa, where the Gauss points stop at -1.394.
"$feps" test/data/block_contact_nodal.dat --quiet --output "$tmp/bcn.h5" \
  && python3 scripts/plot_interface_maps.py --h5 "$tmp/bcn.h5" --group joint --norm 1 --source nodes --state \
       --out "$tmp/bcn.png" >"$tmp/out" 2>&1 && grep -q "(face, 9 nodes): sigma_n/q min -1.5000 " "$tmp/out" \
  && ok "plot_interface_maps.py --source nodes: sigma_n at the nodes reaches -p at the edge" \
  || bad "plot_interface_maps.py --source nodes: $(head -c 300 "$tmp/out")"
expect_line "plot_interface_maps.py --source nodes without the nodal_interface field" 2 "FIELDS names nodal_interface" \
  python3 scripts/plot_interface_maps.py --h5 "$tmp/main.h5" --group contact --source nodes --out "$tmp/m.png"
expect_line "plot_interface_maps.py --step 99" 2 "no step 0099" \
  python3 scripts/plot_interface_maps.py --h5 "$tmp/main.h5" --group contact --step 99 --out "$tmp/m.png"
# Issue 5's figures 7.7-7.8: model C's total joint deformation, on a coarse model C (24 deg elements,
# 2 stage-2 steps, 1 equilibrium step: seconds). Its beta_bar must be postprocess_model_c.py's.
python3 scripts/make_model_c.py --outdir "$tmp/mc_small" --cases C_G300_nu0.1_b0.09 --steps 2 --theta-step 24 >/dev/null \
  && sed -i 's/^STAGE, s3, STEPS=100,/STAGE, s3, STEPS=1,/' "$tmp/mc_small/C_G300_nu0.1_b0.09.dat" \
  && "$feps" "$tmp/mc_small/C_G300_nu0.1_b0.09.dat" --output "$tmp/mc_small/C_G300_nu0.1_b0.09.h5" --quiet \
  && python3 scripts/plot_joint_deformation.py --joint-total --h5 "$tmp/mc_small/C_G300_nu0.1_b0.09.h5" \
       --out "$tmp/fig7_7.png" >"$tmp/out" 2>&1 && [ -s "$tmp/fig7_7.png" ] \
  && python3 - "$tmp/mc_small/C_G300_nu0.1_b0.09.h5" "$tmp/out" <<'PY' 2>/dev/null \
  && ok "plot_joint_deformation.py --joint-total (Figures 7.7-7.8): beta_bar as postprocess_model_c.py" \
  || bad "plot_joint_deformation.py --joint-total (Figures 7.7-7.8): $(head -c 300 "$tmp/out")"
import re, sys
sys.path.insert(0, "scripts")
import postprocess_model_c as pmc
printed = float(re.search(r"beta_bar \(x >= 250\) = ([0-9.]+) deg", open(sys.argv[2]).read()).group(1))
want = pmc.postprocess(sys.argv[1], verbose=False)["beta_bar"]
sys.exit(0 if abs(printed - want) <= 5e-6 else 1)
PY
# beta_bar takes the interface's elastic closure sigma_n / Kn out of w at A-A, with sigma_n
# feps's nodal_interface (extrapolated from each interface element's Gauss points to its nodes). Where the joint is
# elastic and closed (every point of the coarse case on r = 715, x >= 250: beta = 0.09) that is
# the nodal jump itself, so the reading equals the one that takes out the whole relative
# displacement; at sliding points they differ by the dilatant opening (docs/verification.md).
python3 - "$tmp/mc_small/C_G300_nu0.1_b0.09.h5" <<'PY' >"$tmp/out" 2>"$tmp/err" \
  && ok "model C beta_bar: the elastic closure from the extrapolated sigma_n is the nodal jump where the joint is elastic ($(cat "$tmp/out"))" \
  || bad "model C beta_bar: elastic closure against the nodal jump: $(head -c 300 "$tmp/out") $(head -c 300 "$tmp/err")"
import sys
sys.path.insert(0, "scripts")
import postprocess_model_c as pmc
r = pmc.postprocess(sys.argv[1], verbose=False)
print(f"{r['beta_bar']:.10f} = {r['beta_bar_whole_jump']:.10f} deg, nothing taken out {r['beta_bar_raw']:.6f}")
sys.exit(0 if abs(r["beta_bar"] - r["beta_bar_whole_jump"]) <= 1e-12 and
         abs(r["beta_bar"] - r["beta_bar_raw"]) > 1e-4 else 1)
PY
# Equilibrium of the written fields (test/reference/check_equilibrium.py: nodal forces assembled with its
# own shape functions from the stresses, tractions and reactions): the main job (FE1: hex8 and
# interfaces, residual carried), SE1 (linear) and the coarse model C (packing, interface, soil).
for h5 in main.h5 b_cholmod.h5 mc_small/C_G300_nu0.1_b0.09.h5; do
  python3 test/reference/check_equilibrium.py "$tmp/$h5" >"$tmp/out" 2>&1 \
    && ok "check_equilibrium.py $h5: $(grep -c ': PASS' "$tmp/out") checks pass" \
    || bad "check_equilibrium.py $h5: $(grep -v ': PASS' "$tmp/out" | head -c 400)"
done
# REPORT, REACTION of the model C decks: the top end's fx is the H that postprocess_model_c.py's
# statics sums from the written reactions of the top pipe's end nodes.
python3 -W ignore - "$tmp/mc_small/C_G300_nu0.1_b0.09.h5" <<'PY' >"$tmp/out" 2>"$tmp/err" \
  && ok "model C REPORT top_end: fx = postprocess_model_c.py's H ($(cat "$tmp/out"))" \
  || bad "model C REPORT top_end against postprocess_model_c.py's H: $(head -c 300 "$tmp/out") $(head -c 300 "$tmp/err")"
import sys
import h5py
sys.path.insert(0, "scripts")
import postprocess_model_c as pmc
with h5py.File(sys.argv[1]) as f:
    fx = float(f["summary"].attrs["reaction_top_end_fx"])
H = pmc.top_pipe_statics(sys.argv[1])["H"]
print(f"{fx:.6g} N against {H:.6g} N")
sys.exit(0 if abs(fx - H) <= 1e-9 * abs(H) and abs(H) > 0 else 1)
PY
expect_line "plot_joint_deformation.py --joint-total on a model B result" 2 "not a model C result" \
  python3 scripts/plot_joint_deformation.py --joint-total --h5 "$tmp/main.h5" --out "$tmp/m.png"
# beta_bar reads the interface's normal stress at the nodes (feps's nodal_interface) as well as
# the displacements: a result written without it (FIELDS) is named, not a traceback.
cp "$tmp/mc_small/C_G300_nu0.1_b0.09.h5" "$tmp/mc_no_joint.h5" && python3 - "$tmp/mc_no_joint.h5" <<'PY'
import sys, h5py
with h5py.File(sys.argv[1], "a") as f:
    del f["steps"][sorted(f["steps"], key=int)[-1]]["nodal_interface/joint"]
PY
expect_line "plot_joint_deformation.py --joint-total on a model C result without the interface's nodal stresses" 2 \
  "no /steps/[0-9]*/nodal_interface/joint" \
  python3 scripts/plot_joint_deformation.py --joint-total --h5 "$tmp/mc_no_joint.h5" --out "$tmp/m.png"
# The maps' q: a model B or C result's own (4.21, 10 MPa), any other file must be given --norm
# (it used to be 4.21 for every file: model A, C and chapter 9 maps silently divided by model B's).
for case in "b_cholmod.h5 pipe 4.21" "mc_small/C_G300_nu0.1_b0.09.h5 top_pipe 10"; do
  read -r h5 group q <<<"$case"
  rm -f "$tmp/out1" "$tmp/out2"
  python3 scripts/plot_stress_maps.py --h5 "$tmp/$h5" --group "$group" --out "$tmp/m1.png" >"$tmp/out1" 2>&1 \
    && python3 scripts/plot_stress_maps.py --h5 "$tmp/$h5" --group "$group" --norm "$q" --out "$tmp/m2.png" >"$tmp/out2" 2>&1 \
    && [ "$(sed 's/ -> .*//' "$tmp/out1")" = "$(sed 's/ -> .*//' "$tmp/out2")" ] \
    && ok "plot_stress_maps.py without --norm on $h5 divides by q = $q" \
    || bad "plot_stress_maps.py's q of $h5: $(head -c 300 "$tmp/out1") / $(head -c 300 "$tmp/out2")"
done
# feps's nodal averages (FIELDS nodal_stress) against plot_stress_maps.py's own extrapolation,
# written independently (Lagrange products in numpy, not feps's monomial solve): hex8, hex20 with
# 27 points, hex20r with 8; the same numbers to 1e-10 of the largest.
sed 's/TYPE=hex20,/TYPE=hex20r,/' test/data/bending_hex20.dat >"$tmp/bending_hex20r.dat"
cp test/data/lame_hex8.dat "$tmp/lame_hex8_nodal.dat" && echo "FIELDS, all, nodal_stress" >>"$tmp/lame_hex8_nodal.dat"
"$feps" test/data/lame_hex20_nodal.dat --quiet --output "$tmp/n_hex20.h5" \
  && "$feps" "$tmp/bending_hex20r.dat" --quiet --output "$tmp/n_hex20r.h5" \
  && "$feps" "$tmp/lame_hex8_nodal.dat" --quiet --output "$tmp/n_hex8.h5" \
  && python3 - "$tmp/n_hex20.h5" "$tmp/n_hex20r.h5" "$tmp/n_hex8.h5" <<'PY' >"$tmp/out" 2>&1 \
  && ok "nodal_stress of hex20, hex20r and hex8 = test/reference/element_rules.py's own extrapolation ($(cat "$tmp/out"))" \
  || bad "nodal_stress against element_rules.py's extrapolation: $(head -c 300 "$tmp/out")"
import sys
import h5py
import numpy as np
sys.path.insert(0, "scripts")
import feps_results as fr
sys.path.insert(0, "test/reference")
import element_rules as er
worst = 0.0
for path in sys.argv[1:]:
    with h5py.File(path) as f:
        step = fr.last_step(f)
        for g in f[f"steps/{step}/nodal_stress"]:
            ds = f[f"steps/{step}/stress/{g}"]
            ppe = int(ds.attrs["points_per_element"])
            ext = er.extrapolation_matrix(fr.element_type(f, g), ppe)
            conn = fr.connectivity(f, g)
            nodal = np.einsum("ng,egc->enc", ext, ds[...].reshape(-1, ppe, 6))
            sums = np.zeros((f["mesh/coordinates"].shape[0], 6))
            np.add.at(sums, conn.ravel(), nodal.reshape(-1, 6))
            count = np.bincount(conn.ravel(), minlength=len(sums))
            used = count > 0
            own = sums[used] / count[used, None]
            got = f[f"steps/{step}/nodal_stress/{g}"][...]
            worst = max(worst, np.abs(own - got[used]).max() / np.abs(got).max())
            # nodes of no element of the group hold each column's smallest value over it
            if (~used).any() and not (got[~used] == got[used].min(axis=0)).all():
                worst = 1.0
print(f"largest difference {worst:.1e} of the largest stress")
sys.exit(0 if worst <= 1e-10 else 1)
PY
expect_line "plot_stress_maps.py without --norm on a file of no thesis model" 2 "give --norm" \
  python3 scripts/plot_stress_maps.py --h5 "$tmp/beam.h5" --out "$tmp/m.png"
expect_line "plot_interface_maps.py without --norm on a file of no thesis model" 2 "give --norm" \
  python3 scripts/plot_interface_maps.py --h5 "$tmp/beam.h5" --out "$tmp/m.png"
# Issue 5's interface of joint_models.py: exactly one line per model, 'MODEL Z=<mm> sigma_max=<MPa>'.
python3 scripts/joint_models.py --beta 0.2061 --a 15 --Ep 660 --P 4750873.49 --L 2500 --Ec 40000 --R 715 --r 600 \
  >"$tmp/out" 2>&1 && [ "$(wc -l <"$tmp/out")" -eq 2 ] \
  && grep -qx "australian Z=767.86 sigma_max=32.409" "$tmp/out" && grep -qx "haslem Z=504.67 sigma_max=43.709" "$tmp/out" \
  && ok "joint_models.py prints 'australian Z=.. sigma_max=..' and 'haslem Z=.. sigma_max=..'" \
  || bad "joint_models.py line format: $(head -c 300 "$tmp/out")"
printf 'case,nu_p,sigma_max,status\na,-0.3,20.1,ok\nb,0.1,21.5,ok\n' >"$tmp/pc.csv"
expect_line "plot_campaign.py --logx with nu_p = -0.3" 1 "row a: column 'nu_p' is -0.3" \
  python3 scripts/plot_campaign.py "$tmp/pc.csv" --x nu_p --y sigma_max --logx -o "$tmp/pc.png"
python3 scripts/plot_campaign.py "$tmp/pc.csv" --x nu_p --y sigma_max -o "$tmp/new/folder/pc.png" >/dev/null 2>&1 \
  && [ -s "$tmp/new/folder/pc.png" ] && ok "plot_campaign.py -o makes a missing folder" || bad "plot_campaign.py -o makes a missing folder"
expect_line "export_inp.py, a missing HDF5 file" 2 "export_inp: error: no HDF5 file" \
  python3 scripts/export_inp.py "$tmp/no.h5" -o "$tmp/x.inp"
python3 scripts/export_inp.py --help | grep -q -- "--print-nodes" && bad "export_inp.py --help: no --print-nodes" \
  || ok "export_inp.py --help: no --print-nodes"
# A unit slip (E in Pa) is a warning, not an error: one stderr line naming file, line, field and
# material, as soon as the deck is read; the run goes on and writes its results; --quiet is silent.
sed 's/E=200000\./E=2.0e11/' test/data/cube.dat >"$tmp/cube_pa.dat"
"$feps" "$tmp/cube_pa.dat" --output "$tmp/cube_pa.h5" >"$tmp/out" 2>"$tmp/err"; st=$?
[ $st -eq 0 ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && [ -s "$tmp/cube_pa.h5" ] \
  && grep -q "^feps: warning: $tmp/cube_pa.dat:15: field 4: material steel: E = 2.000E+11 MPa is above 1e6 MPa" "$tmp/err" \
  && ok "E in Pa: one warning line naming file, line, field and material; the run goes on" \
  || bad "E in Pa warning: exit $st: $(head -c 300 "$tmp/err")"
"$feps" "$tmp/cube_pa.dat" --output "$tmp/cube_pa.h5" --quiet >"$tmp/out" 2>"$tmp/err" && [ ! -s "$tmp/err" ] && [ ! -s "$tmp/out" ] \
  && ok "E in Pa with --quiet: nothing printed" || bad "E in Pa with --quiet printed: $(head -c 300 "$tmp/err")"
# REPORT, SECTION on model B SE1 and SD1 (issue 26): the forces and moments through two sections
# of the whole model equal the applied loads and reactions on the nodes at or above each plane
# (by every node's equilibrium), to 1e-6 of the largest; the pipe's own section is printed too.
for d in SE1 SD1; do
  { cat "input/modelB/$d.dat"; printf 'REPORT, SECTION, NAME=cut, Z=650.\nREPORT, SECTION, NAME=cut2, Z=2100.\nREPORT, SECTION, NAME=pipe650, GROUP=pipe, Z=650.\n'; } >"$tmp/sec_$d.dat"
  sed -i "s#^INCLUDE, #INCLUDE, $PWD/input/modelB/#" "$tmp/sec_$d.dat"
  "$feps" "$tmp/sec_$d.dat" --quiet --output "$tmp/sec_$d.h5" >"$tmp/out" 2>"$tmp/err"
  python3 - "$tmp/sec_$d.h5" <<'PY' && ok "REPORT, SECTION on $d: N, Vx, Vy, Mx, My, T = the loads at or above z = 650 and 2100 (1e-6)" \
    || bad "REPORT, SECTION on $d: $(head -c 300 "$tmp/err")"
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1]) as f:
    x = f["mesh/coordinates"][()]
    s = f["steps"][sorted(f["steps"], key=int)[-1]]
    fa = s["applied_force"][()] + s["reaction"][()]
    for name, z0 in (("cut", 650.0), ("cut2", 2100.0)):
        at = x[:, 2] > z0 - 1e-6
        ref = np.r_[fa[at].sum(0), np.cross(x[at] - [0.0, 0.0, z0], fa[at]).sum(0)]
        got = np.array([f["summary"].attrs[f"section_{name}_{q}"] for q in ("Vx", "Vy", "N", "Mx", "My", "T")])
        scale = np.r_[[np.abs(ref[:3]).max()] * 3, [np.abs(ref[3:]).max()] * 3]
        assert (np.abs(got - ref) <= 1e-6 * scale).all(), (name, got, ref)
    assert "section_pipe650_N" in f["summary"].attrs
PY
done
# plot_stress_maps.py --field hoop reads feps's stress_cyl: its peak is the hoop stress a hand
# rotation of the Cartesian stress gives at that Gauss point (SE1, inner surface, 4 digits).
"$feps" input/modelB/SE1.dat --quiet --fields all,stress_cyl --output "$tmp/se1cyl.h5" >/dev/null 2>&1
python3 scripts/plot_stress_maps.py --h5 "$tmp/se1cyl.h5" --field hoop --out "$tmp/hoop.png" >"$tmp/out" 2>"$tmp/err" \
  && python3 - "$tmp/se1cyl.h5" "$tmp/out" <<'PY' && ok "plot_stress_maps.py --field hoop: the peak is the hand-rotated hoop stress there" \
    || bad "plot_stress_maps.py --field hoop: $(head -c 300 "$tmp/err") $(head -c 300 "$tmp/out")"
import re, sys
import h5py
import numpy as np
line = open(sys.argv[2]).read()
q, theta, z = (float(v) for v in re.search(r"q = (\S+) MPa at theta=(\S+) deg, z=(\S+) mm", line).groups())
with h5py.File(sys.argv[1]) as f:
    x = f["mesh/groups/pipe/points"][()]
    s = f["steps/0001/stress/pipe"][()]
r = np.hypot(x[:, 0], x[:, 1])
t = np.degrees(np.arctan2(x[:, 1], x[:, 0]))
at = np.flatnonzero((np.abs(t - theta) <= 0.05) & (np.abs(x[:, 2] - z) <= 0.05))   # the printed place
i = at[np.argmin(r[at])]                              # its Gauss point nearest the bore
c, sn = x[i, 0] / r[i], x[i, 1] / r[i]
hoop = s[i, 0] * sn**2 + s[i, 1] * c**2 - 2 * s[i, 5] * sn * c
assert abs(hoop - q) <= 1e-3 * abs(q), (hoop, q)
PY
# plot_plastic_points.py (issue 26): the states it counts are the point_state dataset's, and a
# result without point states is one line, exit 2.
"$feps" test/data/beam_point_state.dat --quiet --output "$tmp/pps.h5" >/dev/null 2>&1
python3 scripts/plot_plastic_points.py --h5 "$tmp/pps.h5" --out "$tmp/pps.png" >"$tmp/out" 2>"$tmp/err" \
  && [ -s "$tmp/pps.png" ] && python3 - "$tmp/pps.h5" "$tmp/out" <<'PY' && ok "plot_plastic_points.py counts the yielding and tension points of the dataset" \
    || bad "plot_plastic_points.py: $(head -c 300 "$tmp/err") $(head -c 300 "$tmp/out")"
import sys
import h5py
import numpy as np
with h5py.File(sys.argv[1]) as f:
    last = sorted(f["steps"], key=int)[-1]
    s = f[f"steps/{last}/point_state/beam"][()][:, 0]
line = next(l for l in open(sys.argv[2]) if l.startswith("beam (solid)"))
want = {"elastic": (s == 0).sum(), "yielding": (s == 1).sum(), "tension cut-off": (s == 3).sum()}
assert want["yielding"] + want["tension cut-off"] > 0, want
for name, n in want.items():
    assert (f"{n} {name}" in line) == (n > 0), (name, n, line)
PY
"$feps" test/data/cube.dat --quiet --output "$tmp/nops.h5" >/dev/null 2>&1
expect_line "plot_plastic_points.py on a result without point states" 2 "no point states" \
  python3 scripts/plot_plastic_points.py --h5 "$tmp/nops.h5" --out "$tmp/nops.png"
# `feps joint` is the library's joint models on the command line; joint_models.py is its front end.
"$feps" joint --beta 0.2061 --a 15 --Ep 660 --P 4750873.49 >"$tmp/fj" 2>&1 \
  && python3 scripts/joint_models.py --beta 0.2061 --a 15 --Ep 660 --P 4750873.49 --feps "$feps" >"$tmp/out" 2>&1 \
  && cmp -s "$tmp/fj" "$tmp/out" && ok "feps joint prints what joint_models.py prints" \
  || bad "feps joint against joint_models.py: $(head -c 300 "$tmp/fj")"
# --json carries the library's doubles: the values of the independent Python implementation it
# replaced (test/test_joint_models.f90, the same pins) to 1e-12.
python3 - "$feps" <<'PY' && ok "feps joint --json: Z, sigma_max, M of both models to 1e-12" || bad "feps joint --json values"
import json, subprocess, sys
out = json.loads(subprocess.run([sys.argv[1], "joint", "--beta", "0.2061", "--a", "15", "--Ep", "660", "--json"],
                                capture_output=True, text=True, check=True).stdout)
pins = {("australian", "Z"): 767.8632154555078, ("australian", "sigma_max"): 32.408766699089384,
        ("australian", "M"): 2405869653.7617483, ("haslem", "Z"): 504.666987623762,
        ("haslem", "sigma_max"): 43.70940224656189}
worst = max(abs(out[m][q] - v) / v for (m, q), v in pins.items())
p, m = out["australian"]["p_factor"], out["australian"]["m_factor"]
s = out["australian"]
sys.exit(0 if worst < 1e-12 and abs(p * s["sigma_max"] / s["P"] - 1) < 1e-14 and abs(m * s["sigma_max"] / s["M"] - 1) < 1e-14 else 1)
PY
expect_line "feps joint without --Ep" 2 "^feps: error: joint: --a and --Ep are required" "$feps" joint --beta 0.1 --a 15
expect_line "feps joint with --beta and --Z" 2 "give exactly one of --beta and --Z" "$feps" joint --beta 0.1 --Z 500 --a 15 --Ep 660
expect_line "feps joint, an unknown option" 2 'joint: unknown option "--q"' "$feps" joint --q 10 --beta 0.1 --a 15 --Ep 660
expect_line "feps joint, an option given twice" 2 "joint: --beta is given twice" "$feps" joint --beta 0.1 --beta 0.2 --a 15 --Ep 660
expect_line "feps joint, an option without its value" 2 'joint: "--Ep" is not an option with a value' "$feps" joint --beta 0.1 --a 15 --Ep
expect_line "feps joint, a negative packing modulus" 2 "joint: australian: need E_c > 0 and E_p > 0" "$feps" joint --beta 0.1 --a 15 --Ep -660
for v in nan inf; do
  expect_line "joint_models.py --beta $v" 2 "joint_models: need a finite beta" \
    python3 scripts/joint_models.py --beta $v --a 15 --Ep 660
done
expect_arg_error "joint_models.py --check with --beta (it would be ignored)" "--check takes no other option (given: --beta)" \
  python3 scripts/joint_models.py --check --beta 0.1
expect_arg_error "make_model_b.py --soil-radius 500 (inside the pipe)" "must exceed the pipe's outer radius 715" \
  python3 scripts/make_model_b.py --outdir "$tmp/x" --soil-radius 500
expect_arg_error "make_model_c.py --steps -3" "argument --steps" python3 scripts/make_model_c.py --outdir "$tmp/x" --steps -3
expect_arg_error "make_model_c.py --theta-step 0" "argument --theta-step" \
  python3 scripts/make_model_c.py --outdir "$tmp/x" --theta-step 0
[ ! -e "$tmp/x" ] && ok "  ... no deck written" || bad "  ... no deck written"
expect_arg_error "study_prestress.py --q nan" "argument --q" python3 scripts/study_prestress.py --q nan
python3 test/data/make_symmetry_decks.py --outdir "$tmp/sym" >/dev/null && cmp -s "$tmp/sym/symmetry_half.dat" test/data/symmetry_half.dat \
  && cmp -s "$tmp/sym/symmetry_full.dat" test/data/symmetry_full.dat && ok "make_symmetry_decks.py --outdir writes test/data's decks" \
  || bad "make_symmetry_decks.py --outdir writes test/data's decks"
expect_arg_error "make_symmetry_decks.py --bogus" "unrecognized arguments" python3 test/data/make_symmetry_decks.py --bogus
expect_arg_error "stability_extremes.py --only bogus" "invalid choice: 'bogus'" python3 scripts/stability_extremes.py --only bogus
# The lined hole (docs/verification.md, "A pipe in elastic ground"): the closed form's own checks
# (equilibrium and compatibility by finite differences, which the Fortran test does not repeat),
# the test's eight decks written again byte for byte, and one run compared with the closed form by
# the script (its own numpy solution, independent of the test's Fortran one).
python3 test/reference/lined_hole.py --check >"$tmp/out" 2>&1 && grep -q "^all checks pass" "$tmp/out" \
  && ok "lined_hole.py --check: the closed form's self-checks" || bad "lined_hole.py --check: $(grep FAIL "$tmp/out" | head -c 300)"
lh_ok=1
for c in bonded_2 slip_2 bonded_3 slip_3; do
  python3 test/reference/lined_hole.py --decks "$tmp/lh" --bond "${c%_*}" --dim "${c#*_}" --level 2 --name "lined_${c}d.dat" \
    >/dev/null && cmp -s "$tmp/lh/lined_${c}d.dat" "test/data/lined_${c}d.dat" || lh_ok=0
done
for c in "bonded:" "slip:--nodal" "friction:--nodal --phi 15"; do
  python3 test/reference/lined_hole.py --decks "$tmp/lh" --bond "${c%%:*}" ${c#*:} --level 1 --far uniform --rout 40 \
    --name "lined_far_${c%%:*}.dat" >/dev/null && cmp -s "$tmp/lh/lined_far_${c%%:*}.dat" "test/data/lined_far_${c%%:*}.dat" \
    || lh_ok=0
done
python3 test/reference/lined_hole.py --decks "$tmp/lh" --bond bilateral --dim 2 --level 2 --K -0.5 \
  --name lined_bilateral_2d.dat >/dev/null && cmp -s "$tmp/lh/lined_bilateral_2d.dat" test/data/lined_bilateral_2d.dat \
  || lh_ok=0
[ "$lh_ok" -eq 1 ] && ok "lined_hole.py writes test/data/lined_*.dat" || bad "lined_hole.py writes test/data/lined_*.dat"
"$feps" test/data/lined_slip_2d.dat --output "$tmp/lined_slip.h5" --quiet >/dev/null 2>&1 \
  && python3 -c 'import sys; sys.path.insert(0, "test/reference"); import lined_hole as l
e = l.compare(sys.argv[1], quiet=True)
sys.exit(not (e["s_tt bore"][0] < 1.3e-2 and e["u_r bore"][0] < 4.5e-4 and e["interface tau (/ p)"][0] < 1e-12))' \
  "$tmp/lined_slip.h5" && ok "lined_hole.py: the tri6 full-slip run against the closed form" \
  || bad "lined_hole.py: the tri6 full-slip run against the closed form"
expect_line "lined_hole.py on a missing results file" 2 "no such results file" \
  python3 test/reference/lined_hole.py "$tmp/no_such_lined.h5"
expect_line "orderings_model_a_ch9.py on an empty folder" 1 "no model A or chapter 9 results" \
  python3 scripts/orderings_model_a_ch9.py "$tmp/empty"
expect_line "bench_compare.sh with a missing deck" 2 "no deck $tmp/no_such.dat" \
  bash scripts/bench_compare.sh "$feps" "$feps" --repeat 1 "$tmp/no_such.dat"
expect_line "bench_compare.sh with a build that is not there" 2 "is not an executable" \
  bash scripts/bench_compare.sh "$tmp/no_feps" "$feps" test/data/cube.dat
expect_line "bench_solve_bound.sh with a size that is not a number of bytes" 2 \
  "usage: bash scripts/bench_solve_bound.sh" bash scripts/bench_solve_bound.sh 50MB
# The test harness: an unknown suite name is an error listing the suites (it passed as 0 of 0).
tester=${FEPS_TESTER:-$(fpm test --runner echo 2>/dev/null | tail -n 1)}
expect_line "fpm test -- nosuchsuite" 2 'no test suite "nosuchsuite" (the suites: datain' "$tester" nosuchsuite
# --mixed-precision (docs/tradeoff.md): CHOLMOD only, else one line, exit 2 and no file; a
# nonlinear run names how its factors were solved in its summary and /summary (the initial-
# stiffness slide: 4 of its 12 factors are solved three times or more).
expect_line "--mixed-precision with --solver skyline" 2 "it needs the cholmod solver, not skyline" \
  "$feps" test/data/slide_1dof_unload_is.dat --mixed-precision --solver skyline --output "$tmp/mp_sky.h5"
[ ! -e "$tmp/mp_sky.h5" ] && ok "--mixed-precision with skyline writes no file" || bad "--mixed-precision with skyline wrote a file"
"$feps" test/data/slide_1dof_unload_is.dat --mixed-precision --output "$tmp/mp.h5" >"$tmp/out" 2>&1 \
  && grep -q "^solver           cholmod-mixed$" "$tmp/out" \
  && grep -q "^mixed precision  4 of 12 factors solved in single precision from their third solve on (test solves within" "$tmp/out" \
  && python3 -c 'import sys, h5py; a = h5py.File(sys.argv[1])["summary"].attrs; sys.exit(not (a["solver"] == b"cholmod-mixed" and a["single_precision_factors"] == 4 and a["precision_fallbacks"] == 0 and 0 < a["test_solve_error"] < 1e-3))' "$tmp/mp.h5" \
  && ok "--mixed-precision: the summary line and /summary's solver, single_precision_factors, test_solve_error" \
  || bad "--mixed-precision summary: $(grep -i "mixed\|solver" "$tmp/out" | head -c 300)"
# The tetrahedra and wedges of the element catalog through the command: the Lame decks run, and
# their XDMF files (Tetrahedron(_10), Wedge(_15) cells) are read back below with the others.
for t in tet4 tet10 wedge6 wedge15; do
  "$feps" "test/data/lame_$t.dat" --quiet --output "$tmp/lame_$t.h5" >"$tmp/out" 2>&1 \
    && ok "lame_$t.dat runs (XDMF cell $(python3 -c 'import sys, h5py; print(h5py.File(sys.argv[1])["mesh/groups/wall"].attrs["xdmf_topology"].decode())' "$tmp/lame_$t.h5"))" \
    || bad "lame_$t.dat: $(cat "$tmp/out")"
done
# The XDMF files of this run's results, read with VTK's XDMF reader (ParaView's "XDMF Reader";
# setup.sh installs vtk) and compared with their HDF5 files: every step, block, cell, point,
# array and load factor (test/reference/check_xdmf_vtk.py).
xmfs=("$tmp"/*.xmf "$tmp"/mc_small/*.xmf)
python3 test/reference/check_xdmf_vtk.py "${xmfs[@]}" >"$tmp/out" 2>&1 \
  && ok "check_xdmf_vtk.py: the ${#xmfs[@]} XDMF files of these checks read back as their HDF5 files hold them" \
  || bad "check_xdmf_vtk.py: $(grep -v ': ok with' "$tmp/out" | head -c 400)"
# meshio's XDMF time-series reader reads the file for meshio beside each of them, every point and
# cell array equal to its dataset (test/reference/check_meshio.py; docs/output-format.md).
meshios=()
for x in "${xmfs[@]}"; do [ -e "${x%.xmf}.meshio.xdmf" ] && meshios+=("${x%.xmf}.meshio.xdmf"); done
[ "${#meshios[@]}" -eq "${#xmfs[@]}" ] && python3 test/reference/check_meshio.py "${meshios[@]}" >"$tmp/out" 2>&1 \
  && ok "check_meshio.py: the ${#meshios[@]} meshio files beside them: $(grep -c ': ok with' "$tmp/out") read back as their HDF5 files hold them; skipped: $(grep ': skipped' "$tmp/out" | sed 's|^.*/||; s|: skipped.*block of | (|; s| (no.*|)|' | tr '\n' ' ')" \
  || bad "check_meshio.py: ${#meshios[@]} meshio files for ${#xmfs[@]} XDMF files: $(grep -v ': ok with' "$tmp/out" | head -c 400)"

echo "the slowest checks (seconds, each since the check before it):"
sort -rn "$tmp/timings" | head -n 12 | awk '{printf "  %7.1f  %s\n", $1, substr($0, index($0, " ") + 1)}'
echo "$pass passed, $fail failed"
[ "$fail" -eq 0 ]
