#!/usr/bin/env python3
"""Reading feps HDF5 results for the plotting and campaign scripts (docs/output-format.md).

    import feps_results as fr
    with fr.open_result("SE1.h5") as f:
        step = fr.last_step(f)                             # "0001"
        xg = fr.gauss_points(f, "pipe")                    # (npoints, 3), same rows as stress/pipe
        s1 = f[f"steps/{step}/principal/pipe"][:, 0]

Everything about an element group comes from the result schema feps writes (its element
catalog's attributes on /mesh/groups/<group>: family, dimension, points_per_element,
result_field, components, xdmf_topology; the integration points /mesh/groups/<group>/points
and the measure each stands for, point_weights; each dataset's `components`), never from a table of element types of this module's own. The
nodal averages are feps's own fields (nodal_stress, nodal_principal, nodal_interface): nothing
here extrapolates. (An independent copy of feps's rules, for the checks only, is
test/reference/element_rules.py.)
"""
import os

import h5py
import numpy as np

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


def require_group(f, group, accept=None, what="group"):
    """ValueError naming the file and listing its groups (those `accept`, a predicate on (f,
    group), accepts when given) unless `group` is one of them."""
    names = [g for g in groups(f) if accept is None or accept(f, g)]
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


def group_attr(f, group, name):
    """An attribute the element catalog writes on /mesh/groups/<group> (family, dimension,
    points_per_element, result_field, components, xdmf_topology): str or int."""
    value = f[f"mesh/groups/{group}"].attrs[name]
    return int(value) if np.ndim(value) == 0 and np.issubdtype(np.asarray(value).dtype, np.integer) else text(value)


def family(f, group):
    """'solid', 'interface' or 'bar' (the catalog's family of the group's element type)."""
    return group_attr(f, group, "family")


def is_family(name):
    """Predicate on (f, group) for require_group: the group's family is `name`."""
    return lambda f, group: family(f, group) == name


def components(dataset):
    """The column names of a results dataset (its `components` attribute)."""
    return text(dataset.attrs["components"]).split()


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


def point_weights(f, group):
    """The measure (volume, area or length) each integration point of a group stands for, in the
    row order of its Gauss-point datasets: `/mesh/groups/<group>/point_weights`, from the library's
    own rules and Jacobians."""
    path = f"mesh/groups/{group}/point_weights"
    if path not in f:
        raise ValueError(f"{f.filename}: no {path} (a result of a feps older than point weights: "
                         f"run the deck again)")
    return f[path][:, 0]


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
# from the /summary parameters its decks write (scripts/make_model_b.py, make_model_c.py; a q
# parameter where make_pipe_joint.py's pipe or load is another):
# model B: P = 1000 kN over the half annulus (thesis 5.3); model C: 10 MPa on the top end (6.2).
MEAN_PRESSURE = {"model B": ("parameter_kind", 4.21), "model C": ("parameter_G_p", 10.0)}


def mean_pressure(f):
    """(q, model) of a result of a thesis model B or C deck, from its /summary parameters; (None,
    None) for any other file, whose q the caller must be given (a default would be a silent
    wrong number)."""
    attrs = summary(f)
    for model, (key, q) in MEAN_PRESSURE.items():
        if key in attrs:
            # make_pipe_joint.py's decks of another pipe or load name their q
            return float(attrs.get("parameter_q", q)), model
    return None, None

