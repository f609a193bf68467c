"""What the picture scripts share: reading the .vtu files frictopt writes, the contact-status
legend (names and colours), the contact facets of Γ_c and the per-node pieces of them that the
contact maps are drawn with, and the number format of titles. Imported by render_run.py and
render_vtu.py, which import vtk first (with the message about /usr/bin/python3 if it is
missing)."""

import math
import os

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

STATUS_NAMES = {0: "separated", 1: "stick", 2: "slip"}
STATUS_COLOURS = {0: "#d0d0d0", 1: "#2171b5", 2: "#e6550d"}
# Bit of the point array `boundary_tag` that marks the nodes of Γ_c (src/io/state_output.cpp).
CONTACT_TAG = 1


class VtuError(Exception):
    """A .vtu file that cannot be read as frictopt output; the message says why."""


def read_grid(path):
    """The vtkUnstructuredGrid in `path`; VtuError names the file when it is missing or empty."""
    if not os.path.isfile(path):
        raise VtuError(f"{path}: missing")
    vtk.vtkObject.GlobalWarningDisplayOff()  # a broken file gets our message, not VTK's dump
    reader = vtk.vtkXMLUnstructuredGridReader()
    reader.SetFileName(path)
    reader.Update()
    grid = reader.GetOutput()
    if grid is None or grid.GetNumberOfPoints() == 0:
        raise VtuError(f"{path}: no points (not a .vtu written by frictopt?)")
    return grid


# ----------------------------------------------------------------------------------------
# Numbers in titles.

def format_number(value, digits=3, resolution=0.0):
    """`value` with `digits` significant digits for a title. Zero has no sign: −0.0, and any
    value below `resolution` in magnitude (round-off on a coordinate of a body whose size sets
    the resolution), print as "0"."""
    value = float(value)
    if not math.isfinite(value):
        return f"{value}"
    if value == 0.0 or abs(value) < resolution:
        return "0"
    text = f"{value:.{digits}g}"
    # Rounding cannot give a signed zero here (value ≠ 0 keeps a nonzero digit), but keep the
    # rule in one place.
    return text[1:] if text.startswith("-") and float(text) == 0.0 else text


def format_quantity(value, unit="", digits=3, resolution=0.0):
    """A number and its unit for a title ("0 m", "1.5e+10 N²"); no unit: the number alone."""
    text = format_number(value, digits, resolution)
    return f"{text} {unit}" if unit else text


# ----------------------------------------------------------------------------------------
# The contact surface Γ_c as facets.

def contact_node_mask(grid):
    """Boolean mask of the nodes of Γ_c: bit CONTACT_TAG of `boundary_tag`, or else the nodes
    with a contact status (>= 0). None when the file has neither array."""
    tags = grid.GetPointData().GetArray("boundary_tag")
    if tags is not None:
        return (vtk_to_numpy(tags).astype(int) & CONTACT_TAG) != 0
    status = grid.GetPointData().GetArray("contact_status")
    if status is not None:
        return vtk_to_numpy(status).astype(float) >= 0
    return None


def boundary_faces(grid):
    """The boundary faces of a volume mesh as a list of node-index arrays (ids of `grid`),
    each ordered around the face."""
    surface = vtk.vtkDataSetSurfaceFilter()
    surface.SetInputData(grid)
    surface.PassThroughPointIdsOn()
    surface.Update()
    poly = surface.GetOutput()
    if poly.GetNumberOfPolys() == 0:
        return []
    original = vtk_to_numpy(poly.GetPointData().GetArray("vtkOriginalPointIds")).astype(int)
    polys = poly.GetPolys()
    offsets = vtk_to_numpy(polys.GetOffsetsArray()).astype(int)
    connectivity = vtk_to_numpy(polys.GetConnectivityArray()).astype(int)
    return [original[connectivity[offsets[k]:offsets[k + 1]]] for k in range(offsets.size - 1)]


def contact_facets(grid, mask=None):
    """The facets of Γ_c of a 3D body: its boundary faces whose nodes all lie on Γ_c. These are
    the contact surface as meshed, so a picture drawn on them has no cells over an empty slot
    between two contact faces and no holes on an unstructured mesh."""
    if mask is None:
        mask = contact_node_mask(grid)
    if mask is None or not np.any(mask):
        return []
    return [face for face in boundary_faces(grid) if np.all(mask[face])]


def node_pieces(points_2d, facets):
    """(polygons, nodes): each facet cut into one piece per corner node — the quadrilateral
    node, midpoint of the next edge, facet centroid, midpoint of the previous edge. The pieces
    of a node make up its tributary area on the meshed surface (a quarter of each adjacent
    quadrilateral), and all pieces tile the facets exactly: a map coloured piece by piece shows
    each nodal value over its own area, without gaps and without interpolation."""
    polygons, nodes = [], []
    for face in facets:
        corners = points_2d[face]
        centre = corners.mean(axis=0)
        count = len(face)
        for j in range(count):
            here, after, before = corners[j], corners[(j + 1) % count], corners[j - 1]
            polygons.append([here, 0.5 * (here + after), centre, 0.5 * (here + before)])
            nodes.append(int(face[j]))
    return np.array(polygons, dtype=float).reshape(-1, 4, 2), np.array(nodes, dtype=int)


def arrow_subset(points_2d, candidates, per_side=16):
    """At most about per_side² of the `candidates` (node indices), one per cell of a
    per_side × per_side grid over their bounding box (the node nearest to the cell's centre):
    a readable arrow field on structured and unstructured surfaces alike."""
    candidates = np.asarray(candidates, dtype=int)
    if candidates.size == 0:
        return candidates
    xy = points_2d[candidates]
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    size = np.where(hi > lo, hi - lo, 1.0)
    cell = np.minimum((per_side * (xy - lo) / size).astype(int), per_side - 1)
    centre = lo + (cell + 0.5) * size / per_side
    distance = np.linalg.norm(xy - centre, axis=1)
    keys = cell[:, 0] * per_side + cell[:, 1]
    order = np.lexsort((distance, keys))
    first = np.ones(order.size, dtype=bool)
    first[1:] = keys[order][1:] != keys[order][:-1]
    return np.sort(candidates[order[first]])
