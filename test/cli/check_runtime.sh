#!/usr/bin/env bash
# Runtime-checked builds of feps: the test suites and a sweep of decks under gfortran's run-time
# checks and floating-point traps, and (--sanitize) under AddressSanitizer/UBSan.
#
# usage: bash test/cli/check_runtime.sh [--sanitize] [--valgrind] [--long]
#
# Always, the trapping build (its own fpm build folder; -O0):
#   -g -O0 -fcheck=all -fbacktrace -ffpe-trap=invalid,zero,overflow -finit-real=snan
#   -finit-integer=-2147483647 -finit-logical=true -finit-derived
# and under it:
#   1. fpm test (every suite). Tests that make non-finite numbers on purpose are registered with
#      nonfinite=.true. (test/feps_testing.f90): they run with halting off.
#   2. every deck of test/data/ and input/verification/ run, every deck of test/data/bad/ run and
#      --check'ed, and --check on every deck under input/: the exit status must be that of the
#      default build (fpm build), a bad deck's one-line message the same, and no run-time error,
#      signal or sanitizer report on stderr.
#   The decks in EXPECTED_TRAPS below overflow on purpose: their guard tests the result after
#   IEEE overflow has made it Inf or NaN, which -ffpe-trap=overflow stops first (SIGFPE, exit 136).
#   They must give the default build's answer or that SIGFPE; anything else fails.
# --sanitize: the build with -fsanitize=address,undefined (Fortran and the C shims, leak check
#   on, no traps): fpm test, the same sweep (where every deck, the overflowing ones included, must
#   give the default build's answer) and test/cli/check_cli.sh with FEPS/FEPS_TESTER set to it.
# --valgrind: memcheck (uninitialised reads of allocated memory, which -finit-real does not
#   cover, invalid accesses, definite leaks) on every deck of test/data/, test/data/bad/ and
#   input/verification/ with a -g -O1 build: not the -fcheck one, whose bounds checks of a
#   realloc-on-assignment read the unset bounds of the unallocated array (a gfortran 12 artefact
#   that memcheck reports at every such assignment).
# --long: short runs of thesis decks with the trapping build: the thin model A decks as they
#   are, and the joint2d, chapter 9, model B main and one model C deck with their step counts cut
#   by 10 (the checks do not depend on the step count; a full run at -O0 takes hours).
#
# Takes about 5 min (2 cores; --sanitize adds about 25 min, --valgrind 20, --long 30), too slow for
# .ci/run. Exit status 0 when everything passed, 1 otherwise; the failures are listed at the end.
set -uo pipefail
cd "$(dirname "$0")/../.."

sanitize=0; valgrind=0; long=0
for a in "$@"; do
  case "$a" in
    --sanitize) sanitize=1 ;;
    --valgrind) valgrind=1 ;;
    --long) long=1 ;;
    -h|--help) sed -n '2,/^set -uo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "check_runtime: unknown option $a (see --help)" >&2; exit 2 ;;
  esac
done

TRAP_FLAGS="-g -O0 -fcheck=all -fbacktrace -ffpe-trap=invalid,zero,overflow -finit-real=snan \
-finit-integer=-2147483647 -finit-logical=true -finit-derived"
SAN="-fsanitize=address,undefined -fno-omit-frame-pointer"
SAN_FLAGS="-g -O0 -fcheck=all $SAN"
# bad decks whose guard sees the overflow's Inf (the check after an integral or a sum), and
# overflow_solution.dat, whose finite loads overflow inside CHOLMOD's triangular solve (OpenBLAS).
# (E = 2 G (1 + nu) and STRESS times A are tested before the product: those decks do not trap.)
EXPECTED_TRAPS="test/data/bad/coordinates_overflow.dat test/data/bad/load_overflow.dat \
test/data/bad/stage_load_overflow.dat test/data/overflow_solution.dat"

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=()
fail() { fails+=("$1"); echo "  FAIL $1"; }
# a run-time check, a signal or a sanitizer on stderr
broken() { grep -q "Fortran runtime error\|Program received signal\|runtime error:\|ERROR: AddressSanitizer\|ERROR: LeakSanitizer" "$1"; }

exe_of() {  # flag-set c-flags link-flags kind(run|test): the executable fpm builds for them
  # fpm (0.x) does not relink an executable of a non-default flag set when only the library
  # changed: remove it so that it is linked against the library just built.
  local exe
  exe=$(fpm "$4" --flag "$1" --c-flag "$2" --link-flag "$3" --runner echo 2>/dev/null | tail -n 1)
  rm -f "$exe"
  fpm "$4" --flag "$1" --c-flag "$2" --link-flag "$3" --runner echo 2>/dev/null | tail -n 1
}

echo "== default build (the reference answers)"
fpm build >/dev/null 2>&1 || { echo "check_runtime: default build failed" >&2; exit 1; }
ref=$(fpm run --runner echo 2>/dev/null | tail -n 1)

sweep() {  # label feps traps(0|1): run every deck, compare with the default build
  local label=$1 feps=$2 traps=$3 d n rc want lines opt
  local -a decks=(test/data/*.dat input/verification/*.dat test/data/bad/*.dat)
  for d in "${decks[@]}"; do
    for opt in run check; do
      [ "$opt" = check ] && [[ "$d" != test/data/bad/* ]] && continue
      n=$(echo "$d" | tr / _)_$opt
      local args=("$d" --output "$tmp/$n.h5")
      [ "$opt" = check ] && args=("$d" --check)
      "$ref" "${args[@]}" >"$tmp/ref.out" 2>"$tmp/ref.err"; want=$?
      nice "$feps" "${args[@]}" >"$tmp/$n.out" 2>"$tmp/$n.err"; rc=$?
      rm -f "$tmp/$n.h5" "$tmp/$n.xmf" "$tmp/ref.h5"
      if [ "$traps" -eq 1 ] && [ "$rc" -eq 136 ] && [[ " $EXPECTED_TRAPS " == *" $d "* ]] \
         && grep -q "SIGFPE" "$tmp/$n.err"; then
        echo "  ok   $label $d --$opt: SIGFPE at the intended overflow"
        continue
      fi
      if broken "$tmp/$n.err" || [ "$rc" -ne "$want" ]; then
        fail "$label $d --$opt: exit $rc (default build $want): $(grep -m 3 -A 12 'runtime error\|Program received\|ERROR: \|^feps: error' "$tmp/$n.err" | grep -v '^#[012] ' | head -c 600)"
        continue
      fi
      lines=$(wc -l <"$tmp/$n.err")
      if [ "$rc" -eq 2 ] && ! cmp -s "$tmp/$n.err" "$tmp/ref.err"; then
        fail "$label $d --$opt: message differs from the default build's: $(head -c 300 "$tmp/$n.err")"
        continue
      fi
      echo "  ok   $label $d --$opt (exit $rc)"
    done
  done
  # --check on every deck under input/ (the thesis decks): exit 0, nothing on stderr
  while IFS= read -r d; do
    nice "$feps" "$d" --check >"$tmp/c.out" 2>"$tmp/c.err"; rc=$?
    if [ "$rc" -ne 0 ] || [ -s "$tmp/c.err" ]; then
      fail "$label $d --check: exit $rc: $(head -c 600 "$tmp/c.err")"
    else
      echo "  ok   $label $d --check"
    fi
  done < <(find input -name '*.dat' | sort)
}

echo "== trapping build: $TRAP_FLAGS"
nice fpm build --flag "$TRAP_FLAGS" --c-flag "-g -O0" >"$tmp/build.log" 2>&1 \
  || { cat "$tmp/build.log" >&2; echo "check_runtime: the trapping build failed" >&2; exit 1; }
trap_feps=$(exe_of "$TRAP_FLAGS" "-g -O0" "" run)
trap_test=$(exe_of "$TRAP_FLAGS" "-g -O0" "" test)
echo "== fpm test under the trapping build"
nice "$trap_test" >"$tmp/test.log" 2>&1; rc=$?
tail -n 1 "$tmp/test.log"
[ "$rc" -eq 0 ] || fail "fpm test (trapping build): exit $rc: $(grep -m 5 'FAIL\|runtime error\|Program received' "$tmp/test.log"; grep -A 20 'Program received' "$tmp/test.log" | grep ' at ' | head -n 4)"
echo "== decks under the trapping build"
sweep trap "$trap_feps" 1

if [ "$sanitize" -eq 1 ]; then
  echo "== sanitized build: $SAN_FLAGS"
  nice fpm build --flag "$SAN_FLAGS" --c-flag "-g -O0 $SAN" --link-flag "$SAN" >"$tmp/build.log" 2>&1 \
    || { cat "$tmp/build.log" >&2; echo "check_runtime: the sanitized build failed" >&2; exit 1; }
  san_feps=$(exe_of "$SAN_FLAGS" "-g -O0 $SAN" "$SAN" run)
  san_test=$(exe_of "$SAN_FLAGS" "-g -O0 $SAN" "$SAN" test)
  export UBSAN_OPTIONS=print_stacktrace=1
  echo "== fpm test under the sanitized build"
  # leak check off for the tester: gfortran leaks the temporaries of its array constructors of
  # derived types with allocatable components (test/main.f90, every collect_* list)
  ASAN_OPTIONS=detect_leaks=0 nice "$san_test" >"$tmp/test.log" 2>&1; rc=$?
  tail -n 1 "$tmp/test.log"
  # UBSan's 'signed integer overflow' in the test code's realloc-on-assignment of unallocated
  # arrays is gfortran's size arithmetic on the unset bounds (the result is discarded)
  if [ "$rc" -ne 0 ] || grep -v "signed integer overflow" "$tmp/test.log" | grep -q "runtime error:\|ERROR: "; then
    fail "fpm test (sanitized build): exit $rc: $(grep -m 5 'FAIL\|runtime error:\|ERROR: ' "$tmp/test.log")"
  fi
  echo "== decks under the sanitized build"
  ASAN_OPTIONS=detect_leaks=1 sweep sanitize "$san_feps" 0
  echo "== test/cli/check_cli.sh with the sanitized build"
  # the fuzzer's 4 GB address-space limit leaves no room for ASan's shadow memory: lift it, and
  # let ASan refuse an allocation beyond 4 GB instead (ALLOCATE's stat then reports it); its 60 s
  # per case is too short at -O0 with ASan (band_birth_yielded.dat alone takes 60 s)
  ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1:max_allocation_size_mb=4096 \
    FEPS_FUZZ_MEMORY_GB=100000 FEPS_FUZZ_TIMEOUT=600 FEPS="$PWD/$san_feps" FEPS_TESTER="$PWD/$san_test" nice bash test/cli/check_cli.sh \
    >"$tmp/cli.log" 2>&1; rc=$?
  tail -n 1 "$tmp/cli.log"
  [ "$rc" -eq 0 ] || fail "check_cli.sh (sanitized build): $(grep FAIL "$tmp/cli.log" | head -n 5)"
fi

if [ "$valgrind" -eq 1 ]; then
  echo "== valgrind memcheck, -g -O1 build"
  nice fpm build --flag "-g -O1" --c-flag "-g -O1" >"$tmp/build.log" 2>&1 \
    || { cat "$tmp/build.log" >&2; echo "check_runtime: the -g -O1 build failed" >&2; exit 1; }
  vg_feps=$(exe_of "-g -O1" "-g -O1" "" run)
  for d in test/data/*.dat input/verification/*.dat test/data/bad/*.dat; do
    n=$(echo "$d" | tr / _)
    nice valgrind --error-exitcode=99 --track-origins=yes --leak-check=full --errors-for-leak-kinds=definite \
      --show-leak-kinds=definite "$vg_feps" "$d" --output "$tmp/$n.h5" >"$tmp/$n.out" 2>"$tmp/$n.err"; rc=$?
    rm -f "$tmp/$n.h5" "$tmp/$n.xmf"
    if [ "$rc" -eq 99 ] || ! grep -q "ERROR SUMMARY: 0 errors" "$tmp/$n.err"; then
      fail "valgrind $d: $(grep 'ERROR SUMMARY' "$tmp/$n.err" | sed 's/^==[0-9]*== //'): $(grep -m 1 -A 6 'uninitialised\|Invalid\|definitely lost in' "$tmp/$n.err" | sed 's/^==[0-9]*== //' | tr '\n' ' ' | head -c 500)"
    else
      echo "  ok   valgrind $d"
    fi
  done
fi

if [ "$long" -eq 1 ]; then
  echo "== thesis decks (steps cut by 10) under the trapping build"
  mkdir -p "$tmp/long"
  for d in input/modelA/*_thin.dat input/joint2d/*.dat input/chapter9/*.dat input/modelB.dat \
           input/modelC/C_G300_nu0.1_b0.09.dat; do
    n=$(echo "$d" | tr / _)
    sed -E 's/STEPS=400/STEPS=40/; s/STEPS=250/STEPS=25/; s/STEPS=100/STEPS=10/; s/STEPS=50(,|$)/STEPS=5\1/' "$d" \
      >"$tmp/long/$n"
    start=$(date +%s)
    nice "$trap_feps" "$tmp/long/$n" --output "$tmp/long/$n.h5" >"$tmp/long/$n.out" 2>"$tmp/long/$n.err"; rc=$?
    rm -f "$tmp/long/$n.h5" "$tmp/long/${n%.dat}.xmf"
    if [ "$rc" -ne 0 ] || broken "$tmp/long/$n.err"; then
      fail "long $d: exit $rc: $(grep -m 3 -A 12 'runtime error\|Program received\|^feps: error' "$tmp/long/$n.err" | head -c 600)"
    else
      echo "  ok   long $d ($(( $(date +%s) - start )) s)"
    fi
  done
fi

echo "${#fails[@]} failure(s)"
for f in "${fails[@]}"; do echo "  $f"; done
[ "${#fails[@]}" -eq 0 ]
