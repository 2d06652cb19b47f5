"""The figures of a report are fine enough to print: PNG at 200 dpi or more, shown in the page at the size
matplotlib laid them out for."""

from __future__ import annotations

import base64
import re

import pytest

pytest.importorskip("matplotlib")


def test_the_report_figures_are_written_at_print_resolution(report):
    from PIL import Image

    out = report("four-bar")  # 36 steps, no animation
    with Image.open(out / "figures" / "velocity_plan.png") as im:
        dpi = im.info["dpi"][0]
        pixels = im.size[0]
    assert dpi >= 199.5
    # the SVG of the same figure states its size in points: the PNG holds dpi / 72 pixels per point
    svg = (out / "figures" / "velocity_plan.svg").read_text()
    points = float(re.search(r'<svg[^>]* width="([0-9.]+)pt"', svg).group(1))
    assert pixels == pytest.approx(points / 72 * dpi, abs=2)
    # the page shows it as wide as at 100 dpi
    page = (out / "report.html").read_text()
    data = base64.b64encode((out / "figures" / "velocity_plan.png").read_bytes()).decode()
    shown = re.search(r"<img alt='[^']*' width='(\d+)' src='data:image/png;base64," + re.escape(data[:40]), page)
    assert shown and int(shown.group(1)) == pytest.approx(points / 72 * 100, abs=2)
