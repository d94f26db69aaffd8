#!/usr/bin/env bash
# MUMPS over MPI (issue 29 items 1-2): `mpirun -np N feps DECK --solver mumps` (each rank on its
# own block of elements) with N = 1, 2 and 4 (oversubscribed on a 2-core machine) gives CHOLMOD's
# results to 1e-9, relative to each
# dataset's largest value, for SE1 (linear), FE1 (frictional interfaces), CR (chapter 9,
# Matsuoka-Nakai) and model C (C_G300_nu0.1_b0.09: packing, interfaces, staged misalignment). The
# nonlinear decks run a twentieth of their steps (the same short deck for both solvers: the solver is
# what is compared). Bad input under MPI: one line from rank 0, exit 2 from mpirun, no results
# file. The default build refuses --solver mumps with one line and exit 2. MUMPS's LU of the
# non-symmetric tangents (joint_psi0, full Newton) equals UMFPACK's, with each rank's memory and
# time in /summary; --out-of-core (factors on disk) gives the same answer and leaves no file.
# MUMPS's determinant gives the exact tangent's sign at each step as skyline and UMFPACK do.
# Installs MUMPS and OpenMPI (scripts/setup.sh --mpi) and builds the MPI build (build_mpi.sh).
set -uo pipefail
cd "$(dirname "$0")/../.."
bash scripts/setup.sh --mpi >/dev/null || { echo "check_mumps: setup --mpi failed" >&2; exit 1; }
fpm build --profile release >/dev/null 2>&1 || { echo "check_mumps: release build failed" >&2; exit 1; }
feps=$PWD/$(fpm run --profile release --runner echo 2>/dev/null | tail -n 1)
feps_mpi=$(bash scripts/build_mpi.sh 2>/dev/null) || { echo "check_mumps: MPI build failed" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
pass=0; fail=0
ok() { pass=$((pass + 1)); echo "  ok   $1"; }
bad() { fail=$((fail + 1)); echo "  FAIL $1"; }
mpi=(mpirun --oversubscribe -np)
[ "$(id -u)" -eq 0 ] && mpi=(mpirun --allow-run-as-root --oversubscribe -np)

# the largest difference, relative to each dataset's (and REPORT attribute's) largest value
compare() {
  python3 - "$@" <<'EOF'
import sys, h5py, numpy as np
ref, new = h5py.File(sys.argv[1], 'r'), h5py.File(sys.argv[2], 'r')
names = []
ref.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) and o.dtype.kind == 'f' else None)
worst, where = 0.0, ''
for n in names:
    a, b = ref[n][...], new[n][...]
    if a.shape != b.shape:
        print(f'1.0 {n}: shape {a.shape} against {b.shape}'); sys.exit()
    scale = np.abs(a).max()
    if scale > 0 and np.abs(a - b).max() / scale > worst:
        worst, where = np.abs(a - b).max() / scale, n
# REPORT attributes, each relative to the largest of its report's (a balanced reaction's
# component is round-off: its relative difference means nothing)
attrs = {k: float(v) for k, v in ref['summary'].attrs.items()
         if k.startswith(('rotation_', 'reaction_', 'section_', 'joint_')) and np.ndim(v) == 0
         and np.asarray(v).dtype.kind == 'f'}
for k, v in attrs.items():
    group = k.rsplit('_', 1)[0]
    scale = max(abs(w) for j, w in attrs.items() if j.rsplit('_', 1)[0] == group)
    if scale > 0 and abs(v - float(new['summary'].attrs[k])) / scale > worst:
        worst, where = abs(v - float(new['summary'].attrs[k])) / scale, 'summary ' + k
print(f'{worst:.3e} {where} ({len(names)} datasets)')
EOF
}

for deck in input/modelB/SE1.dat input/modelB/FE1.dat input/chapter9/CR.dat input/modelC/C_G300_nu0.1_b0.09.dat; do
  name=$(basename "$deck" .dat)
  python3 -c "
import re, sys
text = open(sys.argv[1]).read()
print(re.sub(r'STEPS=(\d+)', lambda m: 'STEPS=%d' % max(1, int(m.group(1)) // 20), text), end='')
" "$deck" >"$tmp/$name.dat"
  if ! "$feps" "$tmp/$name.dat" --quiet --output "$tmp/$name.cholmod.h5" >"$tmp/out" 2>&1; then
    bad "$name: the CHOLMOD run failed: $(tail -n 2 "$tmp/out")"; continue
  fi
  for np in 1 2 4; do
    if "${mpi[@]}" "$np" "$feps_mpi" "$tmp/$name.dat" --quiet --solver mumps --output "$tmp/$name.$np.h5" >"$tmp/out" 2>&1; then
      got=$(compare "$tmp/$name.cholmod.h5" "$tmp/$name.$np.h5")
      python3 -c "import sys; sys.exit(float(sys.argv[1]) > 1e-9)" "${got%% *}" \
        && ok "$name, MUMPS on $np rank(s) = CHOLMOD to ${got}" || bad "$name, MUMPS on $np rank(s) against CHOLMOD: $got"
    else
      bad "$name, MUMPS on $np rank(s): $(tail -n 3 "$tmp/out")"
    fi
  done
done

# MUMPS's LU for the non-symmetric tangents (full Newton, interfaces with psi = 0 < phi): the same
# answer and LU count as UMFPACK's; each rank's factorization memory and time in /summary
"$feps" test/data/joint_psi0.dat --quiet --output "$tmp/joint.cholmod.h5" >"$tmp/out" 2>&1 || bad "joint_psi0: the UMFPACK run failed"
for np in 1 2 4; do
  if "${mpi[@]}" "$np" "$feps_mpi" test/data/joint_psi0.dat --quiet --solver mumps --output "$tmp/joint.$np.h5" >"$tmp/out" 2>&1; then
    got=$(compare "$tmp/joint.cholmod.h5" "$tmp/joint.$np.h5")
    lu=$(python3 - "$tmp/joint.cholmod.h5" "$tmp/joint.$np.h5" "$np" <<'EOF'
import sys, h5py
a, b = (h5py.File(f, 'r')['summary'].attrs for f in sys.argv[1:3])
ranks = int(sys.argv[3])
ok = (a['lu_factorizations'] == b['lu_factorizations'] > 0 and 'ranks' not in a and b['ranks'] == ranks
      and len(b['rank_memory_mb']) == ranks and len(b['rank_factorization_time']) == ranks
      and min(b['rank_memory_mb']) >= 0 and min(b['rank_factorization_time']) >= 0)
print(f"{'ok' if ok else 'bad'} {a['lu_factorizations']} LU factorizations against {b['lu_factorizations']}; "
      f"ranks {b.get('ranks')}, memory {[float(m) for m in b['rank_memory_mb']]} MB")
EOF
)
    python3 -c "import sys; sys.exit(float(sys.argv[1]) > 1e-9)" "${got%% *}" && [ "${lu%% *}" = ok ] \
      && ok "joint_psi0 (non-symmetric), MUMPS LU on $np rank(s) = UMFPACK to ${got}; ${lu#ok }" \
      || bad "joint_psi0, MUMPS LU on $np rank(s) against UMFPACK: $got; $lu"
  else
    bad "joint_psi0, MUMPS LU on $np rank(s): $(tail -n 3 "$tmp/out")"
  fi
done

# The sign of the exact tangent's determinant (the stability check, /steps/NNNN
# tangent_determinant_sign) from MUMPS's determinant (ICNTL(33)) equals skyline's (LDL^T pivots)
# on the softening bar and UMFPACK's (LU) on the bar with nu = 0.2 at every step of the
# arc-length path: + before the peak, - past it; on 2 ranks one rank holds no element.
signs() {
  python3 - "$1" <<'EOF'
import sys, h5py
steps = h5py.File(sys.argv[1], 'r')['steps']
print(''.join({1: '+', -1: '-'}.get(int(steps[k].attrs.get('tangent_determinant_sign', 0)), '0')
              for k in sorted(steps, key=int)))
EOF
}
for pair in "crack_bar_arc skyline skyline" "crack_bar_arc_nu cholmod UMFPACK"; do
  set -- $pair
  "$feps" "test/data/$1.dat" --quiet --solver "$2" --output "$tmp/$1.ref.h5" >"$tmp/out" 2>&1 || bad "$1: the $2 run failed"
  want=$(signs "$tmp/$1.ref.h5")
  for np in 1 2; do
    if "${mpi[@]}" "$np" "$feps_mpi" "test/data/$1.dat" --quiet --solver mumps --output "$tmp/$1.$np.h5" >"$tmp/out" 2>&1; then
      got=$(signs "$tmp/$1.$np.h5")
      [ "$got" = "$want" ] && [[ "$want" == *+* ]] && [[ "$want" == *-* ]] \
        && ok "$1 on $np rank(s): the determinant's sign at every step = $3's ($got)" \
        || bad "$1 on $np rank(s): the determinant's signs $got against $3's $want"
    else
      bad "$1, MUMPS on $np rank(s): $(tail -n 3 "$tmp/out")"
    fi
  done
done

# --out-of-core: the factors on disk (in MUMPS_OOC_TMPDIR), the same answer; MUMPS removes its
# own files and nothing else in that folder
mkdir "$tmp/ooc" && echo keep >"$tmp/ooc/user_file"
if MUMPS_OOC_TMPDIR="$tmp/ooc" "${mpi[@]}" 2 "$feps_mpi" "$tmp/SE1.dat" --quiet --solver mumps --out-of-core \
     --output "$tmp/SE1.ooc.h5" >"$tmp/out" 2>&1; then
  got=$(compare "$tmp/SE1.cholmod.h5" "$tmp/SE1.ooc.h5")
  solver=$(python3 -c "import h5py, sys; s = h5py.File(sys.argv[1], 'r')['summary'].attrs['solver']; print(s.decode() if isinstance(s, bytes) else s)" "$tmp/SE1.ooc.h5")
  python3 -c "import sys; sys.exit(float(sys.argv[1]) > 1e-9)" "${got%% *}" && [ "$solver" = mumps-ooc ] \
    && [ "$(ls "$tmp/ooc")" = user_file ] \
    && ok "SE1 out of core on 2 ranks = CHOLMOD to ${got}; its files gone, the folder's own kept" \
    || bad "SE1 out of core: $got, solver $solver, left: $(ls "$tmp/ooc" | tr '\n' ' ')"
else
  bad "SE1 out of core on 2 ranks: $(tail -n 3 "$tmp/out")"
fi
# --out-of-core is MUMPS's: with another solver, one line and exit 2
"$feps" input/modelB/SE1.dat --out-of-core --output "$tmp/no.h5" >"$tmp/out" 2>"$tmp/err"
got=$?
[ "$got" -eq 2 ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "needs the mumps" "$tmp/err" && [ ! -e "$tmp/no.h5" ] \
  && ok "--out-of-core without mumps: one line, exit 2" || bad "--out-of-core without mumps: exit $got: $(cat "$tmp/err")"

# bad input under MPI: one line from rank 0 (mpirun adds its own report), exit 2, no results
for np in 1 2 4; do
  "${mpi[@]}" "$np" "$feps_mpi" test/data/bad/activate_orphan_node.dat --solver mumps --output "$tmp/bad.h5" >"$tmp/out" 2>"$tmp/err"
  got=$?
  [ "$got" -eq 2 ] && [ "$(grep -c '^feps: error:' "$tmp/err")" -eq 1 ] && [ ! -e "$tmp/bad.h5" ] \
    && ok "bad input on $np rank(s): one line from rank 0, exit 2, no results file" \
    || bad "bad input on $np rank(s): exit $got, $(grep -c '^feps: error:' "$tmp/err") error lines"
done
# a singular stiffness under MUMPS is named (the equation of its first null pivot): the cube
# without the support that holds x and y at its origin
grep -v "^FIX, origin" test/data/cube.dat >"$tmp/unconstrained.dat"
"${mpi[@]}" 2 "$feps_mpi" "$tmp/unconstrained.dat" --solver mumps --output "$tmp/sing.h5" >"$tmp/out" 2>"$tmp/err"
got=$?
[ "$got" -eq 2 ] && grep -q "^feps: error:.*singular at node.*MUMPS.s null pivot" "$tmp/err" && [ ! -e "$tmp/sing.h5" ] \
  && ok "an unconstrained model under MUMPS: exit 2, named, no results file" \
  || bad "an unconstrained model under MUMPS: exit $got: $(head -c 300 "$tmp/err")"
# The elements partitioned over the ranks by METIS (each rank assembles and updates its own; the
# forces are summed and the point states exchanged): /summary's rank_elements are balanced and
# add up to the model's elements, and every driver and stage feature on 2 and 4 ranks gives
# the 1-rank MUMPS answer (the same solver: only the partition differs) to 1e-9, each kind of
# field relative to its largest value over the run: arc length through a slip peak and along its
# plateau (block_arc), a cracking cube pulled by prescribed displacements to separation with full
# Newton and line search (crack_bar_5_nu), groups born between stages (activate_block),
# prestressed bars (prestress_block), bars born in a yielded band (band_birth_yielded), supports
# held and released between stages (stage_supports_incremental), a soil column built in two lifts
# with its weight (soil_column_lifts), interface friction (friction_pull), GEOSTATIC with a surface
# load (k0_reset). The cracking cube to its stage's DELTA1 = 1e-7 instead: near complete
# separation its full Newton iterations take different paths on 1 and 2 ranks (step 21: 108 and
# 33 iterations with cut-backs, the same displacements to 4e-15 at its end), so its points'
# stresses agree to the tolerance they were converged to, not to round-off. Not here: block_displacement's PATH=DISPLACEMENT, whose plateau (every point
# sliding) is a neutral equilibrium: its shear shares differ by 4e-8 between 1 and 4 ranks (as
# between CHOLMOD and MUMPS on one rank, 2e-6), after agreeing to 2e-13 up to the plateau.
for case in block_arc crack_bar_5_nu:1e-7 activate_block prestress_block band_birth_yielded \
            stage_supports_incremental soil_column_lifts friction_pull k0_reset; do
  deck=${case%%:*}
  tol=1e-9
  [ "$deck" != "$case" ] && tol=${case#*:}
  "${mpi[@]}" 1 "$feps_mpi" "test/data/$deck.dat" --quiet --solver mumps --output "$tmp/$deck.1.h5" >"$tmp/out" 2>&1 \
    || { bad "$deck on 1 rank: $(tail -n 2 "$tmp/out")"; continue; }
  for np in 2 4; do
    if ! "${mpi[@]}" "$np" "$feps_mpi" "test/data/$deck.dat" --quiet --solver mumps --output "$tmp/$deck.$np.h5" \
         >"$tmp/out" 2>&1; then
      bad "$deck on $np ranks: $(tail -n 2 "$tmp/out")"; continue
    fi
    got=$(python3 - "$tmp/$deck.1.h5" "$tmp/$deck.$np.h5" "$np" <<'EOF2'
import sys, h5py, numpy as np
ref, new, ranks = h5py.File(sys.argv[1], 'r'), h5py.File(sys.argv[2], 'r'), int(sys.argv[3])
names = []
ref.visititems(lambda n, o: names.append(n) if isinstance(o, h5py.Dataset) and o.dtype.kind == 'f' else None)
# each kind of field relative to its largest value over the run (a field that is round-off at
# one step, beside its value at others, is compared to that value)
scale = {}
for n in names:
    kind = n.split('/')[2] if n.startswith('steps/') else n
    scale[kind] = max(scale.get(kind, 0.0), float(np.abs(ref[n][...]).max()))
worst, where = 0.0, ''
for n in names:
    kind = n.split('/')[2] if n.startswith('steps/') else n
    if ref[n].shape != new[n].shape:
        print(f'1.0 {n}: shape'); sys.exit()
    d = float(np.abs(ref[n][...] - new[n][...]).max()) / scale[kind] if scale[kind] > 0 else 0.0
    if d > worst:
        worst, where = d, n
s = new['summary'].attrs
blocks = [int(e) for e in s['rank_elements']]
total = sum(len(g['connectivity']) for g in new['mesh/groups'].values())
# METIS balances the ranks' points (elements of different kinds weigh differently) within a few
# per cent: no rank above 1.15 times the mean where there are elements enough to share
balanced = len(blocks) == ranks and sum(blocks) == total and (total < 20 * ranks or max(blocks) <= 1.15 * total / ranks)
print(f"{worst:.3e} {where}; elements per rank {blocks} of {total}{'' if balanced else ' NOT BALANCED'}")
EOF2
)
    python3 -c "import sys; sys.exit(float(sys.argv[1]) > float(sys.argv[2]))" "${got%% *}" "$tol" \
      && [[ "$got" != *"NOT BALANCED"* ]] \
      && ok "$deck on $np ranks = on 1 rank to ${got} (within $tol)" || bad "$deck on $np ranks against 1 rank (to $tol): $got"
  done
done

# restart under MPI: restart data written on 2 ranks (the matrix whole, though each rank holds
# its share) resume on 2 ranks and on 1 to the uninterrupted 2-rank answer
if "${mpi[@]}" 2 "$feps_mpi" "$tmp/FE1.dat" --quiet --solver mumps --restart-every 5 --output "$tmp/fe1r.h5" \
     >"$tmp/out" 2>&1 && [ -e "$tmp/fe1r.restart.h5" ]; then
  for np in 2 1; do
    if "${mpi[@]}" "$np" "$feps_mpi" "$tmp/FE1.dat" --quiet --solver mumps --restart "$tmp/fe1r.restart.h5" --step 10 \
         --output "$tmp/fe1res.$np.h5" >"$tmp/out" 2>&1; then
      got=$(compare "$tmp/fe1r.h5" "$tmp/fe1res.$np.h5")
      python3 -c "import sys; sys.exit(float(sys.argv[1]) > 1e-9)" "${got%% *}" \
        && ok "FE1 resumed at step 10 on $np rank(s) from 2 ranks' restart data = the uninterrupted run to ${got}" \
        || bad "FE1 resumed on $np rank(s): $got"
    else
      bad "FE1 resumed on $np rank(s): $(tail -n 2 "$tmp/out")"
    fi
  done
else
  bad "FE1 with restart data on 2 ranks: $(tail -n 2 "$tmp/out")"
fi

# rank 0 alone writes: a write that fails on it mid-run (a tmpfs half the results' size) stops
# every rank at that step: one line, exit 1, nothing left, no rank left waiting. (A file-size
# limit cannot stand in for the tmpfs here: OpenMPI's shared-memory files meet it first.)
full=$(( $(stat -c %s "$tmp/FE1.2.h5") / 2048 ))
mkdir -p "$tmp/full"
if mount -t tmpfs -o size=${full}k tmpfs "$tmp/full" 2>/dev/null; then
  timeout 120 "${mpi[@]}" 2 "$feps_mpi" "$tmp/FE1.dat" --quiet --solver mumps --output "$tmp/full/fe1.h5" \
    >"$tmp/out" 2>"$tmp/err"
  got=$?
  left=$(ls "$tmp/full")
  umount "$tmp/full"
  [ "$got" -eq 1 ] && [ "$(grep -c '^feps: error:' "$tmp/err")" -eq 1 ] && [ -z "$left" ] \
    && ok "a results write that fails on rank 0 (a ${full} kB tmpfs) stops both ranks: exit 1, one line, nothing left" \
    || bad "a failed write on rank 0: exit $got, $(grep -c '^feps: error:' "$tmp/err") error lines, left: $left"
else
  echo "  skip a results write that fails on rank 0: this machine does not let the check mount a tmpfs"
fi

# the default build has no MUMPS: one line, exit 2
"$feps" input/modelB/SE1.dat --solver mumps --output "$tmp/no.h5" >"$tmp/out" 2>"$tmp/err"
got=$?
[ "$got" -eq 2 ] && [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -q "needs the MPI build" "$tmp/err" && [ ! -e "$tmp/no.h5" ] \
  && ok "the default build refuses --solver mumps: one line, exit 2" || bad "the default build with --solver mumps: exit $got: $(cat "$tmp/err")"

echo "check_mumps: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
