#!/usr/bin/env python3
"""Read feps results with meshio's XDMF time-series reader and compare every array with the HDF5 file.

Usage: python3 test/reference/check_meshio.py RESULT.meshio.xdmf [RESULT.meshio.xdmf ...]

An independent check, as test/reference/check_xdmf_vtk.py: meshio (5.3.5) reads the file for
meshio that feps writes beside its results (docs/output-format.md), h5py reads the HDF5 file by
the layout of docs/output-format.md, and the two are compared exactly; nothing of feps's XDMF
writer is used.

- points: /mesh/coordinates;
- cell blocks: one per element group with an XDMF cell (attribute `xdmf_topology`), of meshio's
  cell type for it, whose point ids are /xdmf/<group>/topology; each group once;
- steps: one per /steps/<NNNN>, in the order of their numbers, at time = the step's `load_factor`;
- point data: each nodal dataset of the step under its name, and each group's nodal dataset
  /steps/<NNNN>/<field>/<group> as `<field>/<group>`; nothing else;
- cell data: per Gauss-point field, on each block the group's /steps/<NNNN>/cell/<field>/<group>,
  or NaN on a block whose group has no such field; nothing else.

A file with a cell type that meshio itself cannot hold is skipped, saying so: meshio 5.3.5 maps
XDMF's Wedge_15 to its `wedge15` but has no topological dimension for it, so that no reader of
meshio can make such a cell block (KeyError 'wedge15'); feps's `wedge15` groups are written all
the same.

Exit status 0 when every file passes or is skipped so, 1 on a mismatch (each printed), 2 with a one-line error when
meshio or h5py is missing or a file cannot be read.
"""

import os
import sys


def fail_usage(message):
    print("check_meshio.py: " + message, file=sys.stderr)
    sys.exit(2)


def check(path, meshio, h5py, np):
    bad = []
    stem = path[:-len(".meshio.xdmf")] if path.endswith(".meshio.xdmf") else os.path.splitext(path)[0]
    h5 = stem + ".h5"
    if not os.path.exists(h5):
        fail_usage(f"{path}: no results file {h5} beside it")
    to_meshio = meshio.xdmf.common.xdmf_to_meshio_type
    with h5py.File(h5, "r") as f, meshio.xdmf.TimeSeriesReader(path) as reader:
        points, cells = reader.read_points_cells()
        coords = f["mesh/coordinates"][...]
        if points.shape != coords.shape or not np.array_equal(points, coords):
            bad.append(f"points {points.shape} differ from /mesh/coordinates {coords.shape}")
        # a DATAIN block of bare nodes (mesh-only files) has no element type and no XDMF cell
        shown = {}
        for g, grp in f["mesh/groups"].items():
            cell = grp.attrs.get("xdmf_topology", b"")
            cell = cell.decode() if isinstance(cell, bytes) else str(cell)
            if cell:
                shown[g] = cell
        order = []
        for i, block in enumerate(cells):
            match = [g for g in shown if g not in order and block.type == to_meshio[shown[g]]
                     and np.array_equal(block.data, f["xdmf"][g]["topology"][...])]
            if not match:
                bad.append(f"cell block {i} ({block.type}, {block.data.shape}) is no group's topology")
                return bad, 0
            order.append(match[0])
        if sorted(order) != sorted(shown):
            bad.append(f"cell blocks of groups {order}, the groups with an XDMF cell {sorted(shown)}")
        steps = sorted(f["steps"], key=int) if "steps" in f else []
        if reader.num_steps != len(steps):
            bad.append(f"{reader.num_steps} steps, the HDF5 file {len(steps)}")
            return bad, 0
        for k, key in enumerate(steps):
            s = f["steps"][key]
            t, point_data, cell_data = reader.read_data(k)
            where = f"step {key}"
            if t != float(s.attrs["load_factor"]):
                bad.append(f"{where}: time {t!r}, load factor {float(s.attrs['load_factor'])!r}")
            want_point = {}
            for name, item in s.items():
                if isinstance(item, h5py.Dataset):
                    want_point[name] = item[...]
                elif name != "cell":
                    for group, ds in item.items():
                        if ds.shape[0] == coords.shape[0] and "points_per_element" not in ds.attrs:
                            want_point[f"{name}/{group}"] = ds[...]
            if sorted(point_data) != sorted(want_point):
                bad.append(f"{where}: point data {sorted(point_data)}, HDF5 {sorted(want_point)}")
            for name in set(point_data) & set(want_point):
                if not np.array_equal(point_data[name], want_point[name]):
                    bad.append(f"{where}: point data {name} differs from its dataset")
            kinds = sorted(s["cell"]) if "cell" in s else []
            if sorted(cell_data) != kinds:
                bad.append(f"{where}: cell data {sorted(cell_data)}, HDF5 {kinds}")
            for kind in set(cell_data) & set(kinds):
                for block, group in zip(cell_data[kind], order):
                    if group in s["cell"][kind]:
                        want = s["cell"][kind][group][...]
                        if not np.array_equal(block, want):
                            bad.append(f"{where}: cell data {kind} on {group} differs from its dataset")
                    elif not np.all(np.isnan(block)):
                        bad.append(f"{where}: cell data {kind} on {group}, which has no {kind}, is not NaN")
        return bad, len(steps)


def main(argv):
    if not argv:
        fail_usage("usage: python3 test/reference/check_meshio.py RESULT.meshio.xdmf [...]")
    try:
        import h5py
        import meshio
        import meshio.xdmf.common  # noqa: F401
        import numpy as np
    except ImportError as exc:
        fail_usage(f"needs meshio, h5py and numpy ({exc})")
    status = 0
    from meshio._mesh import topological_dimension
    import re
    for path in argv:
        types = re.findall(r'TopologyType="([^"]+)"', open(path).read())
        missing = sorted({meshio.xdmf.common.xdmf_to_meshio_type.get(t, t) for t in types}
                         - set(topological_dimension))
        if missing:
            print(f"{path}: skipped: meshio {meshio.__version__} cannot make a cell block of "
                  f"{', '.join(missing)} (no topological dimension for it)")
            continue
        try:
            bad, nsteps = check(path, meshio, h5py, np)
        except (OSError, meshio.ReadError, KeyError, ValueError) as exc:
            fail_usage(f"{path}: cannot read it: {exc!r}")
        for line in bad:
            print(f"{path}: {line}")
        if bad:
            status = 1
        else:
            print(f"{path}: ok with meshio {meshio.__version__}: {nsteps} steps, every array equal")
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
