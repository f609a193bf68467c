#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Pictures of a frictopt run directory, written into RUN_DIR/pictures/.

An `optimize` directory (history.csv, summary.json, NAME_iterNNNN.vtu / NAME.pvd) gives
pictures of the initial design (iteration 0) next to the final one (last iterate written):

  3D  body_von_mises.png   deformed body coloured by the von Mises stress, cut at the mesh
                           plane nearest to x2 = b/2 (back half shown, so the stresses under
                           the contact are visible); same colour scale and same displacement
                           magnification for both designs.
      contact_maps.png     on the contact surface Γ_c, seen from above: contact pressure
                           (top row, same colour scale) and stick/slip/separated status with
                           the tangential traction as arrows (bottom row), each node's value
                           over its share of the contact facets.
      shape.png            the lift F_α (Bézier surface over the chart, control net, mesh
                           nodes) of both designs, and the deformed bodies seen from below
                           coloured by the von Mises stress.
  2D  shape.png            the bottom F_α (Bézier curve from α, control polygon, mesh nodes)
                           of both designs, and the deformed meshes coloured by von Mises
                           over the undeformed outline and the foundation x2 = 0.
      contact_stress.png   normal (solid) and tangential (dashed) contact stress along Γ_c,
                           like the thesis' figures 5.2.x, with the stick/slip status below.
  both history.png         Θ per iteration with its unit (log scale when positive; serious
                           steps filled, null steps open, squares after a line search; the
                           counts add up to summary.json's) and the stationarity measure.

A `solve` directory (NAME.vtu, summary.json) gives the same body and contact pictures for its
single design, and no history.

Usage (VTK needs an X display even off screen with Debian's VTK; run_headless provides one):
    viz/run_headless.sh /usr/bin/python3 viz/render_run.py RUN_DIR [--no-cut]
Reads only files frictopt wrote (STYLE §9), and the case file for the shape of the 3D net. Exits non-zero with a message naming the missing
file when RUN_DIR is not a run directory or a picture could not be written.
"""

import argparse
import csv
import glob
import io
import json
import math
import os
import re
import sys
import tomllib
import xml.etree.ElementTree as ElementTree

try:
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import colormaps
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import BoundaryNorm, ListedColormap, Normalize
    from matplotlib.patches import Patch
    from matplotlib.lines import Line2D
    from matplotlib.ticker import MaxNLocator
    from matplotlib.tri import Triangulation
    from matplotlib.path import Path
    from PIL import Image
    from frictopt_vtu import (STATUS_COLOURS, STATUS_NAMES, VtuError, arrow_subset,
                              contact_facets, format_number, format_quantity, node_pieces,
                              read_grid)
except ImportError as error:  # the usual cause: a pyenv/venv python3 on PATH
    sys.exit(f"render_run: {error}; run it with /usr/bin/python3 (Debian's python3-vtk9, "
             "matplotlib, numpy)")

STRESS_CMAP = "viridis"
PRESSURE_CMAP = "magma_r"
DPI = 100
MAX_PNG_BYTES = 250 * 1024
# PNG metadata without the library version, so that equal inputs give equal files.
PNG_METADATA = {"Software": None}
INITIAL_COLOUR = "#4d4d4d"
FINAL_COLOUR = "#cb181d"


class RunError(VtuError):
    """A run directory that cannot be pictured; the message says why."""


# ----------------------------------------------------------------------------------------
# Reading what frictopt wrote.

class Design:
    """One state written by frictopt: a .vtu file and what the run says about it."""

    def __init__(self, path, label, cost=None, alpha=None, iteration=None):
        self.path = path
        self.label = label        # "initial design", "final design", "design"
        self.cost = cost          # Θ at this design, if the run recorded it
        self.alpha = alpha        # design vector, if recorded
        self.iteration = iteration
        self.grid = read_grid(path)
        self.points = vtk_to_numpy(self.grid.GetPoints().GetData()).astype(float)
        self.dim = 2 if is_planar(self.points) else 3

    def point_array(self, name):
        array = self.grid.GetPointData().GetArray(name)
        return None if array is None else vtk_to_numpy(array).astype(float)

    def cell_array(self, name):
        array = self.grid.GetCellData().GetArray(name)
        return None if array is None else vtk_to_numpy(array).astype(float)

    def cells(self):
        """Connectivity as an (n_cells, nodes_per_cell) integer array (frictopt writes one
        cell type per file)."""
        cells = self.grid.GetCells()
        offsets = vtk_to_numpy(cells.GetOffsetsArray())
        connectivity = vtk_to_numpy(cells.GetConnectivityArray())
        sizes = np.diff(offsets)
        if sizes.size == 0 or np.any(sizes != sizes[0]):
            raise RunError(f"{self.path}: expected cells of one type")
        return connectivity.reshape(-1, int(sizes[0]))

    def contact_mask(self):
        status = self.point_array("contact_status")
        return None if status is None else status >= 0

    def title(self, unit="", digits=4):
        parts = [self.label]
        if self.iteration is not None:
            parts[0] += f" (iteration {self.iteration})"
        if self.cost is not None:
            parts.append(f"Θ = {format_quantity(self.cost, unit, digits)}")
        return ", ".join(parts)

    def size(self):
        return float(np.max(self.points.max(axis=0) - self.points.min(axis=0)))


def is_planar(points):
    extent = points.max(axis=0) - points.min(axis=0)
    return extent[2] <= 1e-12 * max(extent[0], extent[1], 1e-300)


def read_json(path):
    try:
        with open(path, encoding="utf-8") as stream:
            return json.load(stream)
    except (OSError, ValueError) as error:
        raise RunError(f"{path}: {error}") from error


def read_history(path):
    """Rows of history.csv as dicts of floats (and 'step' as text)."""
    try:
        with open(path, newline="", encoding="utf-8") as stream:
            rows = list(csv.DictReader(stream))
    except OSError as error:
        raise RunError(f"{path}: {error}") from error
    needed = {"iteration", "step", "theta", "stationarity_relative"}
    if rows and not needed <= set(rows[0]):
        raise RunError(f"{path}: columns {sorted(needed - set(rows[0]))} missing")
    history = []
    for row in rows:
        entry = {key: (value if key == "step" else float(value)) for key, value in row.items()
                 if key is not None and value not in (None, "")}
        history.append(entry)
    return history


def series_files(run_dir):
    """{iteration: path} of the iterate .vtu files, from NAME.pvd or else NAME_iterNNNN.vtu."""
    files = {}
    for pvd in sorted(glob.glob(os.path.join(run_dir, "*.pvd"))):
        try:
            root = ElementTree.parse(pvd).getroot()
        except ElementTree.ParseError as error:
            raise RunError(f"{pvd}: {error}") from error
        for entry in root.iter("DataSet"):
            path = os.path.join(run_dir, entry.get("file", ""))
            files[int(round(float(entry.get("timestep", "0"))))] = path
        if files:
            return files
    for path in sorted(glob.glob(os.path.join(run_dir, "*_iter[0-9][0-9][0-9][0-9].vtu"))):
        files[int(re.search(r"_iter(\d{4})\.vtu$", path).group(1))] = path
    return files


def read_case_copy(path):
    """The run's copy of its case file as a dict ({} when absent or unreadable: the pictures
    only use it for the shape of the control net)."""
    try:
        with open(path, "rb") as stream:
            return tomllib.load(stream)
    except (OSError, tomllib.TOMLDecodeError):
        return {}


def case_name(run_dir, summary, case_copy=None):
    """The case's name for titles: the case file's folder (cases2d/NAME/case.toml) or stem;
    for the run's own copy RUN_DIR/case.toml (an optimize run reads that), or a case.toml
    named without its folder, the case's [output] name; else the run directory's name."""
    case = summary.get("case", "") if summary else ""
    if case and os.path.abspath(os.path.dirname(case)) != os.path.abspath(run_dir):
        stem = os.path.splitext(os.path.basename(case))[0]
        folder = os.path.basename(os.path.dirname(case))
        if stem != "case":
            return stem
        if folder:
            return folder
    output_name = (case_copy or {}).get("output", {}).get("name")
    if isinstance(output_name, str) and output_name:
        return output_name
    return os.path.basename(os.path.abspath(run_dir))


class Run:
    def __init__(self, run_dir):
        if not os.path.isdir(run_dir):
            raise RunError(f"{run_dir}: not a directory")
        self.dir = run_dir
        summary_path = os.path.join(run_dir, "summary.json")
        history_path = os.path.join(run_dir, "history.csv")
        self.summary = read_json(summary_path) if os.path.isfile(summary_path) else {}
        # The run's copy of the case file (optimize), else the case file the summary names
        # (solve writes no copy).
        self.case = read_case_copy(os.path.join(run_dir, "case.toml"))
        if not self.case and isinstance(self.summary.get("case"), str):
            self.case = read_case_copy(self.summary["case"])
        self.name = case_name(run_dir, self.summary, self.case)
        # The cost's kind as the case file spells it ([cost] kind); older summaries name the
        # functional only.
        self.cost_name = self.summary.get("cost_kind") or self.summary.get("cost")
        # Θ's unit as frictopt states it (summary.json "cost_unit"); "" when not stated.
        self.cost_unit = self.summary.get("cost_unit", "")
        self.history = None
        series = series_files(run_dir)
        if os.path.isfile(history_path) or series or self.summary.get("command") == "optimize":
            self.kind = "optimize"
            if not os.path.isfile(history_path):
                raise RunError(f"{history_path}: missing (an optimize run writes it from its "
                               "first iteration)")
            if not self.summary:
                raise RunError(f"{summary_path}: missing (the optimize run did not finish?)")
            self.history = read_history(history_path)
            if not series:
                raise RunError(f"{run_dir}: no NAME_iterNNNN.vtu / NAME.pvd (was [output] "
                               "vtk = false?)")
            first, last = min(series), max(series)
            final_iteration = self.summary.get("iterations")
            self.designs = [Design(series[first], "initial design" if first == 0
                                   else "first iterate written",
                                   self.summary.get("initial_cost") if first == 0 else None,
                                   self.summary.get("initial_alpha") if first == 0 else None,
                                   first)]
            if last != first:
                is_final = final_iteration is None or last == final_iteration
                self.designs.append(Design(series[last],
                                           "final design" if is_final else "last iterate written",
                                           self.summary.get("final_cost") if is_final else None,
                                           self.summary.get("alpha") if is_final else None,
                                           last))
        else:
            files = sorted(glob.glob(os.path.join(run_dir, "*.vtu")))
            if not files:
                raise RunError(f"{run_dir}: no history.csv and no .vtu file — not a frictopt "
                               "run directory (frictopt solve/optimize CASE -o DIR writes one)")
            self.kind = "solve"
            self.designs = [Design(path, "design of the case file" if len(files) == 1 else
                                   os.path.basename(path)[:-4],
                                   None, self.summary.get("alpha")) for path in files]
        dims = {d.dim for d in self.designs}
        if len(dims) != 1:
            raise RunError(f"{run_dir}: .vtu files of different dimension")
        self.dim = dims.pop()

    def headline(self):
        text = f"{self.name}"
        if self.cost_name:
            text += f" — cost {self.cost_name}"
            if self.cost_unit:
                text += f" [{self.cost_unit}]"
        return text

    def load_warning(self):
        """One line when summary.json warns that the final design carries another load than
        the initial one (frictopt's "warnings", docs/optim.md "Outcomes"), else ""."""
        warnings = self.summary.get("warnings") if isinstance(self.summary, dict) else None
        if not isinstance(warnings, list) or not warnings:
            return ""
        initial, final = self.summary.get("initial_load"), self.summary.get("final_load")
        if isinstance(initial, dict) and isinstance(final, dict):
            p0, p = initial.get("total_normal_force"), final.get("total_normal_force")
            if (isinstance(p0, (int, float)) and isinstance(p, (int, float))
                    and math.isfinite(p0) and math.isfinite(p) and p0 > 0):
                unit = "N/m" if self.dim == 2 else "N"
                return (f"warning: the final design carries another load — total normal force "
                        f"{p0:.4g} → {p:.4g} {unit} ({100.0 * (p - p0) / p0:+.0f} %)")
        return f"warning: {warnings[0]}"

    def control_points(self, count):
        """(m1, m2) of the 3D control net with `count` = m1·m2 entries: [design]
        control_points of the run's copy of the case file; None when it is not there."""
        design = self.case.get("design", {}) if self.case else {}
        shape = design.get("control_points")
        if (isinstance(shape, list) and len(shape) == 2
                and all(isinstance(m, int) for m in shape) and shape[0] * shape[1] == count):
            return int(shape[0]), int(shape[1])
        return None

    def chart(self):
        """((origin), (extents)) of the Bézier chart when the run states it (summary.json's
        "design_chart", or a "chart" with "origin" and "extents" in summary.json or
        final_design.json), else None."""
        sources = [self.summary]
        final_design = os.path.join(self.dir, "final_design.json")
        if os.path.isfile(final_design):
            sources.append(read_json(final_design))
        for source in sources:
            chart = None
            if isinstance(source, dict):
                chart = source.get("design_chart", source.get("chart"))
            if isinstance(chart, dict) and "origin" in chart and "extents" in chart:
                return (np.asarray(chart["origin"], dtype=float),
                        np.asarray(chart["extents"], dtype=float))
        return None


# ----------------------------------------------------------------------------------------
# Shared helpers.

TEXT_MARGIN = 4  # pixels between a title and the figure's edge


def figure_titles(fig):
    """(text artist, widest allowed extent in pixels) of the titles of a figure: the
    figure's suptitle and supxlabel (its width), and every axes title (its axes' width, a
    little more, never beyond the figure)."""
    width = fig.bbox.width - 2 * TEXT_MARGIN
    titles = [(text, width) for text in (getattr(fig, "_suptitle", None),
                                         getattr(fig, "_supxlabel", None))
              if text is not None and text.get_text()]
    for ax in fig.axes:
        for text in (ax.title, getattr(ax, "_left_title", None),
                     getattr(ax, "_right_title", None)):
            if text is not None and text.get_text():
                titles.append((text, min(width, 1.15 * ax.bbox.width)))
    return titles


def wrap_text(text, renderer, allowed):
    """Breaks the lines of `text` (a matplotlib Text) so that none is wider than `allowed`
    pixels: after a ";" where that is enough, else between words (a single word wider
    than that stays on its own line)."""
    def width(candidate):
        text.set_text(candidate)
        return text.get_window_extent(renderer).width

    def greedy(pieces):
        lines, current = [], ""
        for piece in pieces:
            candidate = f"{current} {piece}" if current else piece
            if current and width(candidate) > allowed:
                lines.append(current)
                current = piece
            else:
                current = candidate
        return lines + [current]

    lines = []
    for line in text.get_text().split("\n"):
        if width(line) <= allowed:
            lines.append(line)
            continue
        for part in greedy(re.split(r"(?<=;) ", line)):
            lines.extend([part] if width(part) <= allowed else greedy(part.split(" ")))
    text.set_text("\n".join(lines))


def fit_texts(fig):
    """Lays out the figure so that every title lies inside it: a title wider than it may be
    (figure_titles) is wrapped, and, where the figure is not laid out by constrained layout,
    the subplots move down until the suptitle clears them."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    for text, allowed in figure_titles(fig):
        if text.get_window_extent(renderer).width > allowed:
            wrap_text(text, renderer, allowed)
    fig.canvas.draw()
    suptitle = getattr(fig, "_suptitle", None)
    if suptitle is not None and suptitle.get_text() and not fig.get_constrained_layout():
        bottom = suptitle.get_window_extent(renderer).y0 - TEXT_MARGIN
        top = max((ax.get_tightbbox(renderer).y1 for ax in fig.axes if ax.get_visible()),
                  default=bottom)
        if top > bottom:
            shift = (top - bottom) / fig.bbox.height
            for spec in {id(ax.get_subplotspec().get_gridspec()): ax.get_subplotspec()
                         .get_gridspec() for ax in fig.axes
                         if ax.get_subplotspec() is not None}.values():
                spec.update(top=spec.top - shift, bottom=min(spec.bottom, spec.top - shift - 0.3))
            fig.canvas.draw()


def save(fig, path, run=None):
    """Writes the figure as an RGB PNG, or as a 256-colour palette PNG when the RGB file
    would exceed MAX_PNG_BYTES (a palette can band smooth colour maps slightly). The run's
    load warning (Run.load_warning) ends the title; titles are fitted inside the figure first
    (fit_texts)."""
    warning = run.load_warning() if run is not None else ""
    if warning:
        suptitle = getattr(fig, "_suptitle", None)
        if suptitle is not None and suptitle.get_text():
            suptitle.set_text(f"{suptitle.get_text()}\n{warning}")
        elif fig.axes:
            fig.axes[0].set_title(f"{fig.axes[0].get_title()}\n{warning}")
    fit_texts(fig)
    buffer = io.BytesIO()
    fig.savefig(buffer, dpi=DPI, metadata=PNG_METADATA, format="png")
    plt.close(fig)
    buffer.seek(0)
    with Image.open(buffer) as image:
        rgb = image.convert("RGB")
        rgb.save(path, optimize=True)
        if os.path.getsize(path) > MAX_PNG_BYTES:
            rgb.quantize(colors=256, method=Image.Quantize.FASTOCTREE,
                         dither=Image.Dither.NONE).save(path, optimize=True)
    if not os.path.isfile(path) or os.path.getsize(path) == 0:
        raise RunError(f"{path} was not written")
    return path


def displacement_scale(designs):
    """(factor, text): one magnification for all designs. True scale when the largest
    displacement is already visible (≥ 2% of the body size), else the factor making it 5%."""
    size = max(float(np.max(d.points.max(axis=0) - d.points.min(axis=0))) for d in designs)
    u_max = 0.0
    for d in designs:
        u = d.point_array("displacement")
        if u is not None and u.size:
            u_max = max(u_max, float(np.nanmax(np.linalg.norm(u, axis=1))))
    if u_max == 0.0 or not math.isfinite(u_max):
        return 1.0, "undeformed (displacement zero)"
    if u_max >= 0.02 * size:
        return 1.0, f"displacement at true scale (largest {format_quantity(u_max, 'm')})"
    factor = 0.05 * size / u_max
    # A round factor reads better: 1, 2, 5 × 10^k not above the exact one.
    exponent = math.floor(math.log10(factor))
    for mantissa in (5, 2, 1):
        if mantissa * 10 ** exponent <= factor:
            factor = mantissa * 10 ** exponent
            break
    return factor, (f"displacement × {format_number(factor, 6)} (largest "
                    f"{format_quantity(u_max, 'm')})")


def von_mises_range(designs, where="point"):
    values = [d.point_array("von_mises") if where == "point" else d.cell_array("von_mises")
              for d in designs]
    values = [v[np.isfinite(v)] for v in values if v is not None]
    if not values:
        return None
    lo = min(float(v.min()) for v in values)
    hi = max(float(v.max()) for v in values)
    return lo, hi if hi > lo else lo + 1.0


def stress_levels(value_range, divisor):
    """(levels, cmap, norm) of a banded stress colour map in display units: about 16 bands
    with round boundaries covering value_range. Bands read like contour lines and match the
    colour bar exactly (a continuous map would be banded anyway by PNG palettes)."""
    lo, hi = value_range[0] / divisor, value_range[1] / divisor
    levels = MaxNLocator(nbins=16).tick_values(lo, hi)
    levels = levels[(levels >= levels[levels <= lo].max()) & (levels <= levels[levels >= hi].min())]
    cmap = colormaps[STRESS_CMAP].resampled(len(levels) - 1)
    return levels, cmap, BoundaryNorm(levels, cmap.N)


def stress_unit(hi):
    """(divisor, unit) giving readable stress numbers."""
    for divisor, unit in ((1e9, "GPa"), (1e6, "MPa"), (1e3, "kPa")):
        if abs(hi) >= divisor:
            return divisor, unit
    return 1.0, "Pa"


# ----------------------------------------------------------------------------------------
# 3D: the deformed body (VTK renders each design, matplotlib lays out titles and colour bar).

def cut_plane_x2(points):
    """The mesh plane x2 = const nearest to the middle: a cut there keeps whole cells, so the
    cut face is flat and shows the mesh (no stair-steps, no triangulated slivers)."""
    levels = np.unique(np.round(points[:, 1], 12))
    middle = 0.5 * (levels[0] + levels[-1])
    return float(levels[np.argmin(np.abs(levels - middle))])


# Camera directions (from the focal point, x3 up): the front view shows the cut face, the right
# side and the top; the view from below shows the contact face Γ_c, the front and the right.
VIEW_FRONT = (0.7, -1.9, 0.9)
VIEW_BELOW = (0.8, -1.5, -1.3)


def render_body_image(design, scale, value_range, cut, bounds, width, height,
                      view=VIEW_FRONT, zoom=1.6):
    """RGB image (height × width × 3) of one design's deformed body."""
    grid = design.grid
    source = vtk.vtkPassThrough()
    source.SetInputData(grid)
    port = source.GetOutputPort()
    if cut:
        # Cut in the design's reference configuration, where the mesh planes x2 = const are
        # exact, then warp: the cut face stays one mesh plane. The tiny shift keeps the cells
        # whose front face lies on the plane.
        y_cut = cut_plane_x2(design.points)
        plane = vtk.vtkPlane()
        plane.SetOrigin(0.0, y_cut - 1e-9 * (bounds[3] - bounds[2]), 0.0)
        plane.SetNormal(0.0, -1.0, 0.0)  # inside (value < 0): x2 > y_cut
        half = vtk.vtkExtractGeometry()
        half.SetInputConnection(port)
        half.SetImplicitFunction(plane)
        half.ExtractInsideOn()
        half.ExtractBoundaryCellsOff()
        port = half.GetOutputPort()
    if grid.GetPointData().GetArray("displacement") is not None:
        warp = vtk.vtkWarpVector()
        warp.SetInputConnection(port)
        warp.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS,
                                    "displacement")
        warp.SetScaleFactor(scale)
        port = warp.GetOutputPort()
    surface = vtk.vtkDataSetSurfaceFilter()
    surface.SetInputConnection(port)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputConnection(surface.GetOutputPort())
    if value_range is not None:
        # The banded map of the colour bar (stress_levels): equal bands from levels[0] to
        # levels[-1], in Pa.
        levels, cmap, _ = stress_levels(value_range, 1.0)
        lut = vtk.vtkLookupTable()
        lut.SetNumberOfTableValues(cmap.N)
        for i in range(cmap.N):
            lut.SetTableValue(i, *cmap(i))
        lut.SetTableRange(float(levels[0]), float(levels[-1]))
        mapper.SetLookupTable(lut)
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray("von_mises")
        mapper.SetUseLookupTableScalarRange(True)
        mapper.InterpolateScalarsBeforeMappingOn()  # sharp band edges across each face
        mapper.ScalarVisibilityOn()
    else:
        mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    # Mostly ambient light: the faces keep the colours of the colour bar, the diffuse part
    # still tells them apart.
    prop.SetAmbient(0.55)
    prop.SetDiffuse(0.45)
    if grid.GetNumberOfCells() <= 40000:  # edges help on coarse meshes, blacken fine ones
        prop.EdgeVisibilityOn()
        prop.SetEdgeColor(0.2, 0.2, 0.2)
        prop.SetLineWidth(0.6)

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor(actor)
    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(renderer)
    camera = renderer.GetActiveCamera()
    centre = [0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]),
              0.5 * (bounds[4] + bounds[5])]
    # From the front (−x2 side), a little to the right and above: the cut face, the right
    # side and the top show.
    camera.SetFocalPoint(*centre)
    extent = max(bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4], 1e-300)
    camera.SetPosition(*(c + extent * v for c, v in zip(centre, view)))
    camera.SetViewUp(0.0, 0.0, 1.0)
    renderer.ResetCamera(bounds)  # the same bounds for every design: comparable pictures
    camera.Zoom(zoom)
    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    image.ReadFrontBufferOff()
    image.Update()
    data = image.GetOutput()
    w, h, _ = data.GetDimensions()
    pixels = vtk_to_numpy(data.GetPointData().GetScalars()).reshape(h, w, -1)[::-1, :, :3]
    window.Finalize()
    return pixels.copy()


def picture_body_3d(run, out_dir, cut=True):
    designs = run.designs
    scale, scale_text = displacement_scale(designs)
    value_range = von_mises_range(designs)
    # Common bounds of the warped bodies, so that both panels use the same camera.
    bounds = [math.inf, -math.inf] * 3
    for d in designs:
        u = d.point_array("displacement")
        moved = d.points + (scale * np.nan_to_num(u) if u is not None else 0.0)
        for k in range(3):
            bounds[2 * k] = min(bounds[2 * k], float(moved[:, k].min()))
            bounds[2 * k + 1] = max(bounds[2 * k + 1], float(moved[:, k].max()))
    n = len(designs)
    width = 7.6 * n + 1.35
    fig = plt.figure(figsize=(max(width, 11.0), 7.2), dpi=DPI)
    grid_spec = fig.add_gridspec(1, n + 1, width_ratios=[7.6] * n + [0.25],
                                 left=0.01, right=1.0 - 1.0 / max(width, 11.0), top=0.84,
                                 bottom=0.03, wspace=0.04)
    for k, d in enumerate(designs):
        ax = fig.add_subplot(grid_spec[0, k])
        # Render at the panel's pixel size, so that the picture is not resampled.
        box = ax.get_window_extent()
        image = render_body_image(d, scale, value_range, cut, bounds,
                                  int(round(box.width)), int(round(box.height)))
        ax.imshow(image, interpolation="none")
        ax.set_axis_off()
        ax.set_title(d.title(run.cost_unit), fontsize=12)
    if value_range is not None:
        divisor, unit = stress_unit(value_range[1])
        bar_ax = fig.add_subplot(grid_spec[0, n])
        levels, cmap, norm = stress_levels(value_range, divisor)
        mappable = plt.cm.ScalarMappable(norm=norm, cmap=cmap)
        fig.colorbar(mappable, cax=bar_ax, ticks=levels[::2],
                     label=f"von Mises stress [{unit}] (nodal values, interpolated)")
    cut_text = ("cut at x2 = " + format_quantity(cut_plane_x2(designs[0].points), "m",
                                                 resolution=1e-9 * designs[0].size())
                + ", back half shown" if cut else "whole body")
    fig.suptitle(f"{run.headline()}: deformed body coloured by von Mises stress\n"
                 f"{scale_text}; {cut_text}; view from the front (−x2), x3 up",
                 fontsize=13)
    return save(fig, os.path.join(out_dir, "body_von_mises.png"), run)


# ----------------------------------------------------------------------------------------
# 3D: contact surface maps.

def contact_surface(design):
    """What the contact maps draw of one 3D design: the pieces of the contact facets per node
    (frictopt_vtu.node_pieces) in the plane (x1, x2) of the undeformed design, the node of each
    piece, and the nodal arrays of Γ_c. None without contact arrays or contact facets."""
    status = design.point_array("contact_status")
    if status is None:
        return None
    facets = contact_facets(design.grid)
    if not facets:
        return None
    polygons, nodes = node_pieces(design.points[:, :2], facets)
    traction = design.point_array("contact_traction")
    on_surface = np.unique(nodes)
    return {"polygons": polygons, "nodes": nodes, "surface_nodes": on_surface,
            "xy": design.points[:, :2],
            "p": design.point_array("contact_pressure"),
            "status": np.nan_to_num(status, nan=-1.0).astype(int),
            "traction": None if traction is None else np.nan_to_num(traction[:, :2])}


def piece_collection(surface, values, cmap, norm):
    """A PolyCollection of the surface's node pieces coloured by the nodal `values`. Pieces
    are drawn unsmoothed with their edges in their own colour, so that neighbouring pieces
    leave no hairline of background between them."""
    collection = PolyCollection(surface["polygons"], cmap=cmap, norm=norm,
                                edgecolors="face", linewidths=0.4, antialiaseds=False,
                                rasterized=True)
    collection.set_array(values[surface["nodes"]])
    return collection


def picture_contact_3d(run, out_dir):
    pairs = [(d, contact_surface(d)) for d in run.designs]
    pairs = [(d, s) for d, s in pairs if s is not None]
    if not pairs:
        return None
    designs = [d for d, _ in pairs]
    surfaces = [s for _, s in pairs]
    p_max = max((float(np.nanmax(s["p"][s["surface_nodes"]])) for s in surfaces
                 if s["p"] is not None), default=0.0)
    divisor, unit = stress_unit(p_max if p_max > 0 else 1.0)
    t_max = max((float(np.max(np.linalg.norm(s["traction"][s["surface_nodes"]], axis=1)))
                 for s in surfaces if s["traction"] is not None), default=0.0)

    # Every panel shows the same window: the contact facets of all designs.
    corners = np.concatenate([s["polygons"].reshape(-1, 2) for s in surfaces])
    lo, hi = corners.min(axis=0), corners.max(axis=0)
    pad = 0.02 * float(np.max(hi - lo))
    limits = [(lo[k] - pad, hi[k] + pad) for k in range(2)]
    resolution = 1e-9 * float(np.max(hi - lo))
    arrow_text = ""
    n = len(designs)
    # Panels 5.2 in wide, as high as the surface's aspect ratio asks (within limits).
    panel_height = min(max(5.2 * (hi[1] - lo[1]) / max(hi[0] - lo[0], 1e-300), 1.8), 6.0)
    fig, axes = plt.subplots(2, n, figsize=(5.2 * n + 1.6, 2.0 * panel_height + 2.0),
                             squeeze=False, constrained_layout=True)
    pressure_mappable = None
    status_cmap = ListedColormap([STATUS_COLOURS[c] for c in (0, 1, 2)])
    status_norm = BoundaryNorm([-0.5, 0.5, 1.5, 2.5], status_cmap.N)
    for k, (d, s) in enumerate(zip(designs, surfaces)):
        ax = axes[0, k]
        nodes = s["surface_nodes"]
        if s["p"] is not None:
            # Each node's value over its own pieces of the contact facets: what the solver
            # computed, without interpolation, and nothing where there is no contact facet.
            norm = Normalize(0.0, p_max / divisor if p_max > 0 else 1.0)
            pressure_mappable = piece_collection(s, s["p"] / divisor, PRESSURE_CMAP, norm)
            ax.add_collection(pressure_mappable)
            values = s["p"][nodes] / divisor
            ax.set_title(f"{d.title(run.cost_unit)}\ncontact pressure (nodal mean "
                         f"{format_quantity(np.nanmean(values), unit)}, max "
                         f"{format_quantity(np.nanmax(values), unit)})", fontsize=10)
        ax = axes[1, k]
        status = s["status"]
        ax.add_collection(piece_collection(s, status.astype(float), status_cmap, status_norm))
        codes = sorted(set(int(c) for c in status[nodes]))
        counts = ", ".join(f"{STATUS_NAMES[c]} {int(np.sum(status[nodes] == c))}"
                           for c in codes if c in STATUS_NAMES)
        ax.set_title(f"{d.title(run.cost_unit)}\nnodes: {counts}", fontsize=10)
        if s["traction"] is not None and t_max > 0:
            # No arrows on separated nodes (zero traction).
            keep = arrow_subset(s["xy"], nodes[status[nodes] > 0])
            spacing = float(np.max(hi - lo)) / 16
            ax.quiver(s["xy"][keep, 0], s["xy"][keep, 1], s["traction"][keep, 0],
                      s["traction"][keep, 1], angles="xy", scale_units="xy",
                      scale=t_max / spacing, width=0.004, color="black")
            arrow_text = ("arrows: tangential traction on the body (longest "
                          f"{format_quantity(t_max / divisor, unit)})")
    for ax in axes.ravel():
        ax.set_xlim(*limits[0])
        ax.set_ylim(*limits[1])
        ax.set_aspect("equal")
        ax.set_xlabel("x1 [m]")
        ax.set_ylabel("x2 [m]")
        ax.xaxis.set_major_formatter(lambda v, _: format_number(v, 6, resolution))
        ax.yaxis.set_major_formatter(lambda v, _: format_number(v, 6, resolution))
    if pressure_mappable is not None:
        fig.colorbar(pressure_mappable, ax=list(axes[0, :]), shrink=0.9,
                     label=f"contact pressure [{unit}]")
    handles = [Patch(facecolor=STATUS_COLOURS[c], edgecolor="none", label=STATUS_NAMES[c])
               for c in (0, 1, 2)]
    axes[1, -1].legend(handles=handles, loc="upper left", bbox_to_anchor=(1.02, 1.0),
                       fontsize=9, frameon=False)
    fig.suptitle(f"{run.headline()}: contact surface Γ_c seen from above "
                 "(positions of the undeformed design; each node's value over its share of "
                 "the contact facets)", fontsize=13)
    if arrow_text:
        fig.supxlabel(f"bottom row: contact status per node; {arrow_text}", fontsize=10)
    return save(fig, os.path.join(out_dir, "contact_maps.png"), run)


# ----------------------------------------------------------------------------------------
# 3D: the design's lift F_α over the chart, and the deformed body seen from below.

def bezier_surface(alpha, shape, s, t):
    """F_α(s, t) of the tensor Bézier surface with control net α[i + m1·j] (x1 fastest,
    docs/case-format.md [design]) at chart parameters s, t in [0, 1]
    (docs/theory/problem.md §2)."""
    m1, m2 = shape
    net = np.asarray(alpha, dtype=float).reshape(m2, m1)
    s, t = np.asarray(s, dtype=float), np.asarray(t, dtype=float)
    basis_s = np.array([math.comb(m1 - 1, i) * s ** i * (1 - s) ** (m1 - 1 - i)
                        for i in range(m1)])
    basis_t = np.array([math.comb(m2 - 1, j) * t ** j * (1 - t) ** (m2 - 1 - j)
                        for j in range(m2)])
    return np.einsum("ji,i...,j...->...", net, basis_s, basis_t)


def length_unit(value):
    """(divisor, unit) giving readable lengths."""
    for divisor, unit in ((1.0, "m"), (1e-3, "mm"), (1e-6, "µm")):
        if abs(value) >= divisor:
            return divisor, unit
    return 1e-9, "nm"


def inside_facets(points_2d, polygons):
    """Mask of the points that lie in at least one of the polygons (the contact facets)."""
    inside = np.zeros(len(points_2d), dtype=bool)
    for polygon in polygons:
        low, high = polygon.min(axis=0), polygon.max(axis=0)
        near = np.flatnonzero(~inside & np.all((points_2d >= low) & (points_2d <= high), axis=1))
        if near.size:
            inside[near] = Path(polygon).contains_points(points_2d[near], radius=1e-12)
    return inside


def lift_data(run):
    """What the lift panels draw, or (None, reason) when the run does not state enough."""
    designs = [d for d in run.designs if d.alpha is not None and len(d.alpha) >= 4]
    if not designs:
        return None, "the run records no design vector α"
    shape = run.control_points(len(designs[0].alpha))
    if shape is None:
        return None, "the case file gives no [design] control_points [m1, m2]"
    facets = contact_facets(designs[0].grid)
    if not facets:
        return None, "the .vtu file has no contact facets"
    chart = run.chart()
    nodes = np.unique(np.concatenate(facets))
    xy = designs[0].points[nodes, :2]
    chart_text = "chart from the run"
    if chart is None:
        # The default patch is Γ_c and the chart its bounding rectangle (docs/case-format.md).
        chart = (xy.min(axis=0), xy.max(axis=0) - xy.min(axis=0))
        chart_text = "chart: bounding rectangle of Γ_c"
    origin, extents = chart
    samples = 41
    s, t = np.meshgrid(np.linspace(0.0, 1.0, samples), np.linspace(0.0, 1.0, samples))
    x, y = origin[0] + extents[0] * s.ravel(), origin[1] + extents[1] * t.ravel()
    triangulation = Triangulation(x, y)
    polygons = [designs[0].points[f, :2] for f in facets]
    centroids = np.column_stack([x[triangulation.triangles].mean(axis=1),
                                 y[triangulation.triangles].mean(axis=1)])
    triangulation.set_mask(~inside_facets(centroids, polygons))
    lifts = [bezier_surface(d.alpha, shape, s.ravel(), t.ravel()) for d in designs]
    # The mesh's own patch nodes: their height above the foundation is F_α at their place when
    # the chart is right (the cross-check of the picture).
    deviation = 0.0
    for d in designs:
        node_xy = d.points[nodes, :2]
        predicted = bezier_surface(d.alpha, shape, (node_xy[:, 0] - origin[0]) / extents[0],
                                   (node_xy[:, 1] - origin[1]) / extents[1])
        deviation = max(deviation, float(np.max(np.abs(d.points[nodes, 2] - predicted))))
    return {"designs": designs, "shape": shape, "origin": origin, "extents": extents,
            "triangulation": triangulation, "lifts": lifts, "nodes": nodes,
            "chart_text": chart_text, "deviation": deviation}, None


def picture_shape_3d(run, out_dir):
    """shape.png of a 3D run: top, the lift F_α (the Bézier surface's height over the chart,
    vertical scale exaggerated) of each design with its control net and the patch nodes of the
    mesh; bottom, the deformed body seen from below, coloured by the von Mises stress."""
    lift, reason = lift_data(run)
    designs = run.designs
    n = len(designs)
    scale, scale_text = displacement_scale(designs)
    value_range = von_mises_range(designs)
    bounds = [math.inf, -math.inf] * 3
    for d in designs:
        u = d.point_array("displacement")
        moved = d.points + (scale * np.nan_to_num(u) if u is not None else 0.0)
        for k in range(3):
            bounds[2 * k] = min(bounds[2 * k], float(moved[:, k].min()))
            bounds[2 * k + 1] = max(bounds[2 * k + 1], float(moved[:, k].max()))
    width = max(6.8 * n + 1.4, 10.0)
    fig = plt.figure(figsize=(width, 12.0), dpi=DPI)
    grid_spec = fig.add_gridspec(2, n + 1, width_ratios=[6.8] * n + [0.22],
                                 height_ratios=[1.0, 1.0], left=0.02,
                                 right=1.0 - 1.1 / width, top=0.86, bottom=0.03,
                                 wspace=0.06, hspace=0.14)
    colours = [INITIAL_COLOUR, FINAL_COLOUR] if n == 2 else [FINAL_COLOUR] * n
    if lift is not None:
        everything = np.concatenate([f[~np.isnan(f)] for f in lift["lifts"]] +
                                    [np.asarray(d.alpha, dtype=float) for d in lift["designs"]])
        z_low, z_high = float(everything.min()), float(everything.max())
        divisor, unit = length_unit(max(abs(z_low), abs(z_high), 1e-300))
        if z_high <= z_low:
            z_high = z_low + max(abs(z_low), 1e-9)
        height_norm = Normalize(z_low / divisor, z_high / divisor)
        # Round-off on the nodes' heights (a body of size L: about 1e-16 L) reads as 0.
        resolution = 1e-9 * float(np.max(lift["extents"])) / divisor
        m1, m2 = lift["shape"]
        origin, extents = lift["origin"], lift["extents"]
        for k, d in enumerate(lift["designs"]):
            ax = fig.add_subplot(grid_spec[0, run.designs.index(d)], projection="3d")
            triangulation = lift["triangulation"]
            ax.plot_trisurf(triangulation, lift["lifts"][k] / divisor, cmap="cividis",
                            norm=height_norm, linewidth=0.0, antialiased=False, alpha=0.9)
            net = np.asarray(d.alpha, dtype=float).reshape(m2, m1) / divisor
            net_x, net_y = np.meshgrid(origin[0] + extents[0] * np.linspace(0, 1, m1),
                                       origin[1] + extents[1] * np.linspace(0, 1, m2))
            ax.plot_wireframe(net_x, net_y, net, color="black", lw=0.6, alpha=0.7)
            ax.scatter(net_x.ravel(), net_y.ravel(), net.ravel(), s=14, facecolors="white",
                       edgecolors="black", depthshade=False)
            ax.scatter(d.points[lift["nodes"], 0], d.points[lift["nodes"], 1],
                       d.points[lift["nodes"], 2] / divisor, s=1.5, color=colours[k],
                       depthshade=False)
            ax.set_zlim(z_low / divisor, z_high / divisor)
            ax.set_box_aspect((extents[0], extents[1], 0.45 * max(extents)))
            ax.view_init(elev=24, azim=-58)
            ax.set_xlabel("x1 [m]", fontsize=9)
            ax.set_ylabel("x2 [m]", fontsize=9)
            ax.set_zlabel(f"F_α [{unit}]", fontsize=9)
            ax.tick_params(labelsize=8)
            ax.set_title(f"{d.title(run.cost_unit)}\nlift F_α (surface), control net (○), "
                         "patch nodes of the mesh (•)", fontsize=10, color=colours[k])
        bar = fig.add_subplot(grid_spec[0, n])
        fig.colorbar(plt.cm.ScalarMappable(norm=height_norm, cmap="cividis"), cax=bar,
                     label=f"lift F_α [{unit}] (height above the foundation plane)")
        lift_text = (f"top: lift F_α over the chart ({lift['chart_text']}; {m1} × {m2} control "
                     "points; vertical scale exaggerated; mesh nodes off F_α by at most "
                     f"{format_quantity(lift['deviation'] / divisor, unit, resolution=resolution)})")
    else:
        ax = fig.add_subplot(grid_spec[0, :n])
        ax.set_axis_off()
        ax.text(0.5, 0.5, f"no lift picture: {reason}", ha="center", va="center",
                fontsize=12, transform=ax.transAxes)
        lift_text = f"top: no lift ({reason})"
    for k, d in enumerate(designs):
        ax = fig.add_subplot(grid_spec[1, k])
        box = ax.get_window_extent()
        image = render_body_image(d, scale, value_range, False, bounds,
                                  int(round(box.width)), int(round(box.height)),
                                  view=VIEW_BELOW, zoom=1.25)
        ax.imshow(image, interpolation="none")
        ax.set_axis_off()
        ax.set_title(f"{d.label}: deformed body seen from below", fontsize=10,
                     color=colours[k])
    if value_range is not None:
        divisor, unit = stress_unit(value_range[1])
        levels, cmap, norm = stress_levels(value_range, divisor)
        fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap),
                     cax=fig.add_subplot(grid_spec[1, n]), ticks=levels[::2],
                     label=f"von Mises stress [{unit}] (nodal values, interpolated)")
    fig.suptitle(f"{run.headline()}: shape of the contact surface and deformed body\n"
                 f"{lift_text}\nbottom: the whole body, {scale_text}, coloured by the von "
                 "Mises stress, seen from below (−x3), the contact face Γ_c in front",
                 fontsize=12)
    return save(fig, os.path.join(out_dir, "shape.png"), run)


# ----------------------------------------------------------------------------------------
# 2D: shape and deformed mesh; contact stress along Γ_c.

def bezier(alpha, a, samples=400):
    """(x1, F_α(x1)) of the Bézier curve with control points ((i a/(d−1)), α_i) (docs/theory/problem.md §2)."""
    alpha = np.asarray(alpha, dtype=float)
    degree = alpha.size - 1
    t = np.linspace(0.0, 1.0, samples)
    basis = np.array([math.comb(degree, i) * t ** i * (1 - t) ** (degree - i)
                      for i in range(degree + 1)])
    return a * t, alpha @ basis


def bottom_nodes(design):
    tags = design.point_array("boundary_tag")
    if tags is not None:
        mask = (tags.astype(int) & 1) != 0
    else:
        mask = design.contact_mask()
    if mask is None or not np.any(mask):
        return None
    order = np.argsort(design.points[mask, 0])
    return np.flatnonzero(mask)[order]


def picture_shape_2d(run, out_dir):
    designs = run.designs
    scale, scale_text = displacement_scale(designs)
    value_range = von_mises_range(designs, where="cell")
    divisor, unit = stress_unit(value_range[1] if value_range else 1.0)
    n = len(designs)
    x_min = min(float(d.points[:, 0].min()) for d in designs)
    x_max = max(float(d.points[:, 0].max()) for d in designs)
    a = x_max - x_min
    colours = [INITIAL_COLOUR, FINAL_COLOUR] if n == 2 else [FINAL_COLOUR] * n

    fig = plt.figure(figsize=(6.6 * n + 1.2 if n > 1 else 9.0, 8.4))
    grid_spec = fig.add_gridspec(2, n + 1, width_ratios=[1.0] * n + [0.04],
                                 height_ratios=[0.62, 1.0], left=0.07, right=0.93, top=0.88,
                                 bottom=0.07, hspace=0.28, wspace=0.12)
    # The bottom boundary F_α on its own axis (vertical scale exaggerated).
    ax = fig.add_subplot(grid_spec[0, :n])
    for d, colour in zip(designs, colours):
        style = "--" if (n == 2 and d is designs[0]) else "-"
        label = d.label + (f" (Θ = {format_quantity(d.cost, run.cost_unit, 4)})"
                           if d.cost is not None else "")
        if d.alpha is not None and len(d.alpha) >= 2:
            x, f = bezier(d.alpha, a)
            ax.plot(x_min + x, f, style, color=colour, lw=2.0, label=f"{label}: F_α")
            control_x = x_min + np.linspace(0.0, a, len(d.alpha))
            ax.plot(control_x, d.alpha, ":", marker="o", ms=4, mfc="none", color=colour,
                    lw=0.8, alpha=0.8)
        nodes = bottom_nodes(d)
        if nodes is not None:
            ax.plot(d.points[nodes, 0], d.points[nodes, 1], "o", ms=3.0, color=colour,
                    label=None if d.alpha is not None else f"{label}: bottom nodes")
    ax.axhline(0.0, color="black", lw=1.0)
    ax.set_xlim(x_min - 0.01 * a, x_max + 0.01 * a)
    y_top = ax.get_ylim()[1]
    ax.set_ylim(-0.08 * y_top, y_top)
    ax.fill_between([x_min - 0.01 * a, x_max + 0.01 * a], -0.08 * y_top, 0.0, color="#e0e0e0",
                    hatch="///", edgecolor="#9e9e9e", lw=0.0)
    ax.set_xlabel("x1 [m]")
    ax.set_ylabel("initial gap F_α(x1) [m]")
    ax.set_title("bottom of the body, vertical scale exaggerated\nBézier curve F_α, control "
                 "polygon (○, dotted), mesh nodes (•); foundation hatched", fontsize=10)
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(loc="best", fontsize=9, framealpha=0.9)
    ax.grid(alpha=0.3)

    # The deformed meshes, true aspect ratio.
    mappable = None
    y_low = min(0.0, min(float(np.min(d.points[:, 1] + scale * np.nan_to_num(
        d.point_array("displacement")[:, 1]))) for d in designs))
    y_high = max(float(np.max(d.points[:, 1] + scale * np.nan_to_num(
        d.point_array("displacement")[:, 1]))) for d in designs)
    x_low = min(float(np.min(d.points[:, 0] + scale * np.nan_to_num(
        d.point_array("displacement")[:, 0]))) for d in designs)
    x_high = max(float(np.max(d.points[:, 0] + scale * np.nan_to_num(
        d.point_array("displacement")[:, 0]))) for d in designs)
    margin = 0.04 * max(x_high - x_low, y_high - y_low)
    for k, d in enumerate(designs):
        ax = fig.add_subplot(grid_spec[1, k])
        cells = d.cells()
        u = np.nan_to_num(d.point_array("displacement"))
        moved = d.points[:, :2] + scale * u[:, :2]
        von_mises = d.cell_array("von_mises")
        polygons = moved[cells]
        collection = PolyCollection(polygons, edgecolors=(0.15, 0.15, 0.15, 0.6),
                                    linewidths=0.35, rasterized=True)
        if von_mises is not None and value_range is not None:
            levels, cmap, norm = stress_levels(value_range, divisor)
            collection.set_cmap(cmap)
            collection.set_norm(norm)
            collection.set_array(von_mises / divisor)
            mappable = collection
        else:
            collection.set_facecolor("#c6dbef")
        ax.add_collection(collection)
        # Undeformed outline of this design (reference configuration X(α)).
        outline = undeformed_outline(d)
        ax.plot(outline[:, 0], outline[:, 1], "--", color="#737373", lw=0.9)
        ax.axhline(0.0, color="black", lw=1.0)
        ax.fill_between([x_low - margin, x_high + margin], y_low - margin, 0.0,
                        color="#e0e0e0", hatch="///", edgecolor="#9e9e9e", lw=0.0, zorder=0)
        ax.set_xlim(x_low - margin, x_high + margin)
        ax.set_ylim(y_low - margin, y_high + margin)
        ax.set_aspect("equal")
        ax.set_xlabel("x1 [m]")
        if k == 0:
            ax.set_ylabel("x2 [m]")
        ax.set_title(d.title(run.cost_unit), fontsize=11, color=colours[k])
    if mappable is not None:
        fig.colorbar(mappable, cax=fig.add_subplot(grid_spec[1, n]), ticks=levels[::2],
                     label=f"von Mises stress [{unit}] (element centres)")
    fig.suptitle(f"{run.headline()}: shape of the bottom and deformed mesh\n"
                 f"mesh: {scale_text}; dashed: undeformed outline", fontsize=13)
    return save(fig, os.path.join(out_dir, "shape.png"), run)


def undeformed_outline(design):
    """Closed polygon of the boundary of a 2D body (reference configuration)."""
    extract = vtk.vtkFeatureEdges()
    surface = vtk.vtkDataSetSurfaceFilter()
    surface.SetInputData(design.grid)
    extract.SetInputConnection(surface.GetOutputPort())
    extract.BoundaryEdgesOn()
    extract.FeatureEdgesOff()
    extract.ManifoldEdgesOff()
    extract.NonManifoldEdgesOff()
    extract.Update()
    edges = extract.GetOutput()
    points = vtk_to_numpy(edges.GetPoints().GetData())[:, :2]
    lines = vtk_to_numpy(edges.GetLines().GetConnectivityArray()).reshape(-1, 2)
    # Chain the boundary edges into one loop.
    neighbours = {}
    for i, j in lines:
        neighbours.setdefault(int(i), []).append(int(j))
        neighbours.setdefault(int(j), []).append(int(i))
    start = int(lines[0, 0])
    loop, previous, current = [start], None, start
    while True:
        following = [p for p in neighbours[current] if p != previous]
        if not following or following[0] == start:
            break
        previous, current = current, following[0]
        loop.append(current)
        if len(loop) > len(neighbours):
            break
    loop.append(start)
    return points[loop]


def contact_profile(design):
    """x1-sorted contact node data of a 2D design, or None without contact arrays."""
    mask = design.contact_mask()
    if mask is None or not np.any(mask):
        return None
    idx = np.flatnonzero(mask)
    idx = idx[np.argsort(design.points[idx, 0])]
    traction = design.point_array("contact_traction")
    return {"x": design.points[idx, 0],
            "p": design.point_array("contact_pressure")[idx],
            "t": None if traction is None else traction[idx, 0],
            "status": design.point_array("contact_status")[idx].astype(int)}


def picture_contact_stress_2d(run, out_dir):
    designs = [d for d in run.designs if d.contact_mask() is not None]
    if not designs:
        return None
    profiles = [contact_profile(d) for d in designs]
    peak = max(float(np.nanmax(np.abs(np.concatenate(
        [p["p"]] + ([p["t"]] if p["t"] is not None else []))))) for p in profiles)
    divisor, unit = stress_unit(peak if peak > 0 else 1.0)
    n = len(designs)
    colours = [INITIAL_COLOUR, FINAL_COLOUR] if n == 2 else [FINAL_COLOUR] * n
    fig, (ax, strip) = plt.subplots(2, 1, figsize=(10.0, 6.9), sharex=True,
                                    gridspec_kw={"height_ratios": [1.0, 0.07 + 0.09 * n]},
                                    constrained_layout=True)
    for d, prof, colour in zip(designs, profiles, colours):
        label = d.label + (f", Θ = {format_quantity(d.cost, run.cost_unit, 4)}"
                           if d.cost is not None else "")
        ax.plot(prof["x"], prof["p"] / divisor, "-", marker="o", ms=3, color=colour, lw=1.8,
                label=f"normal: pressure λ_ν ({label})")
        if prof["t"] is not None:
            ax.plot(prof["x"], prof["t"] / divisor, "--", marker="s", ms=2.5, color=colour,
                    lw=1.4, label=f"tangential: traction τ₁ ({label})")
    ax.axhline(0.0, color="black", lw=0.6)
    ax.set_ylabel(f"contact stress [{unit}]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=9, loc="best", framealpha=0.9)
    ax.set_title(f"{run.headline()}: contact stress along Γ_c\n"
                 "solid: normal (pressure), dashed: tangential (traction on the body, +x1)",
                 fontsize=12)
    cmap = ListedColormap([STATUS_COLOURS[c] for c in (0, 1, 2)])
    norm = BoundaryNorm([-0.5, 0.5, 1.5, 2.5], cmap.N)
    for row, prof in enumerate(profiles):
        strip.scatter(prof["x"], np.full(prof["x"].size, -row), c=prof["status"], cmap=cmap,
                      norm=norm, marker="s", s=42, edgecolors="none")
    strip.set_yticks([-row for row in range(n)],
                     [d.label.split(" ")[0] if n > 1 else "" for d in designs], fontsize=9)
    strip.set_ylim(-n + 0.4, 0.6)
    strip.set_xlabel("x1 [m]")
    strip.legend(handles=[Patch(color=STATUS_COLOURS[c], label=STATUS_NAMES[c])
                          for c in (0, 1, 2)],
                 loc="upper left", bbox_to_anchor=(1.005, 1.2), fontsize=8, frameon=False)
    strip.set_title("status of the contact nodes", fontsize=9, loc="left")
    for side in ("top", "right", "left"):
        strip.spines[side].set_visible(False)
    return save(fig, os.path.join(out_dir, "contact_stress.png"), run)


# ----------------------------------------------------------------------------------------
# Convergence history.

# The steps of history.csv's "step" column (optim::StepKind): each iteration ends with one
# step, a serious step (the centre moves) or a null step (it stays), either directly or after a
# line search along the direction. summary.json's serious_steps and null_steps count both.
STEP_KINDS = (("serious", "serious step", "o", True), ("line_search_serious",
              "serious step after a line search", "s", True), ("null", "null step", "o", False),
              ("line_search_null", "null step after a line search", "s", False))


def step_counts(rows):
    """{kind: number of iterations that ended with that step} over the history's rows, and the
    method's own counters at its last row ((serious, null) from the columns serious_steps and
    null_steps, which are the counters summary.json reports; None when absent)."""
    counts = {kind: sum(1 for r in rows if r.get("step") == kind) for kind, *_ in STEP_KINDS}
    last = rows[-1] if rows else {}
    counters = None
    if "serious_steps" in last and "null_steps" in last:
        counters = (int(last["serious_steps"]), int(last["null_steps"]))
    return counts, counters


def picture_history(run, out_dir):
    rows = run.history
    if not rows:
        raise RunError(f"{os.path.join(run.dir, 'history.csv')}: no iterations recorded")
    iterations = [0] + [int(r["iteration"]) for r in rows]
    theta = [run.summary.get("initial_cost", float("nan"))] + [r["theta"] for r in rows]
    steps = np.array([""] + [r.get("step", "") for r in rows])
    stationarity = [float("nan")] + [r.get("stationarity_relative", float("nan")) for r in rows]
    iterations, theta, stationarity = (np.array(iterations), np.array(theta, dtype=float),
                                       np.array(stationarity, dtype=float))
    unit = run.cost_unit

    fig, ax = plt.subplots(figsize=(9.5, 5.6), constrained_layout=True)
    finite = np.isfinite(theta)
    # Θ at the centre holds until the next serious step: a staircase.
    ax.plot(iterations[finite], theta[finite], "-", color=FINAL_COLOUR, lw=1.4, zorder=2,
            drawstyle="steps-post")
    counts, counters = step_counts(rows)
    for kind, name, marker, filled in STEP_KINDS:
        which = steps == kind
        if not np.any(which) and kind.startswith("line_search"):
            continue
        ax.plot(iterations[which], theta[which], marker, ls="none", ms=5 if filled else 4.5,
                color=FINAL_COLOUR, mfc=FINAL_COLOUR if filled else "white", mec=FINAL_COLOUR,
                zorder=3, label=f"{name}: {int(which.sum())}")
    if finite[0]:
        ax.plot([0], [theta[0]], "D", color=INITIAL_COLOUR, ms=6, zorder=4,
                label="Θ at the initial design")
    if np.all(theta[finite] > 0):
        ax.set_yscale("log")
    ax.set_xlabel("iteration")
    ax.set_ylabel(f"Θ at the centre [{unit or 'unit not stated'}]  (cost {run.cost_name or '?'})",
                  color=FINAL_COLOUR)
    ax.tick_params(axis="y", colors=FINAL_COLOUR)
    ax.grid(alpha=0.3, which="both")

    handles, labels = ax.get_legend_handles_labels()
    has_stationarity = np.any(np.isfinite(stationarity))
    if has_stationarity:
        right = ax.twinx()
        right.plot(iterations, stationarity, "--", color="#2171b5", lw=1.2)
        if np.all(stationarity[np.isfinite(stationarity)] > 0):
            right.set_yscale("log")
        right.set_ylabel("stationarity ‖z+ω‖ / |Θ(α⁰)|", color="#2171b5")
        right.tick_params(axis="y", colors="#2171b5")
        handles.append(Line2D([], [], ls="--", color="#2171b5", lw=1.2))
        labels.append("stationarity measure (right axis)")
    ax.legend(handles, labels, fontsize=9, loc="upper right", framealpha=0.9,
              title="iterations of history.csv by the step that ended them",
              title_fontsize=9)
    s = run.summary
    first, last = s.get("initial_cost"), s.get("final_cost")
    change = (f"Θ {format_quantity(first, unit, 4)} → {format_quantity(last, unit, 4)}"
              if first is not None and last is not None else "")
    serious = s.get("serious_steps", counters[0] if counters else "?")
    null = s.get("null_steps", counters[1] if counters else "?")
    summary_counts = (f"{s.get('iterations', len(rows))} iterations, {serious} serious + "
                      f"{null} null steps, {s.get('evaluations', '?')} evaluations (oracle "
                      f"calls, line-search trials included), status {s.get('status', '?')}")
    note = ""
    recorded = int(rows[-1]["iteration"])
    total = s.get("iterations", recorded)
    if (isinstance(total, int) and total > recorded) or (
            counters is not None and (counters[0], counters[1]) != (serious, null)):
        # The runs that confirm a stop in the point's units (docs/optim.md) add iterations to
        # the summary but no rows to history.csv.
        note = (f"\nhistory.csv records iterations 1–{recorded}"
                + (f" ({counters[0]} serious, {counters[1]} null steps)" if counters else "")
                + f"; the other {total - recorded} iterations confirm the stop in the point's "
                "units and add no rows" if isinstance(total, int) else "")
    ax.set_title(f"{run.headline()}: convergence of the bundle trust method\n"
                 f"{change}; {summary_counts}{note}", fontsize=11)
    ax.set_xlim(-0.5, max(iterations.max(), 1) + 0.5)
    return save(fig, os.path.join(out_dir, "history.png"), run)


# ----------------------------------------------------------------------------------------

def render(run_dir, cut=True):
    run = Run(run_dir)
    out_dir = os.path.join(run_dir, "pictures")
    os.makedirs(out_dir, exist_ok=True)
    written = []
    if run.dim == 3:
        written.append(picture_body_3d(run, out_dir, cut=cut))
        written.append(picture_contact_3d(run, out_dir))
        written.append(picture_shape_3d(run, out_dir))
    else:
        written.append(picture_shape_2d(run, out_dir))
        written.append(picture_contact_stress_2d(run, out_dir))
    if run.kind == "optimize":
        written.append(picture_history(run, out_dir))
    return [w for w in written if w is not None]


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_dir", help="output directory of frictopt optimize or solve")
    parser.add_argument("--no-cut", action="store_true",
                        help="3D: show the whole body instead of the half behind x2 = b/2")
    args = parser.parse_args()
    try:
        written = render(args.run_dir, cut=not args.no_cut)
    except VtuError as error:  # RunError or an unreadable .vtu
        sys.exit(f"render_run: {error}")
    for path in written:
        print(f"render_run: wrote {path} ({os.path.getsize(path) // 1024} kB)")


if __name__ == "__main__":
    main()
