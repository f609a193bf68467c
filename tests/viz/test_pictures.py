"""Pictures of viz/render_run.py on synthetic run directories (synthetic_runs.py): each test
renders a run, keeps the matplotlib figures that render_run saves, and looks at their pixels
and texts. Run by ctest (tests/viz/CMakeLists.txt) as
    viz/run_headless.sh /usr/bin/python3 -m pytest tests/viz
with viz/ on PYTHONPATH."""

import os
import re

import numpy as np
import pytest

import render_run
import synthetic_runs
from frictopt_vtu import contact_facets, format_number, format_quantity, read_grid

WHITE = np.array([255, 255, 255])


@pytest.fixture
def figures(monkeypatch):
    """{picture file name: figure} of everything render_run saves during the test."""
    kept = {}
    original = render_run.save

    def keep(fig, path, run=None):
        written = original(fig, path, run)
        fig.canvas.draw()  # the pixels and text positions of the saved layout
        kept[path.rsplit("/", 1)[-1]] = fig
        return written

    monkeypatch.setattr(render_run, "save", keep)
    return kept


def draw(run_dir, *pictures):
    """Draws the named pictures (render_run's picture_* functions) of a run directory."""
    run = render_run.Run(run_dir)
    out_dir = f"{run_dir}/pictures"
    os.makedirs(out_dir, exist_ok=True)
    return [getattr(render_run, f"picture_{name}")(run, out_dir) for name in pictures]


def pixels(fig):
    return np.asarray(fig.canvas.buffer_rgba())[:, :, :3].astype(int)


def pixel_at(fig, ax, x, y, image=None):
    """RGB of the figure's pixel at data point (x, y) of axes `ax` (`image`: pixels(fig))."""
    image = pixels(fig) if image is None else image
    column, row = ax.transData.transform((x, y))
    return image[image.shape[0] - 1 - int(round(row)), int(round(column))]


def panels(fig, title_part):
    return [ax for ax in fig.axes if title_part in ax.get_title()]


def is_background(rgb):
    return bool(np.all(np.abs(np.asarray(rgb) - WHITE) <= 3))


def texts_outside(fig):
    """The titles and axis labels of a drawn figure that do not lie wholly inside it."""
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    texts = [getattr(fig, "_suptitle", None), getattr(fig, "_supxlabel", None)]
    for ax in fig.axes:
        texts += [ax.title, ax._left_title, ax._right_title]
        if ax.axison:
            texts += [ax.xaxis.label, ax.yaxis.label]
    outside = []
    for text in texts:
        if text is None or not text.get_visible() or not text.get_text():
            continue
        extent = text.get_window_extent(renderer)
        if (extent.x0 < box.x0 - 0.5 or extent.x1 > box.x1 + 0.5 or extent.y0 < box.y0 - 0.5
                or extent.y1 > box.y1 + 0.5):
            outside.append(text.get_text())
    return outside


def test_slot_between_two_contact_faces_stays_background(tmp_path, figures):
    run = synthetic_runs.write_solve_run(str(tmp_path / "bracket"), synthetic_runs.bracket())
    draw(run, "contact_3d")
    fig = figures["contact_maps.png"]
    for title in ("contact pressure", "nodes:"):
        (ax,) = panels(fig, title)
        # The slot 1 < x1 < 2 under the bridge, between the rows of nodes (x2 = 0, 0.5, 1)
        # whose traction arrows may reach into it.
        for y in (0.2, 0.3, 0.7, 0.8):
            for x in (1.1, 1.5, 1.9):
                assert is_background(pixel_at(fig, ax, x, y)), (title, x, y)
        for x in (0.25, 0.75, 2.25, 2.75):  # the feet are painted
            assert not is_background(pixel_at(fig, ax, x, 0.3)), (title, x)


def test_unstructured_contact_surface_has_no_holes(tmp_path, figures):
    body = synthetic_runs.unstructured_pad()
    run = synthetic_runs.write_solve_run(str(tmp_path / "pad"), body)
    draw(run, "contact_3d")
    fig = figures["contact_maps.png"]
    grid = read_grid(f"{run}/synthetic.vtu")
    points = body[0]
    facets = contact_facets(grid)
    assert len(facets) == 49
    image = pixels(fig)
    for title in ("contact pressure", "nodes:"):
        (ax,) = panels(fig, title)
        holes = []
        for face in facets:
            corners = points[face, :2]
            centre = corners.mean(axis=0)
            # The centre and points between it and each corner (inside the convex facet).
            for point in [centre] + [centre + 0.85 * (c - centre) for c in corners]:
                if is_background(pixel_at(fig, ax, *point, image=image)):
                    holes.append(tuple(point))
        assert not holes, (title, holes[:5])


def test_titles_lie_inside_every_picture(tmp_path, figures):
    long_name = "a-two-foot-bracket-of-a-user-with-a-long-descriptive-case-name"
    run = synthetic_runs.write_optimize_run(
        str(tmp_path / "long"), synthetic_runs.bracket, ["serious"] * 3 + ["null"] * 2,
        case_path=f"/home/user/{long_name}/case.toml")
    render_run.render(run)
    solve = synthetic_runs.write_solve_run(str(tmp_path / "solve"), synthetic_runs.bracket(),
                                           case_path=f"/home/user/{long_name}/case.toml")
    render_run.render(solve)
    assert {"contact_maps.png", "history.png", "shape.png", "body_von_mises.png"} <= set(figures)
    for name, fig in figures.items():
        assert texts_outside(fig) == [], name


def test_cut_at_the_middle_plane_reads_zero(tmp_path, figures):
    run = synthetic_runs.write_solve_run(str(tmp_path / "centred"), synthetic_runs.centred_block())
    draw(run, "body_3d")
    title = figures["body_von_mises.png"]._suptitle.get_text()
    assert "cut at x2 = 0 m" in title, title


def test_number_format_has_no_signed_zero():
    assert format_number(-0.0) == "0"
    assert format_number(0.0) == "0"
    assert format_number(-1e-19, resolution=1e-12) == "0"
    assert format_number(-1.5e-3) == "-0.0015"
    assert format_number(2.0e10, 4) == "2e+10"
    assert format_quantity(-0.0, "m") == "0 m"
    assert format_quantity(1.234e9, "N²", 4) == "1.234e+09 N²"
    assert format_quantity(3.0) == "3"


STEPS = (["serious"] * 5 + ["null"] * 4 + ["line_search_null"] * 3 + ["serious"]
         + ["line_search_serious"] * 2 + ["null"])


def legend_counts(fig):
    """{"serious": n, "null": n} summed over the legend entries of the history."""
    (ax,) = [ax for ax in fig.axes if ax.get_legend() is not None]
    counts = {"serious": 0, "null": 0}
    for text in ax.get_legend().get_texts():
        label = text.get_text()
        match = re.search(r"(\d+)\)?$", label)
        for kind in counts:
            if match and label.startswith(kind):
                counts[kind] += int(match.group(1))
    return counts


def test_history_legend_counts_the_steps_of_the_summary(tmp_path, figures):
    run = synthetic_runs.write_optimize_run(str(tmp_path / "steps"), synthetic_runs.bracket,
                                            STEPS)
    draw(run, "history")
    summary = render_run.read_json(f"{run}/summary.json")
    assert (summary["serious_steps"], summary["null_steps"]) == (8, 8)
    assert legend_counts(figures["history.png"]) == {"serious": 8, "null": 8}


def test_history_says_which_iterations_it_does_not_record(tmp_path, figures):
    run = synthetic_runs.write_optimize_run(str(tmp_path / "confirmed"), synthetic_runs.bracket,
                                            STEPS, confirmation_iterations=12)
    draw(run, "history")
    fig = figures["history.png"]
    assert legend_counts(fig) == {"serious": 8, "null": 8}
    (ax,) = [ax for ax in fig.axes if ax.get_legend() is not None]
    title = ax.get_title().replace("\n", " ")
    assert "28 iterations, 8 serious + 8 null steps" in title, title
    assert "records iterations 1–16 (8 serious, 8 null steps); the other 12 iterations" in title


def test_cost_unit_is_on_the_axis_and_in_the_titles(tmp_path, figures):
    run = synthetic_runs.write_optimize_run(str(tmp_path / "unit"), synthetic_runs.bracket,
                                            ["serious", "null"], cost_unit="N²")
    draw(run, "history", "contact_3d")
    history = figures["history.png"]
    (ax,) = [ax for ax in history.axes if ax.get_legend() is not None]
    assert "[N²]" in ax.get_ylabel()
    assert re.search(r"Θ 4e\+09 N² → [0-9.e+]+ N²", ax.get_title()), ax.get_title()
    body_titles = [ax.get_title() for ax in figures["contact_maps.png"].axes]
    assert any(re.search(r"Θ = 4e\+09 N²", t) for t in body_titles), body_titles


def test_three_dimensional_run_gets_the_lift_and_the_body_from_below(tmp_path, figures):
    run = synthetic_runs.write_optimize_run(str(tmp_path / "lift"), synthetic_runs.unstructured_pad,
                                            ["serious", "serious"], control_points=(3, 2))
    written = render_run.render(run)
    assert f"{run}/pictures/shape.png" in written
    fig = figures["shape.png"]
    lift_axes = [ax for ax in fig.axes if ax.name == "3d"]
    assert len(lift_axes) == 2  # initial and final design
    title = fig._suptitle.get_text()
    assert "3 × 2 control points" in title, title
    # The synthetic pad's contact nodes lie at x3 = α (a flat lift): on F_α.
    assert re.search(r"off F_α by at most 0 mm", title.replace("\n", " ")), title
    # Below the lift panels, the bodies seen from below: not blank.
    images = [ax for ax in fig.axes if ax.get_images()]
    assert len(images) == 2
    for ax in images:
        image = ax.get_images()[0].get_array()
        assert np.ptp(np.asarray(image, dtype=float)) > 50


def test_render_vtu_contact_map_keeps_the_slot_empty(tmp_path, monkeypatch):
    """viz/render_vtu.py draws its 3D contact maps on the same contact facets."""
    import matplotlib.pyplot as plt
    import render_vtu
    run = synthetic_runs.write_solve_run(str(tmp_path / "bracket"), synthetic_runs.bracket())
    kept = []
    monkeypatch.setattr(plt, "close", kept.append)
    render_vtu.render_contact(read_grid(f"{run}/synthetic.vtu"), str(tmp_path / "map.png"))
    (fig,) = [f for f in kept if hasattr(f, "canvas")]
    fig.canvas.draw()
    image = pixels(fig)
    for title in ("contact_pressure", "contact_status"):
        (ax,) = panels(fig, title)
        for x in (1.1, 1.5, 1.9):
            assert is_background(pixel_at(fig, ax, x, 0.3, image)), (title, x)
        assert not is_background(pixel_at(fig, ax, 0.6, 0.3, image)), title


def test_a_design_that_carries_less_load_is_named_in_every_title(tmp_path, figures):
    run = synthetic_runs.write_optimize_run(str(tmp_path / "unloaded"), synthetic_runs.bracket,
                                            ["serious", "null"], loads=(11240.0, 6560.0))
    draw(run, "history", "contact_3d", "body_3d")
    expected = "total normal force 1.124e+04 → 6560 N (-42 %)"
    for name, fig in figures.items():
        titles = [getattr(fig, "_suptitle", None)] + [ax.title for ax in fig.axes]
        text = " ".join(t.get_text().replace("\n", " ") for t in titles if t is not None)
        assert "warning: the final design carries another load" in text, (name, text)
        assert expected in text, (name, text)
        assert not texts_outside(fig), name


def test_no_load_warning_when_the_load_is_kept(tmp_path, figures):
    run = synthetic_runs.write_optimize_run(str(tmp_path / "kept"), synthetic_runs.bracket,
                                            ["serious", "null"], loads=(11240.0, 11000.0))
    draw(run, "history", "contact_3d")
    for fig in figures.values():
        titles = [getattr(fig, "_suptitle", None)] + [ax.title for ax in fig.axes]
        assert not any(t is not None and "warning" in t.get_text() for t in titles)
