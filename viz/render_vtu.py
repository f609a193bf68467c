#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Render every .vtu file in a directory to PNG pictures next to it.

For each FILE.vtu:
  FILE.png          the deformed body (warped by the point array `displacement`, scaled so
                    that the largest warp is 10% of the body size; the factor is in the
                    title), coloured by `von_mises` (point or cell data) with a scalar bar,
                    over the grey outline of the undeformed body. In 3D the body is cut at
                    the mesh plane nearest to x2 = b/2 (in the undeformed body, then warped,
                    so the cut face is flat) and the back half is shown, so the stresses
                    under the contact are visible (--no-cut shows the whole body).
  FILE_contact.png  only if `contact_pressure` and/or `contact_status` exist: a top-down map
                    (3D) or a profile along x1 (2D) of them on the contact surface. Nodes off
                    the contact surface carry NaN pressure / status -1 and are skipped.

Status codes: 0 separated, 1 stick, 2 slip (docs/case-format.md, "Output arrays").

Usage (VTK needs an X display even off screen with Debian's VTK; run_headless provides one):
    viz/run_headless.sh /usr/bin/python3 viz/render_vtu.py DIR [--size 1200x800]
Use /usr/bin/python3: Debian's python3-vtk9 is installed for the system interpreter only.
Exits non-zero if DIR holds no .vtu file or a picture could not be written.
"""

import argparse
import glob
import os
import sys

try:
    import numpy as np
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy
    from frictopt_vtu import (STATUS_COLOURS, STATUS_NAMES, contact_facets, format_quantity,
                              node_pieces, read_grid)
except ImportError as error:  # the usual cause: a pyenv/venv python3 on PATH
    sys.exit(f"render_vtu: {error}; run it with /usr/bin/python3 (Debian's python3-vtk9)")

# Largest warp as a fraction of the body size: large enough to see the deformation, small
# enough that the body keeps its shape.
WARP_FRACTION = 0.10


def find_array(grid, name):
    """('point' | 'cell', vtkDataArray) for the first array called `name`, or (None, None)."""
    for kind, data in (("point", grid.GetPointData()), ("cell", grid.GetCellData())):
        array = data.GetArray(name)
        if array is not None:
            return kind, array
    return None, None


def body_size(grid):
    x0, x1, y0, y1, z0, z1 = grid.GetBounds()
    return max(x1 - x0, y1 - y0, z1 - z0)


def is_planar(grid):
    x0, x1, y0, y1, z0, z1 = grid.GetBounds()
    return (z1 - z0) <= 1e-12 * max(x1 - x0, y1 - y0, 1e-300)


def warp_scale(grid):
    """Scale factor making the largest displacement WARP_FRACTION of the body size."""
    kind, displacement = find_array(grid, "displacement")
    if kind != "point":
        return None
    u = vtk_to_numpy(displacement).reshape(grid.GetNumberOfPoints(), -1)
    u_max = float(np.nanmax(np.linalg.norm(u, axis=1))) if u.size else 0.0
    if not np.isfinite(u_max) or u_max == 0.0:
        return 0.0
    return WARP_FRACTION * body_size(grid) / u_max


def surface_filter():
    surface = vtk.vtkDataSetSurfaceFilter()
    return surface


def render_body(grid, png_path, width, height, cut=True):
    scale = warp_scale(grid)
    planar = is_planar(grid)
    cut = cut and not planar

    # Undeformed outline, for reference.
    undeformed = surface_filter()
    undeformed.SetInputData(grid)
    outline = vtk.vtkFeatureEdges()
    outline.SetInputConnection(undeformed.GetOutputPort())
    outline.BoundaryEdgesOn()
    outline.FeatureEdgesOn()
    outline.ManifoldEdgesOff()
    outline.NonManifoldEdgesOff()
    outline.ColoringOff()
    outline_mapper = vtk.vtkPolyDataMapper()
    outline_mapper.SetInputConnection(outline.GetOutputPort())
    outline_actor = vtk.vtkActor()
    outline_actor.SetMapper(outline_mapper)
    outline_actor.GetProperty().SetColor(0.55, 0.55, 0.55)
    outline_actor.GetProperty().SetLineWidth(1.5)

    # Deformed body. In 3D the stresses that matter sit under the contact, inside the body:
    # keep the cells behind the mesh plane x2 = const nearest to the middle and look at the cut
    # from the front. The cut is made in the undeformed configuration (where the planes
    # x2 = const of the structured mesh are exact) and warped afterwards, so the cut face is
    # one flat mesh plane: cutting the warped body instead gives stair-steps where the warp
    # moves nodes across the plane.
    x0, x1, y0, y1, z0, z1 = grid.GetBounds()
    source = vtk.vtkPassThrough()
    source.SetInputData(grid)
    deformed = source.GetOutputPort()
    y_cut = 0.5 * (y0 + y1)
    if cut:
        points = vtk_to_numpy(grid.GetPoints().GetData())
        levels = np.unique(np.round(points[:, 1], 12))
        y_cut = float(levels[np.argmin(np.abs(levels - y_cut))])
        plane = vtk.vtkPlane()
        plane.SetOrigin(0.0, y_cut - 1e-9 * (y1 - y0), 0.0)
        plane.SetNormal(0.0, -1.0, 0.0)  # "inside" (value < 0) is x2 > y_cut
        half = vtk.vtkExtractGeometry()
        half.SetInputConnection(deformed)
        half.SetImplicitFunction(plane)
        half.ExtractInsideOn()
        half.ExtractBoundaryCellsOff()
        deformed = half.GetOutputPort()
    if scale is not None:
        warp = vtk.vtkWarpVector()
        warp.SetInputConnection(deformed)
        warp.SetInputArrayToProcess(0, 0, 0, vtk.vtkDataObject.FIELD_ASSOCIATION_POINTS,
                                    "displacement")
        warp.SetScaleFactor(scale)
        deformed = warp.GetOutputPort()
    body = surface_filter()
    body.SetInputConnection(deformed)
    mapper = vtk.vtkDataSetMapper()
    mapper.SetInputConnection(body.GetOutputPort())

    kind, von_mises = find_array(grid, "von_mises")
    colour_name = "von_mises"
    if von_mises is None:  # fall back to the displacement magnitude, and say so
        kind, von_mises = find_array(grid, "displacement")
        colour_name = "|displacement|"
    scalar_bar = None
    if von_mises is not None:
        lut = vtk.vtkLookupTable()
        lut.SetHueRange(0.667, 0.0)  # blue (low) to red (high)
        lut.SetNumberOfTableValues(256)
        lut.Build()
        mapper.SetLookupTable(lut)
        mapper.ScalarVisibilityOn()
        if kind == "point":
            mapper.SetScalarModeToUsePointFieldData()
        else:
            mapper.SetScalarModeToUseCellFieldData()
        mapper.SelectColorArray(von_mises.GetName())
        if von_mises.GetNumberOfComponents() > 1:
            lut.SetVectorModeToMagnitude()
            lo, hi = von_mises.GetRange(-1)
        else:
            lo, hi = von_mises.GetRange(0)
        mapper.SetScalarRange(lo, hi if hi > lo else lo + 1.0)
        scalar_bar = vtk.vtkScalarBarActor()
        scalar_bar.SetLookupTable(lut)
        scalar_bar.SetTitle(f"{colour_name} [Pa]\n" if colour_name == "von_mises"
                            else f"{colour_name} [m]\n")
        scalar_bar.SetNumberOfLabels(5)
        scalar_bar.SetLabelFormat("%-#6.3g")
        # Placed in its own viewport at the right (below), so it never covers the body.
        scalar_bar.SetPosition(0.05, 0.12)
        scalar_bar.SetWidth(0.6)
        scalar_bar.SetHeight(0.70)
        for prop in (scalar_bar.GetTitleTextProperty(), scalar_bar.GetLabelTextProperty()):
            prop.SetColor(0.1, 0.1, 0.1)
            prop.ShadowOff()
            prop.ItalicOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    if grid.GetNumberOfCells() <= 20000:  # edges help on coarse meshes, blacken fine ones
        actor.GetProperty().EdgeVisibilityOn()
        actor.GetProperty().SetEdgeColor(0.25, 0.25, 0.25)
        actor.GetProperty().SetLineWidth(0.5)

    name = os.path.basename(png_path)[:-4]
    if scale is None:
        warp_text = "undeformed (no point array 'displacement')"
    elif scale == 0.0:
        warp_text = "displacement is zero"
    else:
        warp_text = (f"displacement x {scale:.3g} "
                     f"(largest warp = {WARP_FRACTION:.0%} of body size)")
    cut_text = (f", cut at x2 = {format_quantity(y_cut, 'm', resolution=1e-9 * body_size(grid))}"
                " (back half)" if cut else "")
    title = vtk.vtkTextActor()
    title.SetInput(f"{name}: coloured by {colour_name}{cut_text}\n{warp_text}")
    title.GetTextProperty().SetFontSize(20)
    title.GetTextProperty().SetColor(0.1, 0.1, 0.1)
    title.SetDisplayPosition(15, height - 60)

    renderer = vtk.vtkRenderer()
    renderer.SetBackground(1.0, 1.0, 1.0)
    renderer.AddActor(actor)
    renderer.AddActor(outline_actor)
    renderer.AddActor2D(title)

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(renderer)
    if scalar_bar is not None:
        renderer.SetViewport(0.0, 0.0, 0.86, 1.0)
        bar_renderer = vtk.vtkRenderer()
        bar_renderer.SetViewport(0.86, 0.0, 1.0, 1.0)
        bar_renderer.SetBackground(1.0, 1.0, 1.0)
        bar_renderer.AddActor2D(scalar_bar)
        window.AddRenderer(bar_renderer)

    camera = renderer.GetActiveCamera()
    if planar:
        camera.ParallelProjectionOn()
        camera.SetPosition(0, 0, 1)
        camera.SetFocalPoint(0, 0, 0)
        camera.SetViewUp(0, 1, 0)
    else:
        # Looking from the front (−x2 side), slightly above: top, front and right faces show.
        camera.SetPosition(0.6, -1.6, 0.9)
        camera.SetFocalPoint(0, 0, 0)
        camera.SetViewUp(0, 0, 1)
    renderer.ResetCamera()
    camera.Zoom(1.15 if planar else 1.3)

    window.Render()
    image = vtk.vtkWindowToImageFilter()
    image.SetInput(window)
    image.ReadFrontBufferOff()
    image.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(png_path)
    writer.SetInputConnection(image.GetOutputPort())
    writer.Write()
    window.Finalize()


def contact_values(grid, name):
    """(positions n×3, values n) of array `name`, at points or at cell centres."""
    kind, array = find_array(grid, name)
    if array is None:
        return None, None
    values = vtk_to_numpy(array).astype(float)
    if values.ndim > 1:
        values = np.linalg.norm(values, axis=1)
    if kind == "point":
        positions = vtk_to_numpy(grid.GetPoints().GetData())
    else:
        centres = vtk.vtkCellCenters()
        centres.SetInputData(grid)
        centres.Update()
        positions = vtk_to_numpy(centres.GetOutput().GetPoints().GetData())
    return positions, values


def render_contact(grid, png_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import PolyCollection
    from matplotlib.colors import ListedColormap, BoundaryNorm, Normalize
    from matplotlib.patches import Patch

    p_pos, pressure = contact_values(grid, "contact_pressure")
    s_pos, status = contact_values(grid, "contact_status")
    panels = [(n, pos, val) for n, pos, val in (("contact_pressure", p_pos, pressure),
                                                ("contact_status", s_pos, status))
              if val is not None]
    planar = is_planar(grid)
    # In 3D each node's value is drawn over its pieces of the contact facets (node_pieces):
    # nothing over an empty slot between two contact faces, no holes on unstructured meshes.
    pieces = None
    if not planar and p_pos is not None and len(p_pos) == grid.GetNumberOfPoints():
        facets = contact_facets(grid)
        if facets:
            pieces = node_pieces(vtk_to_numpy(grid.GetPoints().GetData())[:, :2], facets)

    def draw_pieces(ax, values, cmap, norm):
        collection = PolyCollection(pieces[0], cmap=cmap, norm=norm, edgecolors="face",
                                    linewidths=0.4, antialiaseds=False, rasterized=True)
        collection.set_array(values[pieces[1]])
        ax.add_collection(collection)
        corners = pieces[0].reshape(-1, 2)
        ax.set_xlim(corners[:, 0].min(), corners[:, 0].max())
        ax.set_ylim(corners[:, 1].min(), corners[:, 1].max())
        return collection

    # In 2D the status is a single row of markers: give it a thin panel.
    ratios = [0.35 if (planar and n == "contact_status") else 1.0 for n, _, _ in panels]
    fig, axes = plt.subplots(len(panels), 1, squeeze=False,
                             figsize=(8, (3.4 if planar else 3.8) * sum(ratios) + 0.6),
                             gridspec_kw={"height_ratios": ratios})
    name = os.path.basename(png_path)[:-len("_contact.png")]
    fig.suptitle(f"{name}: contact surface" + ("" if planar else " seen from above"))
    for ax, (array_name, pos, values) in zip(axes[:, 0], panels):
        on_surface = np.isfinite(values)
        if array_name == "contact_status":
            on_surface &= values >= 0
        if status is not None and array_name == "contact_pressure" and len(status) == len(values):
            on_surface &= status >= 0
        x, y, v = pos[on_surface, 0], pos[on_surface, 1], values[on_surface]
        if v.size == 0:
            ax.text(0.5, 0.5, f"no {array_name} values on the contact surface",
                    ha="center", va="center", transform=ax.transAxes)
            continue
        if array_name == "contact_pressure":
            if planar:
                order = np.argsort(x)
                ax.plot(x[order], v[order], "-o", ms=3, color="#08519c")
                ax.set_xlabel("x1 [m]")
                ax.set_ylabel("contact pressure [Pa]")
                ax.grid(alpha=0.3)
            elif pieces is not None:
                mappable = draw_pieces(ax, values, "viridis", Normalize(v.min(), v.max()))
                fig.colorbar(mappable, ax=ax, label="contact pressure [Pa]")
            else:
                mappable = ax.scatter(x, y, c=v, s=12, cmap="viridis")
                fig.colorbar(mappable, ax=ax, label="contact pressure [Pa]")
        else:
            codes = sorted(set(int(c) for c in v))
            colours = [STATUS_COLOURS.get(c, "#000000") for c in codes]
            cmap = ListedColormap(colours)
            norm = BoundaryNorm([c - 0.5 for c in codes] + [codes[-1] + 0.5], cmap.N)
            if planar:
                ax.scatter(x, np.zeros_like(x), c=v, cmap=cmap, norm=norm, s=40, marker="s")
                ax.set_yticks([])
                ax.set_xlabel("x1 [m]")
            elif pieces is not None:
                draw_pieces(ax, values, cmap, norm)
            else:
                ax.scatter(x, y, c=v, cmap=cmap, norm=norm, s=18, marker="s")
            ax.legend(handles=[Patch(color=STATUS_COLOURS.get(c, "#000000"),
                                     label=STATUS_NAMES.get(c, f"status {c}")) for c in codes],
                      loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
        ax.set_title(array_name)
        if not planar:
            ax.set_aspect("equal")
            ax.set_xlabel("x1 [m]")
            ax.set_ylabel("x2 [m]")
    fig.tight_layout()
    fig.savefig(png_path, dpi=110, bbox_inches="tight")  # keeps the outside legend
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("directory", help="directory holding .vtu files")
    parser.add_argument("--size", default="1200x800", help="picture size WIDTHxHEIGHT")
    parser.add_argument("--no-cut", action="store_true",
                        help="3D: show the whole body instead of the half behind x2 = b/2")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.lower().split("x"))

    files = sorted(glob.glob(os.path.join(args.directory, "*.vtu")))
    if not files:
        sys.exit(f"render_vtu: no .vtu files in {args.directory}")
    failures = 0
    for path in files:
        stem = path[:-4]
        try:
            grid = read_grid(path)
            render_body(grid, stem + ".png", width, height, cut=not args.no_cut)
            written = [stem + ".png"]
            if (find_array(grid, "contact_pressure")[1] is not None
                    or find_array(grid, "contact_status")[1] is not None):
                render_contact(grid, stem + "_contact.png")
                written.append(stem + "_contact.png")
            for png in written:
                if not os.path.isfile(png) or os.path.getsize(png) == 0:
                    raise RuntimeError(f"{png} was not written")
            print("render_vtu: wrote " + ", ".join(written))
        except Exception as error:  # report every file, then fail
            failures += 1
            print(f"render_vtu: {path}: {error}", file=sys.stderr)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
