"""Animation of the mechanism over the cycle, drawn from its scheme's scene (:mod:`linkwork.scene`).

Every frame is the scheme of one sample: links, pivots, supports, slider blocks on their guides, tools,
labels, with the trajectories of the points, 720 pixels wide.  A GIF always; an MP4 beside it where
imageio-ffmpeg is installed (``pip install "linkwork[video]"``: its bundled ffmpeg, nothing is
downloaded when it runs).

What does not move is drawn once; the labels, which only move, are drawn once each too, as pictures
(:class:`Sprite`) laid over every frame where the scene puts them.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from linkwork.figures.scheme import draw_item, draw_paths, scale_bar
from linkwork.figures.sheet import mathtext, round_length, sheet
from linkwork.lang import t
from linkwork.scene.scheme import SchemeScene, scheme_scene
from linkwork.scene.style import TEXT
from linkwork.units import turn_deg

if TYPE_CHECKING:
    from matplotlib.text import Text

    from linkwork.motion.kinematic_analysis import Kinematics

#: Width of the frames, pixels, and their resolution (pixels per inch).
WIDTH, DPI = 720, 100


def animate(kin: Kinematics, path: str | Path, frames: int = 48, fps: int = 16, lang: str = "en") -> list[Path]:
    """Write a GIF of the cycle to ``path`` (and an MP4 beside it where imageio-ffmpeg is installed);
    returns the files written.  ``frames`` samples, evenly over the result's angles, ``fps`` a second; the
    texts in ``lang`` (:mod:`linkwork.lang`).

    Parameters
    ----------
    kin : Kinematics
        A kinematics result (:func:`linkwork.kinematics`).
    path : str or Path
        The GIF to write.
    frames : int, default 48
        Frames, evenly over the result's angles.
    fps : int, default 16
        Frames a second.
    lang : str, default "en"
        The language of the texts, ``"en"`` or ``"ru"`` (:mod:`linkwork.lang`).
    """
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
        box = scene.extent(picks)
        bar = round_length(box[2] - box[0])
        box[1] -= 3.0 * scene.em
        sh = sheet(box, width=WIDTH / DPI - 0.3, height=WIDTH / DPI, least=WIDTH / DPI)
        self.fig, self.ax = sh.fig, sh.ax
        self.fig.set_dpi(DPI)
        self.canvas = FigureCanvasAgg(self.fig)
        draw_paths(sh, scene.paths)
        scale_bar(sh, (box[0] + scene.em, box[1] + 1.2 * scene.em), bar, scene.em, lang)
        self.items = [(it, draw_item(sh.ax, it, scene.placed(it, picks[0]))) for it in scene.items if it.kind != "path"]
        self.texts = [
            sh.ax.text(
                0,
                0,
                mathtext(lab.text),
                ha="center",
                va="center",
                fontsize=sh.font(scene.em),
                color=TEXT[lab.kind],
                zorder=5,
            )
            for lab in scene.labels
        ]
        self.title, self.tail = self._title()
        self.where = [scene.placed(it) for it, _ in self.items]  # (A, K, 2) each: every sample at once
        moving = [a for it, a in self.items if it.link != 0] + [self.title]
        self.moving = sorted(moving, key=lambda a: a.get_zorder())
        for artist in self.moving + self.texts:
            artist.set_animated(True)
        self.background: Any = None
        self.sprites: list[Sprite] = []
        self.pixels, self.centres = self._whole_pixels()

    def _whole_pixels(self) -> tuple[np.ndarray, np.ndarray]:
        """The labels' centres at every sample ``(A, L, 2)`` moved to the nearest whole pixel: in pixels (column,
        row from the bottom) and in the drawing's units.  A text is drawn alike at every whole pixel (its glyphs
        are placed to a 64th of a pixel), so the picture of a label drawn once is the label drawn at any."""
        labels = self.scene.labels
        centres = np.stack([lab.centre for lab in labels], 1) if labels else np.zeros((len(self.scene.angles), 0, 2))
        pixels = np.round(self.ax.transData.transform(centres.reshape(-1, 2))).reshape(centres.shape)
        return pixels, self.ax.transData.inverted().transform(pixels.reshape(-1, 2)).reshape(centres.shape)

    def show(self, i: int) -> None:
        """Move everything to sample ``i``."""
        scene = self.scene
        for (it, artist), xy in zip(self.items, self.where, strict=True):
            _move(artist, it.radius, xy[i])
        for j, text in enumerate(self.texts):
            text.set_position(tuple(self.centres[i, j]))
            text.set_visible(bool(np.isfinite(self.centres[i, j]).all()))
        self.title.set_text(f"{turn_deg(scene.angles[i], 0):.0f}{self.tail}")

    def _title(self) -> tuple[Text, str]:
        """The title, centred over the drawing: its words up to the crank angle are drawn once, with what does
        not move; returns the text of the angle after them, moved with every sample, and what follows the
        angle in the title."""
        from matplotlib.transforms import offset_copy

        head, _, tail = t("animation.crank", self.lang, name=self.scene.name, angle="\0").partition("\0")
        at = offset_copy(self.ax.transAxes, fig=self.fig, y=6.0, units="points")  # as a title's pad
        words = self.ax.text(0.5, 1.0, head, ha="left", va="baseline", fontsize=11, transform=at)
        angle = self.ax.text(0.5, 1.0, "", ha="left", va="baseline", fontsize=11, transform=at)
        renderer, prop = self.canvas.get_renderer(), words.get_fontproperties()

        def width(text: str) -> float:  # with its trailing spaces: measured up to a bar after it
            return float(
                renderer.get_text_width_height_descent(text + "|", prop, False)[0]
                - renderer.get_text_width_height_descent("|", prop, False)[0]
            )

        first, rest = width(head), width(f"360{tail}")
        x0 = 0.5 - (first + rest) / 2 / self.ax.bbox.width
        words.set_x(x0)
        angle.set_x(x0 + first / self.ax.bbox.width)
        return angle, tail

    def frame(self, i: int) -> np.ndarray:
        """The picture ``(H, W, 3)`` (uint8, even sizes) of sample ``i``: the moving artists drawn over the
        picture of what does not move, the labels' pictures over them (as the labels are drawn on top)."""
        from PIL import Image

        if self.background is None:
            self.canvas.draw()
            self.background = self.canvas.copy_from_bbox(self.fig.bbox)
            self.sprites = [self._sprite(text) for text in self.texts]
        self.show(i)
        self.canvas.restore_region(self.background)
        for artist in self.moving:
            self.ax.draw_artist(artist)
        rgba = np.asarray(self.canvas.buffer_rgba())
        for j, sprite in enumerate(self.sprites):
            x, y = self.pixels[i, j]
            if np.isfinite(x) and np.isfinite(y):
                sprite.paste(rgba, (int(x), rgba.shape[0] - int(y)))
        h, w = rgba.shape[0] // 2 * 2, rgba.shape[1] // 2 * 2
        return np.asarray(
            Image.frombuffer("RGBA", rgba.shape[1::-1], rgba, "raw", "RGBA", 0, 1).crop((0, 0, w, h)).convert("RGB")
        )

    def _sprite(self, text: Text) -> Sprite:
        """The picture of ``text``, drawn alone onto the cleared canvas at the whole pixel nearest the middle of
        the figure."""
        renderer = self.canvas.get_renderer()
        renderer.clear()
        x, y = np.round(np.array(self.canvas.get_width_height()) / 2)
        text.set_position(tuple(self.ax.transData.inverted().transform((x, y))))
        text.set_visible(True)
        text.draw(renderer)
        pixels = np.asarray(renderer.buffer_rgba())
        return Sprite.cut(pixels, text.get_window_extent(renderer), (int(x), pixels.shape[0] - int(y)))


@dataclass(frozen=True)
class Sprite:
    """A text drawn once, to be laid over frames: its pixels' coverage ``alpha`` ``(h, w, 1)`` (0 to 1), its
    colour times the coverage ``paint`` ``(h, w, 3)``, and where its top left pixel is from the pixel of its
    anchor (columns, rows)."""

    alpha: np.ndarray
    paint: np.ndarray
    offset: tuple[int, int]

    @classmethod
    def cut(cls, pixels: np.ndarray, box: Any, anchor: tuple[int, int]) -> Sprite:
        """The sprite of the text in ``box`` (display units, y up) of ``pixels`` ``(H, W, 4)`` (a text drawn on a
        cleared canvas: its colour and coverage, non-premultiplied), anchored at ``anchor`` (column, row)."""
        height, width = pixels.shape[:2]
        c0, c1 = max(int(np.floor(box.x0)) - 1, 0), min(int(np.ceil(box.x1)) + 1, width)
        r0, r1 = max(height - int(np.ceil(box.y1)) - 1, 0), min(height - int(np.floor(box.y0)) + 1, height)
        part = pixels[r0:r1, c0:c1].astype(np.float32)
        alpha = part[..., 3:] / 255.0
        return cls(alpha, part[..., :3] * alpha, (c0 - anchor[0], r0 - anchor[1]))

    def paste(self, image: np.ndarray, anchor: tuple[int, int]) -> None:
        """Lay the text over ``image`` ``(H, W, 4)`` (uint8, in place) with its anchor at ``anchor`` (column,
        row); what falls outside the image is left out."""
        h, w = self.alpha.shape[:2]
        c0, r0 = anchor[0] + self.offset[0], anchor[1] + self.offset[1]
        rows = slice(max(r0, 0), min(r0 + h, image.shape[0]))
        cols = slice(max(c0, 0), min(c0 + w, image.shape[1]))
        if rows.start >= rows.stop or cols.start >= cols.stop:
            return
        mine = (slice(rows.start - r0, rows.stop - r0), slice(cols.start - c0, cols.stop - c0))
        under = image[rows, cols, :3]
        under[...] = under * (1.0 - self.alpha[mine]) + self.paint[mine] + 0.5


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
    """A looping GIF of ``images`` in one palette (that of the first frame, the drawing's few colours), every
    frame mapped onto it alike (PIL's mapping onto a given palette is not the median cut's own: the first
    frame mapped by the median cut would have another white than the others)."""
    from PIL import Image

    palette = Image.fromarray(images[0]).quantize(colors=64, method=Image.Quantize.MEDIANCUT)
    first, *rest = [Image.fromarray(im).quantize(palette=palette, dither=Image.Dither.NONE) for im in images]
    first.save(path, save_all=True, append_images=rest, duration=round(1000 / fps), loop=0, optimize=False)


def _mp4(images: list[np.ndarray], path: Path, fps: int) -> Path | None:
    """An H.264 MP4 of ``images`` through imageio-ffmpeg's ffmpeg; None where imageio-ffmpeg is not installed."""
    try:
        import imageio_ffmpeg
    except ImportError:
        return None
    h, w = images[0].shape[:2]
    writer = imageio_ffmpeg.write_frames(
        str(path),
        (w, h),
        fps=fps,
        codec="libx264",
        pix_fmt_out="yuv420p",
        macro_block_size=1,
        ffmpeg_log_level="error",
        quality=7,
    )
    writer.send(None)
    for im in images:
        writer.send(im)
    writer.close()
    return path
