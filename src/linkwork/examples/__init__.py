"""The bundled example mechanisms."""

from __future__ import annotations

from importlib import resources
from pathlib import Path

from linkwork.did_you_mean import suggest
from linkwork.errors import Problem, SpecError
from linkwork.limits import QUOTE_PATH, excerpt, quote
from linkwork.spec.reader import load, loads
from linkwork.spec.schema import Spec


def names() -> list[str]:
    """Names of the bundled examples."""
    return sorted(p.name[:-5] for p in resources.files(__name__).iterdir() if p.name.endswith(".yaml"))


def text(name: str) -> str:
    """The YAML text of a bundled example."""
    if name not in names():
        raise SpecError(
            [
                Problem(
                    "",
                    f"no bundled example {quote(name)}{suggest(name, names())}; the examples are: {', '.join(names())}",
                )
            ]
        )
    return (resources.files(__name__) / f"{name}.yaml").read_text(encoding="utf-8")


def load_example(name: str) -> Spec:
    """The validated spec of a bundled example (``linkwork.example``).

    Parameters
    ----------
    name : str
        The example's name, as ``linkwork examples`` lists them (``"four-bar"``, ``"double-cut-shears"``).

    Returns
    -------
    Spec
        The example's description, validated.

    Raises
    ------
    SpecError
        For a name that is no bundled example (the message lists them).

    Examples
    --------
    >>> import linkwork as lw
    >>> lw.example("four-bar").name
    'four-bar'
    """
    return loads(text(name), file=f"{name}.yaml")


def resolve(file_or_example: str | Path) -> Spec:
    """Load and validate a mechanism file, or a bundled example by name (``linkwork.load``).

    Parameters
    ----------
    file_or_example : str or Path
        A mechanism file (``.yaml`` or ``.yml``) or the name of a bundled example.

    Returns
    -------
    Spec
        The description, validated, in SI units whatever the file's units.

    Raises
    ------
    SpecError
        Listing every problem with ``file:line``, the element and what was expected.

    Examples
    --------
    >>> import linkwork as lw
    >>> spec = lw.load("four-bar")
    >>> list(spec.links)
    ['crank', 'coupler', 'rocker']
    """
    path = Path(file_or_example)
    file_or_example = str(file_or_example)
    try:
        exists = path.exists()
    except OSError as exc:  # a name too long, say
        why = f"cannot read the file: {exc.strerror}"
        raise SpecError([Problem("", why, excerpt(file_or_example, QUOTE_PATH))]) from None
    if exists or path.suffix in (".yaml", ".yml") or "/" in file_or_example:
        if not exists:
            raise SpecError([Problem("", "no such file", excerpt(file_or_example, QUOTE_PATH))])
        return load(path)
    if file_or_example in names():
        return load_example(file_or_example)
    raise SpecError(
        [
            Problem(
                "",
                f"no such file or bundled example {quote(file_or_example)}"
                f"{suggest(file_or_example, names())}; `linkwork examples` lists the examples",
            )
        ]
    )
