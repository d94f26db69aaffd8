#!/usr/bin/env python3
"""Open feps XDMF files with ParaView's three XDMF readers and compare what each shows with the HDF5 file.

Usage: python3 test/reference/check_paraview.py [--png FILE.png] RESULT.xmf [RESULT.xmf ...]

An independent check, as test/reference/check_xdmf_vtk.py: ParaView reads the XDMF file (under
`pvbatch`, through `xvfb-run` when there is no display), h5py reads the HDF5 file by the layout of
docs/output-format.md, and the two are compared; nothing of feps's XDMF writer is used. For each
reader, "XDMF Reader" (XDMFReader), Xdmf3ReaderS and Xdmf3ReaderT:

- the time values are the steps' load factors (`/steps/<NNNN>` attribute `load_factor`), ascending;
- at each time, one block per element group with an XDMF cell, with as many cells as the group
  has elements; XDMFReader names each block after its group at every step; Xdmf3ReaderT gives the
  same blocks in the same order at every step (it names no block that comes out of a temporal
  collection), Xdmf3ReaderS the same pieces (it names none);
- each block's field data `step` (the step number) and `load_factor` are those of the step;
- each block's point arrays are the nodal datasets of the step (whole mesh, and its group's
  `/steps/<NNNN>/<field>/<group>`), its cell arrays the `/steps/<NNNN>/cell/<kind>/<group>`,
  each named after its dataset, with as many components as it has columns, and the minimum and
  maximum of every component equal (exactly) to those of the dataset's column; no other array;
- the readers print no error or warning.

With --png, the last step of the first file is rendered with XDMFReader: the grid of a group named
`pipe` (else the first group) warped by its displacement and coloured by the most tensile principal
stress (`principal`, component 0), saved as FILE.png.

Exit status 0 when every file passes with every reader, 1 on a mismatch (each printed), 2 with a
one-line error when pvbatch or h5py is missing or a file cannot be read.
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile

READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")

# The part that runs inside pvbatch (ParaView's own Python, which has no h5py): it writes what
# a reader shows, every block at every time, as JSON.
DUMP = r'''
import json, sys
from paraview import simple, servermanager

xmf, reader_name, out, png = sys.argv[1:5]
if reader_name == "XDMFReader":
    reader = simple.XDMFReader(FileNames=[xmf])
else:
    reader = getattr(simple, reader_name)(FileName=xmf)
reader.UpdatePipelineInformation()
times = reader.TimestepValues
times = [] if times is None else ([times] if isinstance(times, float) else list(times))


def arrays(data):
    found = {}
    for i in range(data.GetNumberOfArrays()):
        a = data.GetArray(i)
        if a is None:
            continue
        found[a.GetName()] = [list(a.GetRange(c)) for c in range(a.GetNumberOfComponents())]
    return found


def leaves(obj, name, found):
    if obj is None:
        return
    if obj.IsA("vtkDataSet"):
        fd = obj.GetFieldData()
        field = {fd.GetArray(i).GetName(): fd.GetArray(i).GetTuple(0)[0]
                 for i in range(fd.GetNumberOfArrays()) if fd.GetArray(i) is not None}
        found.append({"name": name, "cells": obj.GetNumberOfCells(), "points": obj.GetNumberOfPoints(),
                      "point": arrays(obj.GetPointData()), "cell": arrays(obj.GetCellData()), "field": field})
        return
    for i in range(obj.GetNumberOfBlocks() if obj.IsA("vtkMultiBlockDataSet") else obj.GetNumberOfPieces()):
        child_name = None
        if obj.HasMetaData(i):
            child_name = obj.GetMetaData(i).Get(obj.NAME())
        child = obj.GetBlock(i) if obj.IsA("vtkMultiBlockDataSet") else obj.GetPiece(i)
        leaves(child, child_name, found)


result = {"times": times, "steps": []}
for t in times or [None]:
    if t is None:
        reader.UpdatePipeline()
    else:
        reader.UpdatePipeline(t)
    blocks = []
    leaves(servermanager.Fetch(reader), None, blocks)
    result["steps"].append({"time": t, "blocks": blocks})
json.dump(result, open(out, "w"))

if png != "-":
    view = simple.GetActiveViewOrCreate("RenderView")
    view.ViewSize = [1200, 900]
    if times:
        view.ViewTime = times[-1]
    names = [b["name"] for b in result["steps"][-1]["blocks"]]
    group = "pipe" if "pipe" in names else names[0]
    one = simple.ExtractBlock(Input=reader)
    one.Selectors = ["/Root/" + group]
    warp = simple.WarpByVector(Input=one)
    warp.Vectors = ["POINTS", "displacement"]
    warp.ScaleFactor = 100.0
    shown = simple.Show(warp, view)
    simple.ColorBy(shown, ("CELLS", "principal", "0"))
    shown.RescaleTransferFunctionToDataRange(True, False)
    shown.SetScalarBarVisibility(view, True)
    lut = simple.GetColorTransferFunction("principal")
    bar = simple.GetScalarBar(lut, view)
    bar.Title = "most tensile principal stress (MPa)"
    bar.ComponentTitle = ""
    view.ResetCamera()
    camera = simple.GetActiveCamera()
    camera.Elevation(25)
    camera.Azimuth(35)
    view.ResetCamera()
    simple.SaveScreenshot(png, view, ImageResolution=[1200, 900])
'''


def fail_usage(message):
    print("check_paraview.py: " + message, file=sys.stderr)
    sys.exit(2)


def expected(h5_path):
    """What every reader must show, from the HDF5 file alone: per step (ascending load factor) the
    step number, load factor and, per group with an XDMF cell, its cell count and arrays with the
    minimum and maximum of each column."""
    import h5py
    import numpy

    def ranges(dataset):
        values = numpy.asarray(dataset[...], dtype=float)
        return [[float(values[:, c].min()), float(values[:, c].max())] for c in range(values.shape[1])]

    with h5py.File(h5_path, "r") as f:
        groups = {name: g["connectivity"].shape[0] for name, g in f["mesh/groups"].items()
                  if g.attrs["xdmf_topology"].decode()}
        steps = []
        for key in f.get("steps", {}):
            step = f["steps"][key]
            nodal = {k: ranges(v) for k, v in step.items() if isinstance(v, h5py.Dataset)}
            blocks = {}
            for group in groups:
                point = dict(nodal)
                for k, v in step.items():
                    if isinstance(v, h5py.Group) and k != "cell" and group in v \
                            and "points_per_element" not in v[group].attrs:
                        point[k] = ranges(v[group])
                cell = {}
                for kind, v in step.get("cell", {}).items():
                    if group in v:
                        cell[kind] = ranges(v[group])
                blocks[group] = {"cells": groups[group], "point": point, "cell": cell}
            steps.append({"number": int(key), "load_factor": float(step.attrs["load_factor"]),
                          "blocks": blocks})
        steps.sort(key=lambda s: s["number"])
        return groups, steps


def compare(label, shown, want):
    """Mismatches between a block as a reader showed it and a group's expected block."""
    bad = []
    if shown["cells"] != want["cells"]:
        bad.append(f"{label}: {shown['cells']} cells, the group has {want['cells']}")
    for where in ("point", "cell"):
        got, exp = shown[where], want[where]
        if sorted(got) != sorted(exp):
            bad.append(f"{label}: {where} arrays {sorted(got)}, the HDF5 file has {sorted(exp)}")
            continue
        for name in exp:
            if len(got[name]) != len(exp[name]):
                bad.append(f"{label}: {where} array {name} has {len(got[name])} components, "
                           f"the dataset {len(exp[name])} columns")
            elif got[name] != exp[name]:
                bad.append(f"{label}: {where} array {name} ranges {got[name]}, the dataset's {exp[name]}")
    return bad


def check_reader(xmf, reader, groups, steps, png, workdir):
    out = os.path.join(workdir, "shown.json")
    script = os.path.join(workdir, "dump.py")
    with open(script, "w") as f:
        f.write(DUMP)
    command = ["pvbatch", script, os.path.abspath(xmf), reader, out, png or "-"]
    if not os.environ.get("DISPLAY") and shutil.which("xvfb-run"):
        command = ["xvfb-run", "-a"] + command
    run = subprocess.run(command, capture_output=True, text=True, timeout=600)
    if run.returncode == 134 and png:
        # xvfb-run -a has been seen to hand a new server's display out before it accepts a
        # window (RenderWindow::CreateAWindow aborts): one more try
        run = subprocess.run(command, capture_output=True, text=True, timeout=600)
    if run.returncode != 0 or not os.path.exists(out):
        return [f"{reader}: pvbatch failed (status {run.returncode}): {(run.stderr or run.stdout)[-400:]}"]
    bad = []
    noise = [line for line in (run.stdout + run.stderr).splitlines()
             if line.strip() and "XDG_RUNTIME_DIR" not in line]
    if noise:
        bad.append(f"{reader}: printed {len(noise)} lines, first: {noise[0][:200]}")
    shown = json.load(open(out))
    if not steps:
        if shown["times"]:
            bad.append(f"{reader}: times {shown['times']} for a mesh-only file")
        blocks = shown["steps"][0]["blocks"]
        if sorted(b["cells"] for b in blocks) != sorted(groups.values()):
            bad.append(f"{reader}: blocks of {[b['cells'] for b in blocks]} cells, the groups have "
                       f"{sorted(groups.values())}")
        return bad
    want_times = [s["load_factor"] for s in steps]
    if shown["times"] != want_times:
        return bad + [f"{reader}: times {shown['times']}, the steps' load factors {want_times}"]
    first_order = None
    for step, at in zip(steps, shown["steps"]):
        label = f"{reader} step {step['number']} (time {at['time']!r})"
        blocks = at["blocks"]
        if len(blocks) != len(groups):
            bad.append(f"{label}: {len(blocks)} blocks, {len(groups)} groups")
            continue
        order = []
        for i, block in enumerate(blocks):
            field = block["field"]
            if field.get("step") != step["number"] or field.get("load_factor") != step["load_factor"]:
                bad.append(f"{label}: block {i} field data {field}")
            if reader == "XDMFReader":
                name = block["name"]
                if name not in groups:
                    bad.append(f"{label}: block {i} named {name!r}, no group of that name")
                    continue
                bad += compare(f"{label} block {name}", block, step["blocks"][name])
            else:
                if block["name"] is not None and block["name"] not in groups:
                    bad.append(f"{label}: block {i} named {block['name']!r}")
                # unnamed: the group whose cells and arrays it shows (each group once)
                name = next((g for g in groups if g not in order
                             and not compare("", block, step["blocks"][g])), None)
                if name is None:
                    bad.append(f"{label}: block {i} matches no group: "
                               + "; ".join(compare("", block, step["blocks"][g])[0] for g in groups
                                           if compare("", block, step["blocks"][g]))[:400])
                    continue
            order.append(name)
        if first_order is None:
            first_order = order
        elif order != first_order:
            bad.append(f"{label}: blocks in the order {order}, at the first step {first_order}")
    return bad


def main(argv):
    png = None
    if len(argv) >= 2 and argv[0] == "--png":
        png, argv = os.path.abspath(argv[1]), argv[2:]
    if not argv:
        fail_usage("usage: python3 test/reference/check_paraview.py [--png FILE.png] RESULT.xmf [...]")
    if shutil.which("pvbatch") is None:
        fail_usage("pvbatch (ParaView) is not installed: bash test/cli/check_paraview.sh installs it")
    try:
        import h5py  # noqa: F401
    except ImportError:
        fail_usage("h5py is not installed")
    failed = False
    for n, xmf in enumerate(argv):
        h5 = os.path.splitext(xmf)[0] + ".h5"
        if not os.path.exists(h5):
            fail_usage(f"{xmf}: no results file {h5} beside it")
        groups, steps = expected(h5)
        bad = []
        with tempfile.TemporaryDirectory() as workdir:
            for reader in READERS:
                bad += check_reader(xmf, reader, groups, steps,
                                    png if (png and n == 0 and reader == "XDMFReader") else None, workdir)
        for line in bad:
            print(f"{xmf}: {line}")
        failed = failed or bool(bad)
        if not bad:
            print(f"{xmf}: ok with {', '.join(READERS)}: {len(steps)} steps, {len(groups)} groups")
    if png and not failed and not os.path.exists(png):
        print(f"{png}: not rendered")
        failed = True
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
