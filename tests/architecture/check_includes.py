"""Each folder of hvi includes only the folders it may: the table RULES, the dependencies the CMake
links declare (a library links what its folder may include). Reads the `#include "..."` lines (and
any `#include <...>` of an hvi header) of every C++ file of each folder and names the file and line
of each include the table does not allow. Exit status 1 if there is one.

    /usr/bin/python3 tests/architecture/check_includes.py [ROOT]   (ROOT: the repository, default
                                                                    the one this file is in)
"""
import pathlib
import re
import sys

LIBRARIES = ("materials", "geometry", "mpm", "fem", "coupling", "analysis", "cases/parallel", "cases/scene", "cases/run", "cases/cli")

# Folder -> what its files may include besides their own folder: folders, or a folder's subfolder.
RULES = {
    "materials": (),  # hvi_materials: the laws on doubles, nothing of hvi
    "cases/parallel": ("mpm",),  # hvi_parallel: the ranks of an MPI job, the solver's communicator over them, the tasks handed out among them
    "geometry": (),  # hvi_geometry: solids and point sets, nothing of hvi
    "mpm": ("materials",),  # hvi_mpm
    "fem": ("materials",),  # hvi_fem: the laws, never through mpm/
    "coupling": ("materials", "geometry", "mpm", "fem"),  # hvi_coupling
    "analysis": ("mpm/io",),  # hvi_analysis: the snapshots' HDF5 reader, not the solver
    "cases/scene": ("materials", "mpm", "analysis"),  # hvi_scene: the one scene reader
    "cases/run": ("materials", "geometry", "mpm", "fem", "coupling", "analysis", "cases/scene"),  # hvi_run
    "cases/cli": ("materials", "geometry", "mpm", "fem", "coupling", "analysis", "cases/parallel", "cases/scene", "cases/run"),  # hvi
    "bench": LIBRARIES,
    "tests": LIBRARIES,
}

# The top-level folders the rules speak of ("cases" holds the rules' "cases/scene", ...).
TOP_FOLDERS = {folder.split("/")[0] for folder in RULES}

SOURCES = {".hpp", ".cpp", ".h", ".cc", ".cxx", ".hh", ".ipp", ".inl"}
INCLUDE = re.compile(r'^\s*#\s*include\s*(["<])([^">]+)[">]')


def target(root, source, delimiter, name):
    """The included file's path relative to root, or None for a header not of hvi (the compiler's,
    a third party's, or one generated into the build tree)."""
    if delimiter == '"':
        local = (source.parent / name).resolve()
        if local.is_file():
            try:
                return local.relative_to(root).as_posix()
            except ValueError:
                return None
    path = pathlib.PurePosixPath(name)
    if path.parts and path.parts[0] in TOP_FOLDERS and (delimiter == '"' or (root / path).is_file()):
        return path.as_posix()
    return None


def allowed(folder, path):
    return any(path == p or path.startswith(p + "/") for p in (folder,) + RULES[folder])


def is_build_tree(directory):
    return (directory / "CMakeCache.txt").is_file()


def units(root):
    """The folders the rules are about: each top-level folder, or where the rules name its
    subfolders (cases/scene, ...), those subfolders."""
    for directory in sorted(p for p in root.iterdir() if p.is_dir()):
        if directory.name.startswith(".") or is_build_tree(directory):
            continue
        if any(folder.startswith(directory.name + "/") for folder in RULES):
            yield from sorted(p for p in directory.iterdir() if p.is_dir())
        else:
            yield directory


def main():
    root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).parents[2]).resolve()
    errors = []
    for folder, entries in RULES.items():
        for entry in entries:
            if not (root / entry).is_dir():
                errors.append(f"RULES: {folder} may include {entry}/, which is not a folder of {root}")
    files = includes = 0
    seen = set()
    for directory in units(root):
        sources = sorted(p for p in directory.rglob("*") if p.suffix in SOURCES and p.is_file())
        if not sources:
            continue
        folder = directory.relative_to(root).as_posix()
        if folder not in RULES:
            errors.append(f"{folder}/: {len(sources)} C++ files and no rule; add the folder to RULES")
            continue
        seen.add(folder)
        for source in sources:
            files += 1
            rel = source.relative_to(root).as_posix()
            for number, line in enumerate(source.read_text(errors="replace").splitlines(), 1):
                m = INCLUDE.match(line)
                if not m:
                    continue
                path = target(root, source, m.group(1), m.group(2))
                if path is None:
                    continue
                includes += 1
                if not allowed(folder, path):
                    may = ", ".join(e + "/" for e in (folder,) + RULES[folder])
                    errors.append(f"{rel}:{number}: includes {path}; {folder}/ may include only {may}")
    for folder in RULES:
        if folder not in seen:
            errors.append(f"RULES: {folder}/ has no C++ files under {root}")
    for e in errors:
        print(e)
    if errors:
        print(f"{len(errors)} violation(s)")
        return 1
    print(f"{files} files, {includes} includes of hvi headers: each folder includes only what it may")
    return 0


if __name__ == "__main__":
    sys.exit(main())
