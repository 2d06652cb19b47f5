"""Animation of the mechanism over the cycle, with the trajectories of its joint points."""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import numpy as np


def animate(kin: Any, path: str | Path, frames: int = 24, fps: int = 8) -> list[Path]:
    """Write a GIF of the cycle to ``path`` (and an MP4 beside it when ffmpeg is on the PATH);
    returns the files written.  ``frames`` samples, evenly over the result's angles."""
    from matplotlib.animation import FFMpegWriter, FuncAnimation, PillowWriter
    from matplotlib.figure import Figure

    mech = kin.mechanism
    pts = kin.points()
    pts = pts[0] if kin.variants else pts
    n = len(kin.angles)
    picks = np.linspace(0, n, min(frames, n), endpoint=False).astype(int)
    joint_pts = sorted({int(p) for pair in mech.pair_points for p in pair if p >= 0})
    links = []
    for i in range(1, mech.n_links_total):
        own = [p for p in joint_pts if mech.point_link[p] == i]
        if len(own) >= 2:
            centre = np.nanmean(pts[picks[0], own], axis=0)
            order = np.argsort(np.arctan2(*(pts[picks[0], own] - centre).T[::-1]))
            own = [own[j] for j in order] + ([own[order[0]]] if len(own) > 2 else [])
            links.append(own)
    fig = Figure(figsize=(4, 4), dpi=72)
    ax = fig.add_subplot()
    finite = pts[np.isfinite(pts).all(-1)]
    lo, hi = finite.min(0), finite.max(0)
    pad = 0.08 * float((hi - lo).max())
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    for p in joint_pts:
        if mech.point_link[p] != 0:
            ax.plot(pts[:, p, 0], pts[:, p, 1], lw=0.6, color="0.6")
    lines = [ax.plot([], [], "-o", lw=2, ms=3, color="tab:blue")[0] for _ in links]
    title = ax.set_title("")

    def frame(k: int) -> list[Any]:
        i = picks[k]
        for line, own in zip(lines, links, strict=True):
            line.set_data(pts[i, own, 0], pts[i, own, 1])
        title.set_text(f"{mech.name}: {np.degrees(kin.angles[i]) % 360:.0f}°")
        return [*lines, title]

    anim = FuncAnimation(fig, frame, frames=len(picks), blit=False)
    path = Path(path)
    anim.save(path, writer=PillowWriter(fps=fps))
    written = [path]
    if shutil.which("ffmpeg"):
        mp4 = path.with_suffix(".mp4")
        anim.save(mp4, writer=FFMpegWriter(fps=fps))
        written.append(mp4)
    return written
