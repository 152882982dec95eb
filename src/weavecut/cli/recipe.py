"""A recipe's jobs, checked before the first runs, and how one runs (``weave-cut build``).

A recipe is TOML with one ``[[job]]`` table per output::

    [[job]]
    command = "weave"                 # any weave-cut command but build
    input = "square-grid"             # its INPUT: a built-in name, or a file beside the recipe
    output = "square-weave.svg"       # -o, inside the build folder
    levels = 2                        # every other key is an option of that command
    outline-level = 1                 # (dashes or underscores; true for a flag)

A recipe is untrusted input. Every job is checked before the first one runs, and the first
problem is one line naming the recipe, the job and the key:

- the command (any but ``build``, ``serve`` and ``worker``) and its keys (a misspelt key gets
  the nearest one), and every value through the
  option's own type; values reach the command as typed values, never as argv, so no value can
  become an option;
- the input: a built-in name, or a file in the recipe's folder (and below) or in a folder given
  with ``--allow-read``; preset files (``palette = "my.toml"``) likewise;
- every path a job writes (``output``, and every other option that names a file or folder
  written, such as ``levels``'s ``tiles``: ``outputs.path_options``): a relative path inside
  ``-o DIR`` (no ``..``, not absolute, no ``~``, not through a symlink out of it), checked by
  ``Planner.output``; never an input, a device or a FIFO, and never an existing file that
  weave-cut did not write there (recorded with its hash in ``.weave-cut-manifest.json``) unless
  ``--force`` (``manifest.Ledger``, the rule of every command; a recipe cannot say
  ``force``). That holds for every file a job may write: its file outputs, the files its
  command says it writes beside them or into its folder outputs (``outputs.may_replace``:
  ``strands --cutter``'s cut files, ``puzzle``'s folder) and the files the job wrote last
  time. A folder output is not named like a file, and no output is named like the manifest
  (``outputs.problem``, as on the command line; a build makes its own subfolders). A job
  that prints (``stats``) writes what it prints as ``.txt`` (or ``.json`` with
  ``json = true``), never as a page a browser renders.

The manifest records every file each job wrote, by the job's output; a file a job wrote last
time and not this time (a cut file of a page the model no longer has) is removed.

After the last job, ``DIR/index.html`` shows every output (the kit page, ``weavecut.kitpage``).
"""

from __future__ import annotations

import contextlib
import io
import os
import shlex
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import click

from .. import inputs, presets
from ..errors import WeaveCutError
from ..fileio import make_folder, recording, write_atomic
from ..manifest import MANIFEST, Ledger, file_hash, read_manifest, record_manifest
from ..schema import SchemaError, nearest
from .common import option_key, say
from .outputs import is_folder, may_replace, path_options, problem, too_long

if TYPE_CHECKING:  # the kit page (and shapely) load when a job runs, not for --help
    from .. import kitpage

PAGE = "index.html"  # the kit page of the build
# commands that are no job of a recipe: one builds recipes, the others serve (a web app, a
# queue's worker) until stopped
NOT_IN_RECIPES = frozenset({"build", "serve", "worker"})
PRESET_OPTIONS = {"palette": "palettes", "material": "materials", "laser": "laser"}


class RecipeError(SchemaError):
    """A recipe is missing or malformed, names an unknown command or key, or reads or writes
    outside its folders."""


@dataclass(frozen=True)
class Job:
    """One checked job: the command, its typed values by parameter name, and where it writes
    (``output`` absolute: the -o path, else the first other path it writes; ``prints``: the
    output is what the command prints)."""

    where: str  # the recipe and the label
    label: str  # "job 2 (weave)"
    command: click.Command
    values: dict
    output: Path | None
    shown: str | None  # the output as the user sees it
    prints: bool
    reads: tuple[Path, ...]
    paths: dict[str, str]  # parameter name -> every path it writes, as the user sees it
    folder: bool = False  # the output may be a folder (its option takes one)
    named: tuple[tuple[str, str], ...] = ()  # parameter -> a file it reads, as the recipe says
    inside: tuple[tuple[str, str], ...] = ()  # parameter -> a path it writes, as the recipe says

    def command_line(self, inside: bool = False) -> str:
        """The job as a shell command (for --dry-run and progress lines); ``inside``: as the
        recipe names its files (the kit page's: no path of the machine)."""
        paths = dict(self.inside) if inside else self.paths
        words = [self.command.name]
        for p in self.command.params:
            if p.name not in self.values:
                continue
            value = (dict(self.named) if inside else self.values).get(p.name, self.values[p.name])
            if isinstance(p, click.Argument):
                words.append(str(value))
            elif p.name in paths:
                words += ["-o" if "-o" in p.opts else _long(p), paths[p.name]]
            elif getattr(p, "is_flag", False):
                words += [_long(p)] if value in (True, "true", "1", "yes") else []
            else:
                for item in value if isinstance(value, list) else [value]:
                    words += [_long(p), str(item)]
        line = "weave-cut " + " ".join(shlex.quote(w) for w in words)
        shown = dict(self.inside).get("output", self.shown) if inside else self.shown
        return line + (f" > {shlex.quote(shown)}" if self.prints else "")


def _long(p: click.Parameter) -> str:
    return max(p.opts, key=len)


def find_recipe(spec: str) -> Path:
    """A recipe file, or a recipe preset by name (``templates/recipes/NAME.toml``)."""
    path = Path(spec)
    if path.suffix or os.sep in spec or path.exists():
        return path
    try:
        return presets.find("recipes", spec)
    except presets.PresetError as exc:
        raise RecipeError(str(exc)) from exc


def _inside(path: Path, folders) -> bool:
    return any(path == f or path.is_relative_to(f) for f in folders)


class Planner:
    """Checks the jobs of one recipe against the commands of ``group``."""

    def __init__(self, group: click.Group, root: click.Context, recipe: Path, out_dir: Path,
                 shown_dir: str, allow_read: tuple[Path, ...], force: bool) -> None:
        self.group, self.root, self.recipe = group, root, recipe
        self.out_dir, self.shown_dir, self.force = out_dir, shown_dir, force
        self.readable = (recipe.resolve().parent, *(d.resolve() for d in allow_read))
        self.ours: dict[str, str] = {}  # the manifest, as check_outputs read it
        self.wrote: dict[str, list[str]] = {}
        self.written: set[str] = set()  # by the jobs run so far

    def commands(self) -> dict[str, click.Command]:
        return {n: c for n, c in self.group.commands.items() if n not in NOT_IN_RECIPES}

    @staticmethod
    def options(command: click.Command) -> dict[str, click.Parameter]:
        """Recipe keys (dashed long names) of ``command``'s options, -o as 'output'."""
        out = {}
        for p in command.params:
            if isinstance(p, click.Option) and p.name not in ("html", "force"):  # build
                # writes the page; only the build's own --force lets a file be replaced
                out["output" if "-o" in p.opts else option_key(p)] = p
        return out

    def plan(self, n: int, job: dict, overrides: dict[str, str]) -> Job:
        name = job["command"]
        command = self.commands().get(name)
        where = f"{self.recipe} job {n} ({name})"
        if command is None:
            raise RecipeError(f"{self.recipe} job {n}: unknown command {name!r}"
                              f"{nearest(name, self.commands())}; choose one of "
                              f"{', '.join(sorted(self.commands()))}")
        options = self.options(command)
        argument = next((p for p in command.params if isinstance(p, click.Argument)), None)
        allowed = {"command", "output", *options, *(["input"] if argument else [])}
        raw = {}
        for key, value in job.items():
            norm = key.replace("_", "-")
            if norm not in allowed:
                raise RecipeError(f"{where}: unknown key {key!r}{nearest(norm, allowed)}; "
                                  f"{name} takes {', '.join(sorted(allowed - {'command'}))}")
            raw[norm] = value
        raw.update({k: v for k, v in overrides.items() if k in options and k != "output"})
        values, reads = {}, []
        named = {options[k].name: v for k, v in raw.items() if k in options and isinstance(
            v, str) and (v.endswith(".toml") or isinstance(options[k].type, click.Path))}
        if argument is not None and "input" in raw:
            value = raw.pop("input")
            if not isinstance(value, str):
                raise RecipeError(f"{where}: input: expected a string")
            named[argument.name] = value
            if argument.name == "input_mesh":
                value = self.mesh_input(value, where)
                reads += [Path(value)] if Path(value).is_absolute() else []
            values[argument.name] = value
        raw.pop("command")
        prints = "output" in raw and "output" not in options  # it writes what it prints
        writes = [k for k in raw if k == "output" or options[k] in path_options(command)]
        writes.sort(key=lambda k: k != "output")  # -o first: the job's output
        targets = {k: self.output(raw[k], where, k) for k in writes}
        inside = {k: raw[k] for k in writes}
        shown = {k: str(Path(self.shown_dir) / raw.pop(k)) for k in writes}
        for key, value in raw.items():
            values[options[key].name] = self.value(options[key], key, value, where, reads)
        paths = {} if prints else {options[k].name: shown[k] for k in writes}
        values.update({} if prints else {options[k].name: str(targets[k]) for k in writes})
        first = writes[0] if writes else None
        if prints:
            self.check_printed(command, targets[first], values, where)
        for k in writes if not prints else ():
            message = problem(targets[k], is_folder(options[k], values), parent_made=True)
            if message:
                raise RecipeError(f"{where}: {k}: {message.replace(str(targets[k]), shown[k])}")
        folder = bool(paths) and is_folder(options[first], values)
        job = Job(where, f"job {n} ({name})", command, values, targets.get(first),
                  shown.get(first), prints, tuple(reads), paths, folder,
                  tuple(sorted((k, v) for k, v in named.items() if k not in paths)), tuple(sorted(
                      (options[k].name if k in options else k, v) for k, v in inside.items())))
        self.convert(job)
        return job

    def mesh_input(self, value: str, where: str) -> str:
        """A built-in input name as it is, or a mesh file inside a readable folder."""
        if inputs.is_builtin(value):
            return value
        path = (self.recipe.parent / value).resolve()
        try:
            found = path.is_file()
        except OSError:  # a name too long for the file system
            found = False
        if not found:
            raise RecipeError(f"{where}: input {value!r} is neither a built-in input"
                              f"{nearest(value, inputs.INPUTS)} nor a file beside the recipe")
        return str(self.readable_file(path, value, where, "input"))

    def readable_file(self, path: Path, value: str, where: str, key: str) -> Path:
        if not _inside(path, self.readable):
            raise RecipeError(f"{where}: {key} {value!r} is outside the recipe's folder; "
                              "allow its folder with --allow-read DIR")
        return path

    def value(self, p: click.Parameter, key: str, value, where: str, reads: list) -> object:
        """A recipe value for option ``p``, checked for its kind (click converts it later)."""
        if isinstance(value, bool) and not getattr(p, "is_flag", False):
            raise RecipeError(f"{where}: {key}: expected a value, not {value!r}")
        if isinstance(p.type, click.types.IntParamType) and isinstance(value, float):
            raise RecipeError(f"{where}: {key}: expected an integer, got {value!r}")
        if p.multiple and not isinstance(value, list):
            value = [value]
        if not p.multiple and isinstance(value, list):
            raise RecipeError(f"{where}: {key}: expected one value, got a list")
        if isinstance(value, str) and (value.endswith(".toml")  # a preset file, any option
                                       or isinstance(p.type, click.Path)):  # a file read
            path = self.readable_file((self.recipe.parent / value).resolve(), value, where, key)
            reads.append(path)
            value = str(path)
        kind = PRESET_OPTIONS.get(key)
        if kind and isinstance(value, str):
            try:
                presets.load(kind, value)
            except presets.PresetError as exc:
                raise RecipeError(f"{where}: {key}: {exc}") from exc
        return value

    def output(self, value, where: str, key: str = "output") -> Path:
        """The checked absolute path inside the build folder of ``value``, a path the job
        writes (its ``output``, or any other ``path_options`` key): the one rule for them."""
        rel = Path(value) if isinstance(value, str) else None
        if (rel is None or not value or rel.is_absolute() or ".." in rel.parts
                or value.startswith("~")):
            raise RecipeError(f"{where}: {key} {value!r} must be a relative path inside the "
                              "build folder (not absolute, no '..', no '~')")
        target = self.out_dir / rel
        if too_long(target):
            raise RecipeError(f"{where}: {key} is {too_long(target)}")
        if not _inside(target.resolve(), [self.out_dir.resolve()]):
            raise RecipeError(f"{where}: {key} {value!r} leads out of the build folder "
                              "through a symlink")
        if rel.name == MANIFEST or rel == Path(PAGE):
            raise RecipeError(f"{where}: {key} {value!r} is weave-cut's "
                              + ("manifest" if rel.name == MANIFEST else "page of the build"))
        return target

    @staticmethod
    def check_printed(command: click.Command, target: Path, values: dict, where: str) -> None:
        """A printing job's output is text a browser shows as text: ``.txt``, or ``.json``
        when the job prints JSON (never ``.html`` or ``.svg``, which would render a hostile
        input name's markup from the kit page)."""
        try:
            as_json = click.BOOL.convert(values.get("as_json", False), None, None)
        except click.BadParameter:  # refused with the key's name when converted
            as_json = False
        allowed = [".txt", *([".json"] if as_json else [])]
        if target.suffix.lower() not in allowed:
            can = not as_json and any(p.name == "as_json" for p in command.params)
            raise RecipeError(f"{where}: output {target.name!r}: a job that prints writes "
                              f"text; name it {' or '.join(allowed)}"
                              + (" (or .json with json = true)" if can else ""))

    def convert(self, job: Job) -> None:
        """Convert every value with the command's own option types, as click would."""
        sub = self.context(job)
        sub.close()

    def context(self, job: Job) -> click.Context:
        try:
            return job.command.make_context(job.command.name, [], parent=self.root,
                                            default_map=job.values)
        except click.MissingParameter as exc:
            what = "output" if exc.param is not None and "-o" in exc.param.opts else (
                "input" if isinstance(exc.param, click.Argument) else
                (option_key(exc.param) if exc.param else "a key"))
            raise RecipeError(f"{job.where}: needs {what!r}") from exc
        except click.BadParameter as exc:
            key = option_key(exc.param) if exc.param is not None and exc.param.opts else "input"
            raise RecipeError(f"{job.where}: {key}: {exc.message}") from exc
        except click.ClickException as exc:
            raise RecipeError(f"{job.where}: {exc.format_message()}") from exc

    def check_outputs(self, jobs: list[Job]) -> None:
        """No output is an input, another job's output, or a file weave-cut did not write
        (by the manifest as it is now: ``build`` checks before the first write, and again
        once it holds the folder, which another build may have written meanwhile)."""
        self.ours, self.wrote = read_manifest(self.out_dir)
        read = {p.resolve(): j for j in jobs for p in j.reads}
        read[self.recipe.resolve()] = None
        seen: dict[Path, Job] = {}
        for job in jobs:
            if job.output is None:
                continue
            real = job.output.resolve()
            if real in read:
                source = read[real]
                raise RecipeError(f"{job.where}: output {job.shown!r} is "
                                  + ("the recipe itself" if source is None else
                                     f"an input of {source.label}"))
            if real in seen and job.output.suffix:
                raise RecipeError(f"{job.where}: output {job.shown!r} is also the output of "
                                  f"{seen[real].label}")
            seen[real] = job
            for path in self.replaced(job):
                self.check_replace(path, job.where)
        self.check_replace(self.out_dir / PAGE, str(self.recipe))

    def check_replace(self, path: Path, where: str) -> None:
        """``path`` may be written: the rule of every command (``manifest.Ledger``)."""
        try:
            Ledger([self.out_dir], self.force).check(path, f"{self.shown_dir}/{self.rel(path)}")
        except WeaveCutError as exc:
            raise RecipeError(f"{where}: {exc}") from exc

    def replaced(self, job: Job) -> list[Path]:
        """Existing files ``job`` may replace or remove: those of every command
        (``outputs.may_replace``; a printing job's output), and the files it wrote last
        time."""
        last = [self.out_dir / p for p in self.wrote.get(self.rel(job.output), ())]
        found = [job.output] if job.prints else may_replace(job.command, job.values)
        return sorted({p for p in [*found, *last] if os.path.lexists(p)})

    def rel(self, path: Path) -> str:
        """``path`` relative to the build folder (a final symlink not followed)."""
        real = path.parent.resolve() / path.name if path.is_symlink() else path.resolve()
        return real.relative_to(self.out_dir.resolve()).as_posix()

    def run(self, job: Job, n: int, total: int) -> kitpage.Run:
        """Run ``job``; what it wrote, for the kit page."""
        from .. import kitpage

        say(f"[{n}/{total}] {job.command_line()}")
        if job.output is not None:
            make_folder(job.output.parent)  # checked to lie inside the build folder
        sub = self.context(job)
        printed = io.StringIO()
        try:
            with recording() as record:
                with sub, (contextlib.redirect_stdout(printed) if job.prints
                           else contextlib.nullcontext()):
                    job.command.invoke(sub)
                if job.prints:
                    write_atomic(job.output, printed.getvalue().encode("utf-8"))
        except click.ClickException as exc:  # no usage line of the nested command
            raise RecipeError(f"{job.where}: {exc.format_message()}") from exc
        self.remember(job, record.files)
        return kitpage.Run.of(record, job.command_line(inside=True), job.command.name)

    def remember(self, job: Job, written) -> None:
        """Record the files ``job`` wrote in the manifest, and remove the files it wrote last
        time and not now (checked to be weave-cut's before the first job ran)."""
        if job.output is None:
            return
        inside = self.out_dir.resolve()
        now = sorted({self.rel(p) for p in written if Path(p).resolve().is_relative_to(inside)})
        self.written.update(now)
        stale = [p for p in self.wrote.get(self.rel(job.output), ()) if p not in self.written]
        for rel in stale:  # unless edited since (then --force let it be; it is no longer ours)
            if file_hash(self.out_dir / rel) == self.ours.get(rel):
                os.unlink(self.out_dir / rel)
        record_manifest(self.out_dir, {p: file_hash(self.out_dir / p) for p in now},
                        {self.rel(job.output): now}, stale)
