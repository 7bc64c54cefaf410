"""Reading a submission safely: its lab folders found and its lab files read without following any
link, as regular files within the size limit, the stubs where a file cannot be used; and the
submission folders refused before anything is graded.
"""

import os
import stat
from dataclasses import dataclass
from pathlib import Path

from .common import ROOT, SOURCE_LIMIT, STAGE_RE


def open_folder(root: Path, parts: tuple) -> int:
    """A descriptor of the folder root/parts, reached without following any link below root;
    raises LinkError naming the first component that is a link, OSError when it is missing."""
    fd = os.open(root, os.O_RDONLY | os.O_DIRECTORY)
    try:
        for depth, part in enumerate(parts):
            shown = "/".join(parts[:depth + 1])
            if stat.S_ISLNK(os.stat(part, dir_fd=fd, follow_symlinks=False).st_mode):
                raise LinkError(shown)
            inner = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW, dir_fd=fd)
            os.close(fd)
            fd = inner
        return fd
    except BaseException:
        os.close(fd)
        raise


class LinkError(OSError):
    """A component of a submitted path is a symbolic link; its `path` is shown in the report."""

    def __init__(self, path: str):
        super().__init__(f"{path} is a symbolic link")
        self.path = path


def read_regular(folder: int, name: str, shown: str) -> bytes:
    """The bytes of the regular file `name` in the open folder, never through a link; raises
    OSError (LinkError for a link) with the reason the file cannot be used."""
    if stat.S_ISLNK(os.stat(name, dir_fd=folder, follow_symlinks=False).st_mode):
        raise LinkError(shown)
    fd = os.open(name, os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK, dir_fd=folder)
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise OSError(f"{shown} is not a regular file")
        if info.st_size > SOURCE_LIMIT:
            raise OSError(f"{shown} is larger than {SOURCE_LIMIT >> 10} KiB")
        with os.fdopen(os.dup(fd), "rb") as f:
            return f.read(SOURCE_LIMIT)
    finally:
        os.close(fd)


@dataclass
class Submitted:
    """Where a submission's lab folders are: root/parts/NN_name (parts is ("labs",) or ())."""
    root: Path
    parts: tuple


def submitted_sources(labs: Submitted, stage: str, notes: list) -> dict:
    """name -> bytes of the lab files to grade: the submission's regular files named as the stub's
    files of the stage, each reached without following a link at any level below the submission's
    root; the stub where the submission has none, with a note naming the link or the reason."""
    stubs = {p.name: p for p in sorted((ROOT / "labs" / stage).glob("*.cpp"))}
    parts = labs.parts + (stage,)
    try:
        folder = open_folder(labs.root, parts)
    except LinkError as link:
        notes.append(f"{link.path} is a symbolic link: links are not followed, so this lab is "
                     f"graded with the stubs")
        return {name: stub.read_bytes() for name, stub in stubs.items()}
    except OSError:
        notes.append(f"{'/'.join(parts)} is not in the submission: graded with the stubs")
        return {name: stub.read_bytes() for name, stub in stubs.items()}
    sources = {}
    try:
        for name, stub in stubs.items():
            shown = "/".join(parts + (name,))
            try:
                sources[name] = read_regular(folder, name, shown)
            except LinkError:
                notes.append(f"{shown} is a symbolic link: links are not followed, so it is graded "
                             f"with the stub")
            except FileNotFoundError:
                notes.append(f"{name} is not in the submission: graded with the stub")
            except OSError as error:
                notes.append(f"{error.strerror or error}: graded with the stub")
            if name not in sources:
                sources[name] = stub.read_bytes()
        extra = sorted(n for n in os.listdir(folder) if n not in sources)
        if extra:
            notes.append(f"ignored (only the stub's files are graded): {', '.join(extra[:10])}")
    finally:
        os.close(folder)
    return sources


def find_labs(submission: Path):
    """Where the lab folders of a submission (a labs/ copy or a whole repo) are, or None. A linked
    labs/ is not followed: its labs are then reported as links, one note each."""
    for parts in (("labs",), ()):
        try:
            fd = open_folder(submission, parts)
        except LinkError:
            return Submitted(submission, parts)
        except OSError:
            continue
        try:
            if any(STAGE_RE.match(n) for n in os.listdir(fd)):
                return Submitted(submission, parts)
        finally:
            os.close(fd)
    return None


def submission_problems(paths: list) -> list:
    """What makes a submission ungradable before anything starts: missing, not a folder, empty."""
    problems = []
    for p in paths:
        path = Path(p)
        if not path.exists() and not path.is_symlink():
            problems.append(f"submission {p}: no such folder")
        elif path.is_symlink() or not path.is_dir():
            problems.append(f"submission {p}: not a folder (a student's labs/ folder or a copy of the repository)")
        elif not any(path.iterdir()):
            problems.append(f"submission {p}: the folder is empty")
    names = [Path(p).absolute().name for p in paths]
    twice = sorted({n for n in names if names.count(n) > 1})
    if len(paths) > 1 and twice:
        problems.append(f"two submissions named {twice[0]}: each is graded into --out/<name>/")
    return problems
