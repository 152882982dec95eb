"""Where a command writes: one rule for every command, its path options and the jobs of a
recipe, checked before any work.

- The paths a command writes are the values of its ``path_options`` (every ``click.Path``
  that need not exist: ``-o``, ``--html``, ``levels --tiles``). A recipe confines each to its
  build folder (``recipe.Planner.output``, which applies ``problem`` below too).
- ``-o`` means the same everywhere: a file when the command writes one file (the files it
  names after it, such as ``strands --cutter``'s cut files, sit beside it), a folder when it
  writes several (``puzzle``, ``strands --laser-card``, ``build``; ``is_folder``). The folder
  a path goes into must exist (weave-cut makes only the output folder itself, never the
  folders above it), a folder output is not named like a file (``card.pdf``), a file output
  is no folder, and nothing is named like weave-cut's manifest (``problem``).
- No file weave-cut did not write is replaced without ``--force`` (``manifest.Ledger``): the
  files a run may replace (``may_replace``: its file outputs, and what a command says it
  writes beside them or into its folders, ``command.beside(values)``) are checked before any
  work, and every write is checked again as it happens.
"""

from __future__ import annotations

import contextlib
import os
from pathlib import Path

import click

from ..fileio import active_guard, protect, writing_into
from ..manifest import MANIFEST, Ledger
from ..text import nearest

FORCE_KEY = "weavecut.force"
NAME_MAX, PATH_MAX = 255, 4096  # bytes of a file name and of a path (Linux, macOS, NTFS)
FILE_LIKE = (".svg", ".pdf", ".dxf", ".png", ".obj", ".json", ".glb", ".html", ".htm", ".txt",
             ".zip", ".toml", ".dzi", ".jpg", ".jpeg")  # a folder named so is a mistake


class OutputPath(click.Path):
    """A written path that is a file, or a folder when the flag ``folder_with`` is given
    (``strands -o``: a PDF, a folder of cut sheets with ``--laser-card``)."""

    def __init__(self, folder_with: str) -> None:
        super().__init__(file_okay=True, dir_okay=True)
        self.folder_with = folder_with


def path_options(command: click.Command) -> list[click.Option]:
    """The options of ``command`` that name a file or folder it writes: every ``click.Path``
    that need not exist. A recipe confines each to its build folder (``recipe.Planner``), and
    the command checks and locks the folder of each (``writing``)."""
    return [p for p in command.params if isinstance(p, click.Option)
            and isinstance(p.type, click.Path) and not p.type.exists]


def is_folder(param: click.Parameter, values: dict) -> bool:
    """Whether path option ``param`` names a folder, with the command's ``values``."""
    flag = getattr(param.type, "folder_with", None)
    if flag is not None:
        try:
            return click.BOOL.convert(values.get(flag) or False, None, None)
        except click.BadParameter:  # a recipe's 'maybe': refused as the flag's value later
            return False
    return not param.type.file_okay


def written(command: click.Command, values: dict) -> list[tuple[click.Option, str]]:
    """(option, path) of every path ``command`` writes with ``values``."""
    out = []
    for p in path_options(command):
        value = values.get(p.name)
        out += [(p, v) for v in (value if isinstance(value, (tuple, list)) else [value])
                if v is not None]
    return out


def too_long(path) -> str | None:
    """Why ``path`` is too long for a file system, or None."""
    longest = max((len(os.fsencode(part)) for part in Path(path).parts), default=0)
    if longest > NAME_MAX or len(os.fsencode(os.path.abspath(path))) > PATH_MAX:
        return (f"too long for a file system: a name holds at most {NAME_MAX} bytes (this one "
                f"{longest}) and a path {PATH_MAX:,}")
    return None


def problem(path: str, folder: bool, parent_made: bool = False) -> str | None:
    """What is wrong with writing ``path`` (a folder if ``folder``), or None; ``parent_made``:
    the folder above it is made by the caller (a build's subfolders)."""
    path = str(path)
    if not path:
        return "an empty path names no file or folder"
    plain = os.path.normpath(path)
    name, parent = os.path.basename(plain), os.path.dirname(plain) or "."
    if name == MANIFEST:
        return f"{path!r} is weave-cut's manifest of the folder; choose another name"
    if too_long(path):
        return too_long(path)
    if not parent_made and os.path.lexists(parent) and not os.path.isdir(parent):
        return f"{parent!r} is a file, not a folder"
    if not parent_made and not os.path.isdir(parent):
        return (f"the folder {parent!r} does not exist; create it first (weave-cut makes the "
                "output, not the folders above it)")
    suffix = Path(plain).suffix
    if folder and os.path.lexists(path) and not os.path.isdir(path):
        return (f"{path!r} is a file, but here -o is the folder the files go into; name a "
                "folder")
    if folder and not os.path.isdir(path) and suffix.lower() in FILE_LIKE:
        return (f"{path!r} is named like a file, but here it is the folder the files go "
                f"into; name it without {suffix!r}, like {str(Path(plain).with_suffix(''))!r}")
    if not folder and (os.path.isdir(path) or path.endswith(("/", os.sep))):
        return (f"{path!r} is a folder, but here it names the one file written; give a file "
                "name")
    return None


def roots(command: click.Command, values: dict) -> list[str]:
    """The output folders of a run: a folder option's folder, a file option's folder."""
    return [path if is_folder(p, values) else os.path.dirname(os.path.abspath(path))
            for p, path in written(command, values)]


def may_replace(command: click.Command, values: dict) -> list[Path]:
    """The existing files a run with ``values`` may replace: its file outputs, and those the
    command says it writes beside them or into its folders (``command.beside(values)``)."""
    found = [Path(path) for p, path in written(command, values) if not is_folder(p, values)
             and os.path.lexists(path) and (os.path.islink(path) or not os.path.isdir(path))]
    beside = getattr(command, "beside", None)
    found += beside(values) if beside is not None else []
    return sorted(set(found))


def _keep_force(ctx: click.Context, param: click.Parameter, value: bool) -> bool:
    if value:  # a build's --force holds for its jobs, whose own flag stays unset
        ctx.meta[FORCE_KEY] = True
    return value


force_option = click.option(
    "--force", is_flag=True, expose_value=False, callback=_keep_force,
    help="Replace existing files weave-cut did not write (its own files, unchanged since, "
         "are replaced without it).")


def forced() -> bool:
    """Whether the running command (or the build running it) was given --force."""
    ctx = click.get_current_context(silent=True)
    return bool(ctx and ctx.meta.get(FORCE_KEY))


@contextlib.contextmanager
def writing(ctx: click.Context | None):
    """Check where the command of ``ctx`` writes, before any work (a bad path is a usage
    error naming its option; a file weave-cut may not replace is refused with its name), then
    hold the rule and the folders' locks while the command runs (``fileio.writing_into``)."""
    if ctx is None:
        with writing_into(()):
            yield
        return
    command, values = ctx.command, ctx.params
    made = {os.path.abspath(path) for p, path in written(command, values) if is_folder(p, values)}
    named: dict[str, click.Parameter] = {}
    for p, path in written(command, values):  # (a page into the -o folder: made by then)
        inside = os.path.dirname(os.path.abspath(path)) in made
        message = problem(path, is_folder(p, values), parent_made=inside)
        first = named.setdefault(os.path.abspath(path), p)
        if message is None and first is not p:
            message = f"{first.opts[0]} writes {path!r} too; give each output its own name"
        if message:
            raise click.BadParameter(message, ctx=ctx, param=p)
    folders = roots(command, values)
    # a file -o's run lists what it wrote by that -o, and a rerun removes what it no longer
    # writes (a build does so per job, by the job's output: ``recipe.Planner.remember``)
    outputs = [] if command.name == "build" else [path for p, path in written(command, values)
                                                  if "-o" in p.opts]
    ledger = Ledger(folders, forced(), outputs)
    with writing_into(folders, guard=ledger):
        guard = active_guard()
        if guard is ledger:
            ledger.open()
        for argument in (p for p in command.params if isinstance(p, click.Argument)):
            value = values.get(argument.name)
            if isinstance(value, str) and os.path.isfile(value):
                protect(value)  # an input is never an output (checked below)
        for path in may_replace(command, values):
            guard.check(path)
        yield


def check_suffix(output: str, allowed, param_hint: str = "'-o'") -> str:
    """The suffix of the file ``output`` ('.svg', lower case) if it is one of ``allowed``
    (with dots), else a usage error naming the formats (and the one probably meant)."""
    allowed = list(allowed)
    suffix = Path(output).suffix
    if suffix.lower() in allowed:
        return suffix.lower()
    formats = ", ".join(allowed[:-1]) + f" or {allowed[-1]}" if len(allowed) > 1 else allowed[0]
    what = (f"unknown format {suffix!r}{nearest(suffix.lower(), allowed)}" if suffix else
            f"{output!r} has no suffix to say its format")
    raise click.BadParameter(f"{what}; use {formats}", param_hint=param_hint)
