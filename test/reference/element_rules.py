#!/usr/bin/env python3
"""feps's integration rules and shape functions, written again from the thesis and
docs/output-format.md: natural coordinates of the integration points in feps's order, the shape
functions of every element type, and the Gauss-to-node extrapolation of the nodal fields.

Kept in test/reference/ as a deliberately independent implementation: the library's element
catalog (src/elements) writes the integration points (/mesh/groups/<g>/points) and the nodal
averages (nodal_stress, nodal_principal, nodal_interface) into the results file, and the scripts
read them there. This copy exists only to check those: test/cli/check_cli.sh recomputes the
written stresses and interface strains from the displacements and holds nodal_stress to
`extrapolation_matrix`; test/cli/check_docs.py holds the table of integration points in
docs/output-format.md to `integration_points`.
"""
import math

import numpy as np

_G2 = np.array([-1.0, 1.0]) / math.sqrt(3.0)
_G3 = np.array([-math.sqrt(0.6), 0.0, math.sqrt(0.6)])

# hex20 natural coordinates in feps order: corners as hex8, mid-edges 9-12 (bottom), 13-16 (top), 17-20 (vertical)
HEX8_XI = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                     [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)
_HEX20_XI = np.vstack([HEX8_XI, np.array([
    [0, -1, -1], [1, 0, -1], [0, 1, -1], [-1, 0, -1],
    [0, -1, 1], [1, 0, 1], [0, 1, 1], [-1, 0, 1],
    [-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=float)])
_QUAD_S = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1], [0, -1], [1, 0], [0, 1], [-1, 0]], dtype=float)
_TRI_A = 0.44594849091596488631832925388305
_TRI_B = 0.091576213509770743459571463402202



def _hex8_shape(xi):
    """(npts, 8) trilinear shape functions at natural points xi (npts, 3)."""
    return np.prod(1.0 + xi[:, None, :] * HEX8_XI[None, :, :], axis=2) / 8.0


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



HEX8_CORNERS = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
                         [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], float)
HEX20_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]


def lagrange_1d(points, x):
    """(len(x), len(points)) values at x of the 1D Lagrange polynomials through the points."""
    out = np.ones((len(x), len(points)))
    for i, pi in enumerate(points):
        for j, pj in enumerate(points):
            if j != i:
                out[:, i] *= (x - pj) / (pi - pj)
    return out


def extrapolation_matrix(etype, ppe):
    """(nodes, points) matrix taking Gauss-point values of one element to its nodes, as feps's
    nodal_stress does (written here independently: test/cli/check_cli.sh holds nodal_stress to it): hex8 (and hex20 with 2x2x2 points at its
    corners) the trilinear interpolant of the 8 points, which is the inverse of the hex8 shape
    functions at the points; hex20 with 27 points the triquadratic Lagrange interpolant through
    them, evaluated at the 20 nodes; hex20 with 2x2x2 points: each mid-edge node is the mean of
    its edge's corners (the trilinear interpolant there)."""
    shapes, nodes = integration_shapes(etype, ppe)
    if etype in ("hex8", "hex8b"):
        return np.linalg.inv(shapes)
    if nodes == 20 and ppe == 27:
        g = np.sqrt(0.6) * np.array([-1.0, 0.0, 1.0])
        xn = np.vstack([HEX8_CORNERS] + [0.5 * (HEX8_CORNERS[a] + HEX8_CORNERS[b])[None, :] for a, b in HEX20_EDGES])
        lx, ly, lz = (lagrange_1d(g, xn[:, d]) for d in range(3))
        # point k = i + 3 j + 9 l has coordinates (g_i, g_j, g_l)
        return np.einsum("ni,nj,nl->nlji", lx, ly, lz).reshape(len(xn), 27)
    if nodes == 20 and ppe == 8:
        corners = np.linalg.inv(integration_shapes("hex8")[0])
        return np.vstack([corners] + [0.5 * (corners[a] + corners[b])[None, :] for a, b in HEX20_EDGES])
    raise ValueError(f"--source nodes: no extrapolation for {etype} with {ppe} points")
