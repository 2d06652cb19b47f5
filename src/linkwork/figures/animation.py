"""Animation of the mechanism over the cycle, drawn from its scheme's scene (:mod:`linkwork.scene`).

Every frame is the scheme of one sample: links, pivots, supports, slider blocks on their guides, tools,
labels, with the trajectories of the points, 720 pixels wide.  A GIF always; an MP4 beside it where
imageio-ffmpeg is installed (``pip install "linkwork[video]"``: its bundled ffmpeg, nothing is
downloaded when it runs).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.figures.scheme import draw_item, draw_paths, scale_bar, scheme_extent
from linkwork.figures.sheet import round_length, sheet
from linkwork.lang import t
from linkwork.scene.scheme import SchemeScene, scheme_scene
from linkwork.scene.style import TEXT

if TYPE_CHECKING:
    from linkwork.motion.kinematics import Kinematics

#: Width of the frames, pixels, and their resolution (pixels per inch).
WIDTH, DPI = 720, 100


def animate(kin: Kinematics, path: str | Path, frames: int = 48, fps: int = 16, lang: str = "en") -> list[Path]:
    """Write a GIF of the cycle to ``path`` (and an MP4 beside it where imageio-ffmpeg is installed);
    returns the files written.  ``frames`` samples, evenly over the result's angles, ``fps`` a second; the
    texts in ``lang`` (:mod:`linkwork.lang`)."""
    n = len(kin.angles)
    picks = np.linspace(0, n, min(frames, n), endpoint=False).astype(int)
    scene = scheme_scene(kin, at=[int(i) for i in picks])
    images = _frames(scene, [int(i) for i in picks], lang)
    path = Path(path)
    _gif(images, path, fps)
    written = [path]
    mp4 = _mp4(images, path.with_suffix(".mp4"), fps)
    if mp4 is not None:
        written.append(mp4)
    return written


def _frames(scene: SchemeScene, picks: list[int], lang: str) -> list[np.ndarray]:
    """The frames ``(H, W, 3)`` (uint8, even sizes) of the samples ``picks``."""
    film = Film(scene, picks, lang)
    return [film.frame(i) for i in picks]


class Film:
    """The animation's figure, :data:`WIDTH` pixels wide at 100 dpi, holding the scheme at every sample of
    ``picks``: its artists are made once and moved to the sample :meth:`show` is given; what does not move
    (the frame's symbols, the trajectories, the scale bar) is drawn once, under every frame."""

    def __init__(self, scene: SchemeScene, picks: list[int], lang: str = "en") -> None:
        from matplotlib.backends.backend_agg import FigureCanvasAgg

        self.scene, self.lang = scene, lang
        box = scheme_extent(scene, picks)
        bar = round_length(box[2] - box[0])
        box[1] -= 3.0 * scene.em
        sh = sheet(box, width=WIDTH / DPI - 0.3, height=WIDTH / DPI, least=WIDTH / DPI)
        self.fig, self.ax = sh.fig, sh.ax
        self.fig.set_dpi(DPI)
        self.canvas = FigureCanvasAgg(self.fig)
        draw_paths(sh, scene.paths)
        scale_bar(sh, (box[0] + scene.em, box[1] + 1.2 * scene.em), bar, scene.em, lang)
        self.items = [(it, draw_item(sh.ax, it, scene.placed(it, picks[0]))) for it in scene.items if it.kind != "path"]
        self.texts = [sh.ax.text(0, 0, lab.text, ha="center", va="center", fontsize=sh.font(scene.em),
                                 color=TEXT[lab.kind], zorder=5) for lab in scene.labels]  # fmt: skip
        self.title = sh.ax.set_title("", fontsize=11)
        self.where = [scene.placed(it) for it, _ in self.items]  # (A, K, 2) each: every sample at once
        self.moving = [a for it, a in self.items if it.link != 0] + self.texts + [self.title]
        for artist in self.moving:
            artist.set_animated(True)
        self.background: Any = None

    def show(self, i: int) -> None:
        """Move everything to sample ``i``."""
        scene = self.scene
        for (it, artist), xy in zip(self.items, self.where, strict=True):
            _move(artist, it.radius, xy[i])
        for lab, text in zip(scene.labels, self.texts, strict=True):
            text.set_position(tuple(lab.centre[i]))
            text.set_visible(bool(np.isfinite(lab.centre[i]).all()))
        self.title.set_text(t("animation.crank", self.lang, name=scene.name,
                              angle=f"{np.degrees(scene.angles[i]) % 360:.0f}"))  # fmt: skip

    def frame(self, i: int) -> np.ndarray:
        """The picture ``(H, W, 3)`` (uint8, even sizes) of sample ``i``: the moving artists drawn over the
        picture of what does not move."""
        self.show(i)
        if self.background is None:
            self.canvas.draw()
            self.background = self.canvas.copy_from_bbox(self.fig.bbox)
        else:
            self.canvas.restore_region(self.background)
        for artist in sorted(self.moving, key=lambda a: a.get_zorder()):
            self.ax.draw_artist(artist)
        rgb = np.asarray(self.canvas.buffer_rgba())[..., :3]
        return np.ascontiguousarray(rgb[: rgb.shape[0] // 2 * 2, : rgb.shape[1] // 2 * 2])


def _move(artist: Any, radius: float, xy: np.ndarray) -> None:
    """Put an item's artist at its vertices ``xy`` of the frame (hidden where they are not finite)."""
    ok = bool(np.isfinite(xy).all())
    artist.set_visible(ok)
    if not ok:
        return
    if radius:
        artist.set_center(tuple(xy[0]))
    elif hasattr(artist, "set_xy"):
        artist.set_xy(xy)
    else:
        artist.set_data(xy[:, 0], xy[:, 1])


def _gif(images: list[np.ndarray], path: Path, fps: int) -> None:
    """A looping GIF of ``images`` in one palette (that of the first frame, the drawing's few colours)."""
    from PIL import Image

    first = Image.fromarray(images[0]).quantize(colors=64, method=Image.Quantize.MEDIANCUT)
    rest = [Image.fromarray(im).quantize(palette=first, dither=Image.Dither.NONE) for im in images[1:]]
    first.save(path, save_all=True, append_images=rest, duration=round(1000 / fps), loop=0, optimize=False)


def _mp4(images: list[np.ndarray], path: Path, fps: int) -> Path | None:
    """An H.264 MP4 of ``images`` through imageio-ffmpeg's ffmpeg; None where imageio-ffmpeg is not installed."""
    try:
        import imageio_ffmpeg
    except ImportError:
        return None
    h, w = images[0].shape[:2]
    writer = imageio_ffmpeg.write_frames(str(path), (w, h), fps=fps, codec="libx264", pix_fmt_out="yuv420p",
                                         macro_block_size=1, ffmpeg_log_level="error", quality=7)  # fmt: skip
    writer.send(None)
    for im in images:
        writer.send(im)
    writer.close()
    return path
