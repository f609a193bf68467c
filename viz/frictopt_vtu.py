"""What the picture scripts share: reading the .vtu files frictopt writes, and the contact-status
legend (names and colours). Imported by render_run.py and render_vtu.py, which import vtk first
(with the message about /usr/bin/python3 if it is missing)."""

import os

import vtk

STATUS_NAMES = {0: "separated", 1: "stick", 2: "slip"}
STATUS_COLOURS = {0: "#d0d0d0", 1: "#2171b5", 2: "#e6550d"}


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
