#!/usr/bin/env python3
"""Open feps XDMF files with VTK's XDMF reader and compare what it reads with the HDF5 file.

Kept in test/reference/ as a deliberately independent check: the XDMF file is read by VTK (the
reader ParaView uses), the HDF5 file by h5py, and the two compared; nothing of feps's XDMF writer.

Usage: python3 test/reference/check_xdmf_vtk.py RESULT.xmf [RESULT.xmf ...]

docs/output-format.md promises that the XDMF file beside each results file lets ParaView open
the results. ParaView reads it with VTK, so this reads each file as ParaView would, with VTK's
reader (vtkXdmf3Reader when the installed VTK has it, else vtkXdmfReader), walks every time step
and every block (one grid per element group) and checks against the HDF5 file, read with h5py
and the layout of docs/output-format.md, not through the XDMF file:

- the time values are the steps' load factors (cumulative over the stages), in ascending order,
  one per /steps/<NNNN>;
- at each time the data are those of that step (the output's data time is the one asked for), and
  each block's field data `step` and `load_factor` are the step's number and load factor;
- one block per element group with an XDMF cell, named after the group at every step;
- points: every mesh node, at /mesh/coordinates;
- cells: one per element, of the VTK type of the group's xdmf_topology (its catalog attribute), whose
  point ids are the element's connectivity - 1 (the lower layer, its first half, for interface
  elements);
- point data: each nodal dataset of the step on every block, and /steps/<NNNN>/<field>/<group>
  (nodal_stress, nodal_principal) on its group's block, as one array named after the dataset with
  one component per column (in the order of its `components`);
- cell data: each /steps/<NNNN>/cell/<kind>/<group> as the array <kind>, one component per column
  (VTK 9.7.2's vtkXdmfReader reads a Matrix attribute, any field of 2 or more columns that is no
  global x y z vector, as one tuple of all its values row by row: such an array is compared after
  reshaping, and counted in the "ok" line);
- no array VTK shows beyond these; values equal to 1e-12 relative (of the largest magnitude of the
  array), integers exactly;
- VTK places the nodes as feps does (check_shape): positive volumes of solids, the middle node of
  every quadratic edge near the middle of its chord, polylines that do not turn back;
- the reader prints no error or warning (each is a mismatch).

A mesh-only file (no /steps) must open as one set of blocks without time steps or arrays.
Exit status 0 when every file passes, 1 on a mismatch (each printed), 2 with a one-line error when
VTK or h5py is missing or a file cannot be read.
"""

import contextlib
import os
import re
import sys
import tempfile

RTOL = 1e-12

# XDMF TopologyType (the group attribute `xdmf_topology` that feps writes from its element
# catalog) -> the VTK cell type name and number vtkXdmfReader makes of it: the reader's contract,
# not a table of feps's element types.
VTK_CELL = {
    "Hexahedron": ("VTK_HEXAHEDRON", 12),
    "Hexahedron_20": ("VTK_QUADRATIC_HEXAHEDRON", 25),
    "Tetrahedron": ("VTK_TETRA", 10),
    "Tetrahedron_10": ("VTK_QUADRATIC_TETRA", 24),
    "Wedge": ("VTK_WEDGE", 13),
    "Wedge_15": ("VTK_QUADRATIC_WEDGE", 26),
    "Triangle": ("VTK_TRIANGLE", 5),
    "Triangle_6": ("VTK_QUADRATIC_TRIANGLE", 22),
    "Quadrilateral": ("VTK_QUAD", 9),
    "Quadrilateral_8": ("VTK_QUADRATIC_QUAD", 23),
    "Polyline": ("VTK_POLY_LINE", 4),
    "Edge_3": ("VTK_QUADRATIC_EDGE", 21),
}


def fail_usage(message):
    print("check_xdmf_vtk.py: " + message, file=sys.stderr)
    sys.exit(2)


class ReadError(Exception):
    """A file that cannot be read (exit status 2)."""


@contextlib.contextmanager
def captured_stderr(lines):
    """Collect what VTK and the XDMF library print on file descriptor 2 (errors) into `lines`."""
    sys.stderr.flush()
    saved = os.dup(2)
    with tempfile.TemporaryFile(mode="w+b") as sink:
        os.dup2(sink.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved, 2)
            os.close(saved)
            sink.seek(0)
            text = sink.read().decode("utf-8", "replace")
            text = re.sub(r"\x1b\[[0-9;]*m", "", text)
            for line in text.splitlines():
                # vtkLogger's 'date time (uptime) [thread] file:line ERR| message', the XDMF
                # library's 'XDMF Error in file line n (message)'; not the dumps that follow
                match = re.search(r"(?:ERR|WARN)\|\s*(.*)", line)
                if match:
                    lines.append(match.group(1).strip())
                elif "XDMF Error" in line or "XDMF Warning" in line:
                    lines.append(re.sub(r" in \S+ line \d+", "", line.strip()))


def load_modules():
    try:
        import numpy
        import h5py
    except ImportError as exc:
        fail_usage("needs numpy and h5py (%s)" % exc)
    try:
        from vtkmodules.vtkCommonCore import vtkVersion
        from vtkmodules.vtkCommonDataModel import vtkCompositeDataSet
        from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
        from vtkmodules.util.numpy_support import vtk_to_numpy
    except ImportError:
        fail_usage("vtk is not installed (pip install vtk)")
    reader_class = None
    try:
        from vtkmodules.vtkIOXdmf3 import vtkXdmf3Reader as reader_class
    except ImportError:
        try:
            from vtkmodules.vtkIOXdmf2 import vtkXdmfReader as reader_class
        except ImportError:
            fail_usage("this vtk has neither vtkXdmf3Reader nor vtkXdmfReader")
    return {
        "np": numpy, "h5py": h5py, "version": vtkVersion.GetVTKVersion(),
        "NAME": vtkCompositeDataSet.NAME(), "sddp": vtkStreamingDemandDrivenPipeline,
        "to_numpy": vtk_to_numpy, "Reader": reader_class,
    }


def hdf5_path(xmf_path):
    """The HDF5 file the XDMF file points into (its first Format="HDF" DataItem)."""
    try:
        with open(xmf_path, encoding="utf-8") as handle:
            text = handle.read()
    except OSError as exc:
        raise ReadError("cannot read %s: %s" % (xmf_path, exc.strerror))
    match = re.search(r'Format="HDF">([^<]*?):/', text)
    if match is None:
        raise ReadError("%s: no HDF5 DataItem" % xmf_path)
    name = match.group(1).replace("&amp;", "&").replace("&lt;", "<").replace("&gt;", ">")
    name = name.replace("&quot;", '"').replace("&apos;", "'")
    return os.path.join(os.path.dirname(xmf_path), name)


def text_attr(obj, key, default=""):
    value = obj.attrs.get(key, default)
    return value.decode() if isinstance(value, bytes) else str(value)


def global_vector(components):
    """A nodal field VTK should read as one vector: three global Cartesian components, such as
    'ux uy uz' or 'fx fy fz'. reaction_nodal's 'f1 f2 f3', in each node's own system, is three
    scalars (a vector is drawn along global x y z)."""
    return len(components) == 3 and all(w.endswith(a) for w, a in zip(components, "xyz"))


def first_error(lines):
    """': <the first line VTK printed>' or ''."""
    return (": VTK: " + lines[0]) if lines else ""


def blocks_of(data, m, path=""):
    """(name, dataset) of every leaf block of a composite data set, depth first."""
    out = []
    if data is None:
        return out
    if data.IsA("vtkMultiBlockDataSet"):
        for i in range(data.GetNumberOfBlocks()):
            meta = data.GetMetaData(i) if data.HasMetaData(i) else None
            name = meta.Get(m["NAME"]) if meta is not None and meta.Has(m["NAME"]) else str(i)
            out += blocks_of(data.GetBlock(i), m, name)
    elif data.IsA("vtkPartitionedDataSetCollection") or data.IsA("vtkPartitionedDataSet"):
        raise ReadError("unexpected output type " + data.GetClassName())
    else:
        out.append((path, data))
    return out


class Checker:
    def __init__(self, m, xmf):
        self.m, self.np, self.xmf = m, m["np"], xmf
        self.errors = []
        self.checked = 0   # values compared, quadratic edges placed
        self.flattened = 0   # Matrix arrays VTK read as one tuple

    def vtk_errors(self, where, lines):
        """A reader that complains has not read the file as written: each complaint is a mismatch."""
        for line in lines:
            self.bad(where or "reading", "VTK: " + line)
        del lines[:]

    def bad(self, where, message):
        self.errors.append("%s: %s: %s" % (self.xmf, where, message))

    def close(self, where, got, want):
        np = self.np
        got = np.asarray(got, dtype=float)
        want = np.asarray(want, dtype=float)
        if got.shape != want.shape:
            self.bad(where, "shape %s, HDF5 %s" % (got.shape, want.shape))
            return
        self.checked += want.size
        scale = float(np.max(np.abs(want))) if want.size else 0.0
        diff = float(np.max(np.abs(got - want))) if want.size else 0.0
        if not diff <= RTOL * scale:
            row = int(np.unravel_index(np.argmax(np.abs(got - want)), want.shape)[0])
            self.bad(where, "differs by %.3e (largest |value| %.3e) first at row %d: %s, HDF5 %s"
                     % (diff, scale, row, got[row].tolist() if got.ndim else got,
                        want[row].tolist() if want.ndim else want))

    def expected_groups(self, f):
        """name -> ((XDMF topology, family, dimension), 0-based cell connectivity) for groups with
        an XDMF cell, from the element catalog's attributes feps writes on each group."""
        groups = {}
        for name, group in f["mesh/groups"].items():
            if "xdmf_topology" not in group.attrs:
                continue   # no XDMF cell (a mesh-only 'nodes<k>' block)
            cell = (text_attr(group, "xdmf_topology"), text_attr(group, "family"), int(group.attrs["dimension"]))
            conn = self.np.asarray(group["connectivity"][...], dtype=self.np.int64) - 1
            if cell[1] == "interface":
                conn = conn[:, :conn.shape[1] // 2]
            groups[name] = (cell, conn)
        return groups

    def expected_arrays(self, f, step, group, nnode, nelem):
        """Point and cell arrays VTK should show for `group` at `step`: name -> values (a
        dataset of one column as a 1-D array, as VTK gives a one-component array)."""
        np = self.np
        point, cell = {}, {}
        if step is None:
            return point, cell

        def whole(ds):
            values = np.asarray(ds[...])
            return values[:, 0] if values.ndim == 2 and values.shape[1] == 1 else values

        s = f["steps"][step]
        for key, item in s.items():
            if key == "cell":
                for kind, by_group in item.items():
                    if group in by_group:
                        ds = by_group[group]
                        if ds.shape[0] != nelem:
                            self.bad("step %s %s" % (step, ds.name), "%d rows, %d elements"
                                     % (ds.shape[0], nelem))
                        cell[kind] = whole(ds)
            elif hasattr(item, "shape"):
                if len(item.shape) == 2 and item.shape[0] == nnode:
                    point[key] = whole(item)
            elif group in item:
                ds = item[group]
                # a group's nodal field (nodal_stress, nodal_principal); Gauss-point datasets
                # (points_per_element) are shown through their cell averages
                if len(ds.shape) == 2 and ds.shape[0] == nnode and "points_per_element" not in ds.attrs:
                    point[key] = whole(ds)
        return point, cell

    def vtk_arrays(self, attrs):
        out = {}
        for i in range(attrs.GetNumberOfArrays()):
            array = attrs.GetAbstractArray(i)
            out[array.GetName()] = self.m["to_numpy"](array)
        return out

    def check_block(self, f, step, name, block, expected):
        np, to_numpy = self.np, self.m["to_numpy"]
        where = ("step %s" % step if step is not None else "mesh") + " block " + name
        coords = np.asarray(f["mesh/coordinates"][...])
        nnode = coords.shape[0]
        etype, conn = expected
        if not block.IsA("vtkUnstructuredGrid"):
            self.bad(where, "a %s, not a vtkUnstructuredGrid" % block.GetClassName())
            return
        if block.GetNumberOfPoints() != nnode:
            self.bad(where, "%d points, HDF5 %d nodes" % (block.GetNumberOfPoints(), nnode))
        else:
            self.close(where + " points", to_numpy(block.GetPoints().GetData()), coords)
        nelem = conn.shape[0]
        if block.GetNumberOfCells() != nelem:
            self.bad(where, "%d cells, HDF5 %d elements" % (block.GetNumberOfCells(), nelem))
        else:
            type_name, type_id = VTK_CELL[etype[0]]
            types = np.array([block.GetCellType(i) for i in range(nelem)])
            if np.any(types != type_id):
                self.bad(where, "cell types %s, %s (%d) expected for %s"
                         % (sorted(set(types.tolist())), type_name, type_id, etype))
            cells = block.GetCells()
            offsets = to_numpy(cells.GetOffsetsArray())
            ids = to_numpy(cells.GetConnectivityArray())
            sizes = np.diff(offsets)
            if np.any(sizes != conn.shape[1]):
                self.bad(where, "cells of %s points, %d expected"
                         % (sorted(set(sizes.tolist())), conn.shape[1]))
            else:
                got = ids.reshape(nelem, conn.shape[1]).astype(np.int64)
                self.checked += conn.size
                wrong = np.nonzero(np.any(got != conn, axis=1))[0]
                if wrong.size:
                    e = int(wrong[0])
                    self.bad(where, "%d cells with other point ids, first element %d: %s, HDF5 %s"
                             % (wrong.size, e + 1, got[e].tolist(), conn[e].tolist()))
                elif block.GetNumberOfPoints() == nnode:
                    self.check_shape(where, block, etype, got, coords)
        if step is not None:       # the step's number and load factor as field data (Center="Grid")
            for key, want in (("step", float(int(step))),
                              ("load_factor", float(f["steps"][step].attrs["load_factor"]))):
                fd = block.GetFieldData().GetArray(key)
                if fd is None or fd.GetNumberOfTuples() != 1:
                    self.bad(where, "no field data " + key)
                elif fd.GetTuple1(0) != want:
                    self.bad(where, "field data %s %r, HDF5 %r" % (key, fd.GetTuple1(0), want))
        point, cell = self.expected_arrays(f, step, name, nnode, nelem)
        for kind, want, attrs in (("point", point, block.GetPointData()),
                                  ("cell", cell, block.GetCellData())):
            got = self.vtk_arrays(attrs)
            for key in sorted(set(want) - set(got)):
                self.bad(where, "%s array %s missing" % (kind, key))
            for key in sorted(set(got) - set(want)):
                self.bad(where, "%s array %s not in the HDF5 file" % (kind, key))
            for key in sorted(set(want) & set(got)):
                values = got[key]
                if values.ndim == 2 and values.shape[0] == 1 and want[key].ndim == 2 \
                        and values.size == want[key].size and want[key].shape[0] > 1:
                    # VTK 9.7.2's vtkXdmfReader reads an XDMF Matrix attribute (a field of 2 or
                    # more columns that are no global x y z vector) as one tuple of all its
                    # values, row by row (ParaView 5.11's readers give one tuple per row)
                    values = values.reshape(want[key].shape)
                    self.flattened += 1
                self.close("%s %s array %s" % (where, kind, key), values, want[key])

    def check_shape(self, where, block, etype, ids, coords):
        """That VTK places each node where feps does: the cell's own node order, read by VTK.

        Point ids equal to feps's connectivity prove nothing if VTK numbers the nodes of a cell
        differently. So, as VTK's cells define them: a solid's volume is positive; the middle
        node of each quadratic edge lies near the middle of its chord (within a quarter of the
        chord: on the feps meshes, straight or slightly curved edges, a node of another edge is
        half a chord or more away); a polyline does not turn back on itself.
        """
        np = self.np
        if block.GetNumberOfCells() == 0:
            return
        x = coords[ids]                           # (cells, nodes, 3)
        if etype[1] == "solid" and etype[2] == 3:
            from vtkmodules.vtkFiltersVerdict import vtkCellSizeFilter
            size = vtkCellSizeFilter()
            size.SetInputData(block)
            size.ComputeVertexCountOff()
            size.ComputeLengthOff()
            size.ComputeAreaOff()
            size.Update()
            volume = self.m["to_numpy"](size.GetOutput().GetCellData().GetArray("Volume"))
            if np.any(volume <= 0):
                e = int(np.nonzero(volume <= 0)[0][0])
                self.bad(where, "%d cells of non-positive volume in VTK, first element %d (%.6g)"
                         % (int(np.sum(volume <= 0)), e + 1, volume[e]))
        if VTK_CELL[etype[0]][1] == 4:               # polyline: consecutive segments go on
            seg = np.diff(x, axis=1)
            if seg.shape[1] > 1:
                dots = np.sum(seg[:, 1:] * seg[:, :-1], axis=2)
                if np.any(dots <= 0):
                    e = int(np.nonzero(np.any(dots <= 0, axis=1))[0][0])
                    self.bad(where, "polyline of element %d turns back: points %s"
                             % (e + 1, x[e].tolist()))
            return
        edges = []                                # (end, end, middle) local indices
        cell = block.GetCell(0)
        cell_ids = [cell.GetPointId(i) for i in range(cell.GetNumberOfPoints())]
        if VTK_CELL[etype[0]][1] == 21:
            edges = [(0, 1, 2)]
        else:
            for k in range(cell.GetNumberOfEdges()):
                edge = cell.GetEdge(k)
                if edge.GetNumberOfPoints() == 3:
                    edges.append(tuple(cell_ids.index(edge.GetPointId(i)) for i in range(3)))
        self.checked += len(edges) * ids.shape[0]
        for a, b, mid in edges:
            chord = np.linalg.norm(x[:, b] - x[:, a], axis=1)
            off = np.linalg.norm(x[:, mid] - 0.5 * (x[:, a] + x[:, b]), axis=1)
            if np.any(off > 0.25 * chord):
                e = int(np.argmax(off / chord))
                self.bad(where, "VTK's quadratic edge (%d, %d; middle %d) of element %d: the "
                         "middle node is %.3g from the chord's middle, chord %.3g"
                         % (a + 1, b + 1, mid + 1, e + 1, off[e], chord[e]))

    def check_output(self, f, step, groups, output):
        where = "step %s" % step if step is not None else "mesh"
        blocks = blocks_of(output, self.m)
        names = [name for name, _ in blocks]
        if sorted(names) != sorted(groups):
            self.bad(where, "blocks %s, groups with an XDMF cell %s" % (names, sorted(groups)))
        for name, block in blocks:
            if name in groups:
                self.check_block(f, step, name, block, groups[name])

    def run(self):
        m, np = self.m, self.np
        h5 = hdf5_path(self.xmf)
        try:
            f = m["h5py"].File(h5, "r")
        except OSError as exc:
            match = re.search(r"error message = '([^']*)'", str(exc))
            reason = match.group(1) if match else (exc.strerror or str(exc))
            raise ReadError("cannot open %s: %s" % (h5, reason))
        with f:
            if "mesh/coordinates" not in f or "mesh/groups" not in f:
                raise ReadError("%s has no mesh" % h5)
            groups = self.expected_groups(f)
            steps = sorted(f["steps"], key=int) if "steps" in f else []
            reader = m["Reader"]()
            reader.SetFileName(self.xmf)
            vtk_errors = []
            with captured_stderr(vtk_errors):
                reader.UpdateInformation()
                info = reader.GetOutputInformation(0)
                times = list(info.Get(m["sddp"].TIME_STEPS()) or [])
            self.vtk_errors("", vtk_errors)
            load_factors = [float(f["steps"][s].attrs["load_factor"]) for s in steps]
            if load_factors != times:
                self.bad("time steps", "%s, HDF5 load factors %s" % (times, load_factors))
            if not steps:
                with captured_stderr(vtk_errors):
                    reader.Update()
                    output = reader.GetOutputDataObject(0)
                if output is None or not blocks_of(output, m):
                    raise ReadError("%s: VTK read no grid%s" % (self.xmf, first_error(vtk_errors)))
                self.vtk_errors("mesh", vtk_errors)
                self.check_output(f, None, groups, output)
            for step, t in zip(steps, load_factors):
                with captured_stderr(vtk_errors):
                    reader.UpdateTimeStep(t)
                    output = reader.GetOutputDataObject(0)
                if output is None or not blocks_of(output, m):
                    raise ReadError("%s: VTK read no grid at time %g%s"
                                    % (self.xmf, t, first_error(vtk_errors)))
                self.vtk_errors("step " + step, vtk_errors)
                got_t = output.GetInformation().Get(output.DATA_TIME_STEP())
                if got_t != t:
                    self.bad("step " + step, "data time %s, asked for %g" % (got_t, t))
                self.check_output(f, step, groups, output)
            return len(steps), len(groups)


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        fail_usage("usage: python3 test/reference/check_xdmf_vtk.py RESULT.xmf [RESULT.xmf ...]")
    m = load_modules()
    reader_name = m["Reader"].__name__
    status = 0
    for xmf in argv[1:]:
        if not os.path.isfile(xmf):
            fail_usage("cannot read %s: no such file" % xmf)
        checker = Checker(m, xmf)
        try:
            nsteps, ngroups = checker.run()
        except ReadError as exc:
            fail_usage(str(exc))
        if checker.errors:
            status = 1
            for line in checker.errors:
                print(line)
            print("%s: FAIL (%d mismatches)" % (xmf, len(checker.errors)))
        else:
            print("%s: ok with %s (VTK %s): %d steps, %d blocks, %d values and edges agree%s"
                  % (xmf, reader_name, m["version"], nsteps, ngroups, checker.checked,
                     " (%d Matrix arrays read as one tuple each)" % checker.flattened
                     if checker.flattened else ""))
    return status


if __name__ == "__main__":
    sys.exit(main(sys.argv))
