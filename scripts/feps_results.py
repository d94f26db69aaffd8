#!/usr/bin/env python3
"""Reading feps HDF5 results for the plotting and campaign scripts (docs/output-format.md).

    import feps_results as fr
    with fr.open_result("SE1.h5") as f:
        step = fr.last_step(f)                             # "0001"
        xg = fr.gauss_points(f, "pipe")                    # (npoints, 3), same rows as stress/pipe
        s1 = f[f"steps/{step}/principal/pipe"][:, 0]

Integration-point positions are read from the file (`/mesh/groups/<group>/points`, written by
feps from its element catalog). The natural coordinates and shape functions below serve the
Gauss-to-corner extrapolations of the plotting scripts and the check of the table in
docs/output-format.md against feps's own points.
"""
import math
import os

import h5py
import numpy as np

_G2 = np.array([-1.0, 1.0]) / math.sqrt(3.0)
_G3 = np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)])

# hex20 natural coordinates in feps order: corners as hex8, mid-edges 9-12 (bottom), 13-16 (top), 17-20 (vertical)
_HEX8_XI = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                     [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
_HEX20_XI = np.vstack([_HEX8_XI, np.array([
    [0, -1, -1], [1, 0, -1], [0, 1, -1], [-1, 0, -1],
    [0, -1, 1], [1, 0, 1], [0, 1, 1], [-1, 0, 1],
    [-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=float)])
_QUAD_S = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [0, -1], [1, 0], [0, 1], [-1, 0]], dtype=float)
_TRI_A = 0.44594849091596488631832925388305
_TRI_B = 0.091576213509770743459571463402202


def open_result(path):
    """The HDF5 file for reading; ValueError naming it when it is missing or not HDF5."""
    if not os.path.isfile(path):
        raise ValueError(f"no result file {path}")
    try:
        return h5py.File(path, "r")
    except OSError as exc:
        raise ValueError(f"{path}: not an HDF5 file ({exc})") from None


def groups(f):
    """Names of the element groups in /mesh/groups."""
    return list(f["mesh/groups"]) if "mesh/groups" in f else []


def require_group(f, group, types=None, what="group"):
    """ValueError naming the file and listing its groups (of the element types accepted by
    `types`, a predicate on the type, when given) unless `group` is one of them."""
    names = [g for g in groups(f) if types is None or types(element_type(f, g))]
    if group not in names:
        raise ValueError(f"{f.filename}: no {what} '{group}' (the file has: {', '.join(names) or 'none'})")


def require(f, path, why=""):
    """ValueError naming the file unless it holds the object at `path`."""
    if path not in f:
        raise ValueError(f"{f.filename}: no /{path}{why}")


def text(value):
    """An HDF5 string attribute as a stripped str."""
    if isinstance(value, bytes):
        value = value.decode()
    elif isinstance(value, np.ndarray):
        value = value.item()
        value = value.decode() if isinstance(value, bytes) else str(value)
    return str(value).strip()


def steps(f):
    """Names of the stored steps ('0001', ..., '9999', '10000', ...), in step order. The names have
    at least 4 digits, so order them by number: as strings '10000' comes before '5000'."""
    return sorted(f["steps"].keys(), key=int) if "steps" in f else []


def last_step(f):
    names = steps(f)
    if not names:
        raise ValueError(f"{f.filename}: no /steps (a mesh-only run?)")
    return names[-1]


def pick_step(f, step=None):
    """'NNNN' from an int, a string or None (= the last step)."""
    if step is None:
        return last_step(f)
    try:
        name = f"{int(step):04d}"
    except ValueError:
        raise ValueError(f"step {step!r} is not a step number") from None
    if name not in steps(f):
        raise ValueError(f"{f.filename}: no step {name} (stored: {', '.join(steps(f)) or 'none, a mesh-only run?'})")
    return name


def case_name(f):
    """The case: the stem of /summary input_file, else of the file name."""
    if "summary" in f and "input_file" in f["summary"].attrs:
        return os.path.splitext(os.path.basename(text(f["summary"].attrs["input_file"])))[0]
    return os.path.splitext(os.path.basename(f.filename))[0]


def element_type(f, group):
    return text(f[f"mesh/groups/{group}"].attrs["element_type"]).lower()


def connectivity(f, group):
    """(nelem, k) 0-based node indices."""
    return f[f"mesh/groups/{group}/connectivity"][...].astype(np.int64) - 1


def coordinates(f):
    return f["mesh/coordinates"][...]


def cylindrical(x):
    """(r, theta in degrees in [0, 360), z) of points x (n, 3) about the global z axis."""
    r = np.hypot(x[:, 0], x[:, 1])
    theta = np.degrees(np.arctan2(x[:, 1], x[:, 0])) % 360.0
    # keep 180 on the negative x axis (y = -0.0 would give -180 -> 180 anyway)
    return r, theta, x[:, 2]


# ---------------------------------------------------------------------------------------- shapes

def _hex8_shape(xi):
    """(npts, 8) trilinear shape functions at natural points xi (npts, 3)."""
    return np.prod(1.0 + xi[:, None, :] * _HEX8_XI[None, :, :], axis=2) / 8.0


def _hex20_shape(xi):
    """(npts, 20) serendipity shape functions."""
    n = np.empty((xi.shape[0], 20))
    for a, xa in enumerate(_HEX20_XI):
        f = 1.0 + xi * xa
        if a < 8:
            n[:, a] = np.prod(f, axis=1) * (xi @ xa - 2.0) / 8.0
        else:
            zero = int(np.flatnonzero(xa == 0.0)[0])
            others = [d for d in range(3) if d != zero]
            n[:, a] = (1.0 - xi[:, zero] ** 2) * f[:, others[0]] * f[:, others[1]] / 4.0
    return n


def _quad_shape(s, nodes):
    """(npts, 4 | 8) bilinear or serendipity shape functions at s (npts, 2)."""
    n = np.empty((s.shape[0], nodes))
    for a in range(nodes):
        sa = _QUAD_S[a]
        f = 1.0 + s * sa
        if nodes == 4:
            n[:, a] = f[:, 0] * f[:, 1] / 4.0
        elif a < 4:
            n[:, a] = f[:, 0] * f[:, 1] * (f[:, 0] + f[:, 1] - 3.0) / 4.0
        elif sa[0] == 0.0:
            n[:, a] = (1.0 - s[:, 0] ** 2) * f[:, 1] / 2.0
        else:
            n[:, a] = (1.0 - s[:, 1] ** 2) * f[:, 0] / 2.0
    return n


def _tri_shape(s, nodes):
    l2, l3 = s[:, 0], s[:, 1]
    l1 = 1.0 - l2 - l3
    if nodes == 3:
        return np.column_stack([l1, l2, l3])
    return np.column_stack([l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), l3 * (2 * l3 - 1),
                            4 * l1 * l2, 4 * l2 * l3, 4 * l3 * l1])


def _line_shape(s, nodes, ends_first=False):
    """(npts, nodes) Lagrange shape functions of a line with nodes at equally spaced s in [-1, 1],
    in order along the line (bars), or with `ends_first` the two ends, then the middle
    (interface-line3)."""
    sn = np.linspace(-1.0, 1.0, nodes)
    if ends_first:
        sn = np.concatenate([sn[[0, -1]], sn[1:-1]])
    n = np.ones((s.shape[0], nodes))
    for i in range(nodes):
        for j in range(nodes):
            if j != i:
                n[:, i] *= (s[:, 0] - sn[j]) / (sn[i] - sn[j])
    return n


def _tensor_points(g, dims):
    """Tensor-product points, the first coordinate fastest."""
    grids = np.meshgrid(*([g] * dims), indexing="ij")
    return np.column_stack([grid.ravel(order="F") for grid in grids])


def _tri_orbit(a):
    """The points (a, a), (1 - 2a, a), (a, 1 - 2a) of a symmetric triangle rule, in feps's order."""
    return np.array([[a, a], [1 - 2 * a, a], [a, 1 - 2 * a]])


def integration_points(etype, points_per_element=None):
    """(natural coordinates (npts, dims) of the integration points feps uses for etype, in feps's
    order; number of nodes the shape functions use). Interface elements use their lower layer (the
    first nodes); bars their n - 1 Gauss-Legendre points in ascending s."""
    etype = etype.lower()
    if etype in ("hex8", "hex8b"):
        return _tensor_points(_G2, 3), 8
    if etype in ("hex20", "hex20r"):
        reduced = etype == "hex20r" or points_per_element == 8
        return _tensor_points(_G2 if reduced else _G3, 3), 20
    if etype in ("tri6", "tri6-6"):
        if etype == "tri6-6" or points_per_element == 6:
            return np.vstack([_tri_orbit(_TRI_A), _tri_orbit(_TRI_B)]), 6
        return _tri_orbit(1.0 / 6.0), 6
    if etype in ("bar2", "bar3", "bar4", "bar5"):
        nodes = int(etype[3:])
        return np.polynomial.legendre.leggauss(nodes - 1)[0][:, None], nodes   # ascending
    if etype.startswith("interface-"):
        nodal = etype.endswith("-nodal")
        shape = etype[len("interface-"):].replace("-nodal", "")
        if shape == "quad4":
            return (_QUAD_S[:4] if nodal else _tensor_points(_G2, 2)), 4
        if shape == "quad8":
            return (np.vstack([_QUAD_S, [0.0, 0.0]]) if nodal else _tensor_points(_G3, 2)), 8
        if shape == "tri3":
            return (np.array([[0, 0], [1, 0], [0, 1]], float) if nodal else _tri_orbit(1.0 / 6.0)), 3
        if shape == "tri6":
            return (np.array([[0.5, 0], [0.5, 0.5], [0, 0.5]]) if nodal else
                    np.vstack([_tri_orbit(_TRI_A), _tri_orbit(_TRI_B)])), 6
        if shape == "line2":
            return (np.array([[-1.0], [1.0]]) if nodal else _G2[:, None]), 2
        if shape == "line3":
            return (np.array([[-1.0], [1.0], [0.0]]) if nodal else _G3[:, None]), 3
    raise ValueError(f"no integration rule known here for element type '{etype}'")


def shape_functions(etype, points):
    """(npts, nodes used) shape functions of etype at natural points (npts, dims); interface
    elements: those of one layer."""
    etype = etype.lower()
    if etype in ("hex8", "hex8b"):
        return _hex8_shape(points)
    if etype in ("hex20", "hex20r"):
        return _hex20_shape(points)
    if etype in ("tri6", "tri6-6"):
        return _tri_shape(points, 6)
    if etype in ("bar2", "bar3", "bar4", "bar5"):
        return _line_shape(points, int(etype[3:]))
    if etype.startswith("interface-"):
        shape = etype[len("interface-"):].replace("-nodal", "")
        if shape in ("quad4", "quad8"):
            return _quad_shape(points, int(shape[4:]))
        if shape in ("tri3", "tri6"):
            return _tri_shape(points, int(shape[3:]))
        if shape in ("line2", "line3"):
            return _line_shape(points, int(shape[4:]), ends_first=True)
    raise ValueError(f"no shape functions known here for element type '{etype}'")


def integration_shapes(etype, points_per_element=None):
    """(shape matrix (npts, nodes used), number of nodes used) of the rule feps uses for etype.
    Interface elements use their lower layer (the first nodes)."""
    points, nodes = integration_points(etype, points_per_element)
    return shape_functions(etype, points), nodes


def gauss_points(f, group, dataset=None):
    """Global coordinates (nelem * npts, 3) of the integration points of a group, in the row order of
    its Gauss-point datasets: `/mesh/groups/<group>/points`, which feps writes from its own element
    catalog. `dataset` (an h5py dataset of that group) checks the point count."""
    path = f"mesh/groups/{group}/points"
    if path not in f:
        raise ValueError(f"{f.filename}: no {path} (a result of a feps older than the element catalog: "
                         f"run the deck again)")
    x = f[path][...]
    if dataset is not None and dataset.shape[0] != x.shape[0]:
        raise ValueError(f"group {group} ({element_type(f, group)}): {dataset.shape[0]} points in "
                         f"{dataset.name}, {x.shape[0]} in {path}")
    return x


def element_of_point(f, group, dataset):
    """Element index (0-based) of each row of a Gauss-point dataset."""
    ppe = int(dataset.attrs["points_per_element"])
    return np.repeat(np.arange(dataset.shape[0] // ppe), ppe)


def group_nodes(f, group):
    """Sorted 0-based indices of the nodes a group's elements use."""
    return np.unique(connectivity(f, group))


def summary(f):
    """/summary attributes as a dict of plain Python values."""
    out = {}
    if "summary" not in f:
        return out
    for key, value in f["summary"].attrs.items():
        if isinstance(value, (bytes, np.bytes_, str)):
            out[key] = text(value)
        elif np.ndim(value) == 0:
            out[key] = value.item() if hasattr(value, "item") else value
        else:
            out[key] = np.asarray(value).tolist()
    return out


# The mean end pressure q (MPa) that normalises the thesis's stress contours, by model, known
# from the /summary parameters its decks write (scripts/make_model_b.py, make_model_c.py):
# model B: P = 1000 kN over the half annulus (thesis 5.3); model C: 10 MPa on the top end (6.2).
MEAN_PRESSURE = {"model B": ("parameter_kind", 4.21), "model C": ("parameter_G_p", 10.0)}


def mean_pressure(f):
    """(q, model) of a result of a thesis model B or C deck, from its /summary parameters; (None,
    None) for any other file, whose q the caller must be given (a default would be a silent
    wrong number)."""
    attrs = summary(f)
    for model, (key, q) in MEAN_PRESSURE.items():
        if key in attrs:
            return q, model
    return None, None

