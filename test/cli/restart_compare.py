"""Compare a continued run's results with the uninterrupted run's, bit for bit.

usage: python3 restart_compare.py FULL.h5 CONTINUED.h5 K
       python3 restart_compare.py --checkpoints FULL.restart.h5 CONTINUED.restart.h5 K

FULL.h5 is the uninterrupted run, CONTINUED.h5 the run continued (feps --restart) after step
K. Every step FULL holds after K must be in CONTINUED and none other (the steps' datasets under
/steps and /xdmf/steps); every dataset and
attribute CONTINUED holds must equal FULL's byte for byte, but the timings and the attributes
that name the restart (restart_from, restart_step). With --checkpoints, the restart data of
every step after K that both checkpoint files hold (the whole state: displacements, point
states, matrix values, counters) must be equal byte for byte, but the summary's timings.
Exit 1 with the differences listed.
"""
import sys

import h5py

TIMINGS = {"wall_time", "time_assembly", "time_factorization", "time_solve", "restart_from", "restart_step"}


def walk(f):
    out = {}
    f.visititems(lambda n, o: out.__setitem__(n, o))
    return out


TIMES = slice(7, 11)   # summary_reals: time_assembly, _factorization, _solve, _update (feps_restart_data)


def checkpoints(a, b, k):
    fa, fb = h5py.File(a, "r"), h5py.File(b, "r")
    steps = [int(n) for n in fb["restart/steps"][...] if int(n) > k]
    bad = []
    if not steps:
        bad.append("no restart data after step " + str(k))
    for n in steps:
        name = f"restart/step_{n:06d}"
        if name not in fa:
            bad.append("not in the uninterrupted run: " + name)
            continue
        da, db = walk(fa[name]), walk(fb[name])
        if set(da) != set(db):
            bad.append(f"{name}: objects differ: {set(da) ^ set(db)}")
        for obj, y in db.items():
            if not isinstance(y, h5py.Dataset) or obj not in da:
                continue
            x, v = da[obj][...], y[...]
            if obj == "summary_reals":
                x, v = x.copy(), v.copy()
                x[TIMES] = 0
                v[TIMES] = 0
            if x.tobytes() != v.tobytes():
                bad.append(f"data differ: {name}/{obj}")
    for line in bad:
        print(line)
    print(f"{b}: restart data of steps {steps}, {len(bad)} differences")
    sys.exit(1 if bad else 0)


def main():
    if sys.argv[1] == "--checkpoints":
        checkpoints(sys.argv[2], sys.argv[3], int(sys.argv[4]))
    full, cont, k = h5py.File(sys.argv[1], "r"), h5py.File(sys.argv[2], "r"), int(sys.argv[3])
    later = sorted(n for n in full["steps"] if int(n) > k)
    held = sorted(cont["steps"])
    bad = []
    if later != held:
        bad.append(f"steps: uninterrupted after {k}: {later}; continued: {held}")
    if "restart_step" not in cont["summary"].attrs or int(cont["summary"].attrs["restart_step"]) != k:
        bad.append("summary: restart_step is not " + str(k))
    da, db = walk(full), walk(cont)
    for name, y in db.items():
        if name not in da:
            bad.append("only in the continued run: " + name)
            continue
        x = da[name]
        if isinstance(y, h5py.Dataset) and x[...].tobytes() != y[...].tobytes():
            bad.append("data differ: " + name)
        for a in set(x.attrs) | set(y.attrs):
            if a in TIMINGS:
                continue
            if a not in x.attrs or a not in y.attrs or str(x.attrs[a]) != str(y.attrs[a]):
                bad.append(f"attribute differs: {name} {a}: {x.attrs.get(a)} / {y.attrs.get(a)}")
    for name in da:
        top = name.split("/")[0]
        if top == "steps" and "/" in name and name.split("/")[1] not in held:
            continue
        parts = name.split("/")    # the meshio file's per-step datasets, /xdmf/steps/<NNNN>/...
        if parts[:2] == ["xdmf", "steps"] and len(parts) > 2 and parts[2] not in held:
            continue
        if name not in db:
            bad.append("missing in the continued run: " + name)
    for line in bad:
        print(line)
    print(f"{sys.argv[2]}: {len(held)} steps after {k}, {len(db)} objects, {len(bad)} differences")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
