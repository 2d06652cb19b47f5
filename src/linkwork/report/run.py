"""What a run of the report collects: its sections, the captions of its figures, its language, the study it
reads and the jobs that draw the figures."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from linkwork.lang import t
from linkwork.report.beside import Beside
from linkwork.report.render import save

if TYPE_CHECKING:
    from linkwork.report.html import Section
    from linkwork.study import Study


class ReportRun:
    """What a run of :func:`linkwork.report.build.analyze` collects: its sections, the captions of its figures,
    its language, the study its sections read (:class:`linkwork.study.Study`), and the jobs that draw the
    figures (queued, then run beside the analyses or here: :class:`linkwork.report.beside.Beside`)."""

    def __init__(self, study: Study, folder: Path, progress: Callable[[str], None], lang: str, parallel: bool) -> None:
        self.study = study
        self.mech = study.mech
        self.folder = folder
        self.progress = progress
        self.lang = lang
        self.sizing: bool | None = None  # the "Sizing" section: asked, refused, or as the file says (None)
        self.sheets: dict[str, str] = {}  # the sheets' format and title block fields given over the file's
        self.sections: list[Section] = []
        self.figures: dict[str, Any] = {}  # those drawn in this process
        self.captions: dict[str, str] = {}
        self.jobs: list[Callable[[], object]] = []
        self.beside = Beside(parallel)
        (folder / "figures").mkdir(parents=True)

    def t(self, key: str, **values: Any) -> str:
        """The text ``key`` in the report's language."""
        return t(key, self.lang, **values)

    def figure(self, name: str, make: Callable[[], Any], caption: str) -> str:
        """Queue the figure ``make()`` draws, to be written as ``figures/NAME.svg`` and ``.png``; returns
        ``name`` for a section's figures."""
        self.captions[name] = self.t("caption", number=len(self.captions) + 1, text=caption)
        self.jobs.append(lambda: self._draw(name, make))
        return name

    def _draw(self, name: str, make: Callable[[], Any]) -> None:
        fig = make()
        save(fig, self.folder / "figures" / name)
        self.figures[name] = fig

    def run_beside(self) -> None:
        """Start the jobs queued so far in the second process."""
        jobs, self.jobs = self.jobs, []
        self.beside.start(jobs)

    def run_here(self) -> None:
        """Run the jobs queued since, in this process, then those of the second process it has not started, and
        wait for it."""
        jobs, self.jobs = self.jobs, []
        for job in jobs:
            job()
        self.beside.wait()
