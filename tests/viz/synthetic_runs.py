"""Small run directories written the way frictopt writes them (.vtu arrays of
docs/case-format.md "Output arrays", summary.json, history.csv, case.toml), for the picture
tests: bodies frictopt's own cases do not give quickly — two contact faces separated by an empty
slot, an unstructured contact surface, a body centred on x2 = 0 — and histories with every kind
of step."""

import csv
import json
import os

import numpy as np
import vtk
from vtk.util.numpy_support import numpy_to_vtk

CONTACT, DIRICHLET = 1, 2


def hex_body(x_levels, y_levels, z_levels, keep=None, jitter=0.0, seed=3):
    """(points, hexahedra) of the box grid over the levels; `keep(i, j, k)` drops the cells it
    rejects (and the nodes no cell uses); `jitter` moves the interior nodes of every x3 level
    in x1 and x2 by up to that fraction of the spacing, so that the grid is unstructured."""
    nx, ny, nz = len(x_levels), len(y_levels), len(z_levels)
    index = np.arange(nx * ny * nz).reshape(nz, ny, nx)
    points = np.array([[x, y, z] for z in z_levels for y in y_levels for x in x_levels], float)
    if jitter:
        rng = np.random.default_rng(seed)
        dx, dy = np.min(np.diff(x_levels)), np.min(np.diff(y_levels))
        for j in range(1, ny - 1):
            for i in range(1, nx - 1):
                shift = rng.uniform(-jitter, jitter, 2) * (dx, dy)
                points[index[:, j, i], 0] += shift[0]
                points[index[:, j, i], 1] += shift[1]
    cells = []
    for k in range(nz - 1):
        for j in range(ny - 1):
            for i in range(nx - 1):
                if keep is not None and not keep(i, j, k):
                    continue
                cells.append([index[k, j, i], index[k, j, i + 1], index[k, j + 1, i + 1],
                              index[k, j + 1, i], index[k + 1, j, i], index[k + 1, j, i + 1],
                              index[k + 1, j + 1, i + 1], index[k + 1, j + 1, i]])
    cells = np.array(cells, dtype=int)
    used = np.unique(cells)
    renumber = np.full(len(points), -1)
    renumber[used] = np.arange(used.size)
    return points[used], renumber[cells]


def write_vtu(path, points, cells, contact, pressure, status, lift=0.0):
    """A frictopt-like .vtu of a body whose nodes `contact` (mask) form Γ_c at x3 = lift."""
    n = len(points)
    grid = vtk.vtkUnstructuredGrid()
    vtk_points = vtk.vtkPoints()
    vtk_points.SetData(numpy_to_vtk(points.copy(), deep=True))
    grid.SetPoints(vtk_points)
    for cell in cells:
        ids = vtk.vtkIdList()
        for node in cell:
            ids.InsertNextId(int(node))
        grid.InsertNextCell(vtk.VTK_HEXAHEDRON, ids)

    def add(name, values, where="point"):
        array = numpy_to_vtk(np.ascontiguousarray(values), deep=True)
        array.SetName(name)
        (grid.GetPointData() if where == "point" else grid.GetCellData()).AddArray(array)

    height = points[:, 2].max()
    displacement = np.zeros((n, 3))
    displacement[:, 2] = -1e-4 * (points[:, 2] - points[:, 2].min() + 0.1)
    add("displacement", displacement)
    add("von_mises", 1e7 * (1.0 + points[:, 0] + points[:, 2] / height))
    tags = np.where(contact, CONTACT, 0) | np.where(points[:, 2] >= height - 1e-12, DIRICHLET, 0)
    add("boundary_tag", tags.astype(np.int32))
    full_pressure = np.full(n, np.nan)
    full_pressure[contact] = pressure
    full_status = np.full(n, -1, dtype=np.int32)
    full_status[contact] = status
    traction = np.full((n, 3), np.nan)
    traction[contact] = 0.0
    traction[contact, 0] = 0.2 * np.where(full_status[contact] > 0, pressure, 0.0)
    add("contact_pressure", full_pressure)
    add("contact_traction", traction)
    add("contact_status", full_status)
    add("von_mises", 1e7 * np.ones(len(cells)), where="cell")
    writer = vtk.vtkXMLUnstructuredGridWriter()
    writer.SetFileName(path)
    writer.SetInputData(grid)
    if not writer.Write():
        raise RuntimeError(f"{path} not written")


def contact_values(points, contact, seed=0):
    """Pressure (about 100 MPa) and a stick/slip/separated status on the contact nodes."""
    xy = points[contact, :2]
    pressure = 1e8 * (1.0 + 0.3 * np.sin(3.0 * xy[:, 0]) * np.cos(2.0 * xy[:, 1]))
    status = np.where(xy[:, 0] < np.median(xy[:, 0]), 1, 2).astype(np.int32)
    status[np.argmin(xy[:, 0] + xy[:, 1])] = 0
    pressure[status == 0] = 0.0
    return pressure, status


def bracket(lift=0.0):
    """A two-foot bracket 3 m × 1 m × 1 m: feet 0 <= x1 <= 1 and 2 <= x1 <= 3 on the
    foundation, an empty slot 1 < x1 < 2 below x3 = 0.5 (cells of 0.5 m)."""
    levels = np.arange(0.0, 3.01, 0.5)
    points, cells = hex_body(levels, [0.0, 0.5, 1.0], [0.0, 0.5, 1.0],
                             keep=lambda i, j, k: not (k == 0 and i in (2, 3)))
    points[:, 2] += lift
    return points, cells, np.abs(points[:, 2] - lift) < 1e-12


def unstructured_pad(lift=0.0):
    """A 1 m × 1 m × 0.4 m pad whose contact surface x3 = 0 is an unstructured quadrilateral
    mesh (the interior nodes of a 7 × 7 grid moved by up to 30% of the spacing)."""
    levels = np.linspace(0.0, 1.0, 8)
    points, cells = hex_body(levels, levels, [0.0, 0.2, 0.4], jitter=0.3)
    points[:, 2] += lift
    return points, cells, np.abs(points[:, 2] - lift) < 1e-12


def centred_block():
    """A block 1 m × 1 m × 0.5 m centred on x2 = 0, whose middle mesh plane is written as −0."""
    points, cells = hex_body(np.linspace(0.0, 1.0, 5), [-0.5, -0.25, -0.0, 0.25, 0.5],
                             [0.0, 0.25, 0.5])
    points[np.abs(points[:, 1]) < 1e-15, 1] = -0.0
    return points, cells, np.abs(points[:, 2]) < 1e-12


def write_solve_run(directory, body, name="synthetic", case_path=None):
    """A `frictopt solve`-like directory: NAME.vtu and summary.json."""
    os.makedirs(directory, exist_ok=True)
    points, cells, contact = body
    pressure, status = contact_values(points, contact)
    write_vtu(os.path.join(directory, f"{name}.vtu"), points, cells, contact, pressure, status)
    summary = {"case": case_path or f"cases3d/{name}/case.toml", "command": "solve"}
    with open(os.path.join(directory, "summary.json"), "w", encoding="utf-8") as stream:
        json.dump(summary, stream)
    return directory


HISTORY_COLUMNS = ["iteration", "evaluations", "step", "theta", "t", "stationarity_relative",
                   "aggregate_error_relative", "bundle_size", "serious_steps", "null_steps",
                   "state_solves", "coulomb_iterations", "qp_iterations", "weak_nodes",
                   "state_seconds", "subgradient_seconds", "elapsed_seconds"]


def write_optimize_run(directory, body_of_lift, steps, name="synthetic", control_points=(3, 2),
                       cost_unit="N²", case_path=None, confirmation_iterations=0, loads=None):
    """An `frictopt optimize`-like directory: NAME_iter0000.vtu and the final iterate (the
    body at a flat lift α = const), NAME.pvd, history.csv with one row per entry of `steps`
    (optim::StepKind spellings), summary.json and case.toml. `confirmation_iterations` more
    iterations are counted in the summary only, as the confirmation runs in the point's units
    do (docs/optim.md). `loads` = (P⁰, P): summary.json's initial and final total normal
    force, with frictopt's load warning when they differ by more than 10 %."""
    os.makedirs(directory, exist_ok=True)
    m1, m2 = control_points
    alphas = [np.full(m1 * m2, 1e-3), np.full(m1 * m2, 2e-3)]
    iterations = [0, len(steps)]
    for iteration, alpha in zip(iterations, alphas):
        points, cells, contact = body_of_lift(float(alpha[0]))
        pressure, status = contact_values(points, contact)
        write_vtu(os.path.join(directory, f"{name}_iter{iteration:04d}.vtu"), points, cells,
                  contact, pressure, status)
    with open(os.path.join(directory, f"{name}.pvd"), "w", encoding="utf-8") as stream:
        stream.write('<?xml version="1.0"?>\n<VTKFile type="Collection" version="0.1">\n'
                     "<Collection>\n")
        for iteration in iterations:
            stream.write(f'<DataSet timestep="{iteration}" file="{name}_iter{iteration:04d}'
                         '.vtu"/>\n')
        stream.write("</Collection>\n</VTKFile>\n")
    serious = null = evaluations = 0
    theta = 4.0e9
    with open(os.path.join(directory, "history.csv"), "w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(HISTORY_COLUMNS)
        for k, step in enumerate(steps, start=1):
            evaluations += 3 if step.startswith("line_search") else 1
            if step.endswith("serious"):
                serious += 1
                theta *= 0.7
            else:
                null += 1
            writer.writerow([k, evaluations, step, theta, 1.0, 0.1 / k, 0.0, 5, serious, null,
                             evaluations, 3, 10, 0, 0.01, 0.01, 0.1 * k])
    summary = {"case": case_path or f"cases3d/{name}/case.toml", "command": "optimize",
               "cost": "target_normal_force", "cost_kind": "target_pressure",
               "status": "converged", "initial_cost": 4.0e9, "final_cost": theta,
               "alpha": alphas[1].tolist(), "initial_alpha": alphas[0].tolist(),
               "iterations": len(steps) + confirmation_iterations, "serious_steps": serious,
               "null_steps": null,
               "evaluations": evaluations}
    if cost_unit is not None:
        summary["cost_unit"] = cost_unit
    if loads is not None:
        p0, p = loads
        summary["initial_load"] = {"total_normal_force": p0}
        summary["final_load"] = {"total_normal_force": p}
        summary["warnings"] = (["the final design carries a different load"]
                               if abs(p - p0) > 0.1 * p0 else [])
    with open(os.path.join(directory, "summary.json"), "w", encoding="utf-8") as stream:
        json.dump(summary, stream)
    with open(os.path.join(directory, "case.toml"), "w", encoding="utf-8") as stream:
        stream.write(f"[geometry]\ndim = 3\n\n[design]\ncontrol_points = [{m1}, {m2}]\n")
    return directory
