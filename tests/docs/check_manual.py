#!/usr/bin/python3
"""The manual cannot drift from the code: every `hvi ...` command line of README.md and docs/user/
names a command and options that `hvi CMD --help` lists, and where it names a scene or study of the
repository, `hvi check` (a study: `hvi sweep --list`) accepts it with its overrides. Every TOML
snippet passes `hvi check`: a whole scene as it stands, a fragment added to the README's minimal
scene (the two spheres) or to the scene a comment `<!-- check: with PATH -->` just before the
block names, a study through `hvi sweep --list`.

Usage: check_manual.py HVI SOURCE_DIR
"""
import pathlib
import re
import shlex
import subprocess
import sys
import tempfile

hvi, root = sys.argv[1], pathlib.Path(sys.argv[2])
pages = [root / "README.md"] + sorted((root / "docs" / "user").glob("*.md"))
# Commands that read a scene (checked with `hvi check`) and a study (with `hvi sweep --list`).
scene_commands = {"check", "run", "geometry", "convergence"}
failures = []
help_cache = {}


checked = {}  # the same `hvi check` of the same scene runs once


def run(args, cwd):
    return subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=120)


def help_of(command):
    if command not in help_cache:
        r = run([hvi, command, "--help"], root)
        help_cache[command] = r.stdout if r.returncode == 0 else None
    return help_cache[command]


def blocks(text):
    """(info string, body, line, base) of every fenced code block; base: the path of a
    `<!-- check: with PATH -->` comment on the line before the block, or None."""
    for m in re.finditer(r"^```(\w*)\n(.*?)^```", text, re.M | re.S):
        before = text[: m.start()].rstrip("\n").rsplit("\n", 1)[-1]
        marker = re.match(r"<!-- check: with (\S+) -->", before)
        yield m.group(1), m.group(2), text.count("\n", 0, m.start()) + 1, marker and marker.group(1)


def command_lines(text):
    """(command line, line) of every hvi command: in sh blocks and in inline code."""
    for info, body, line, _ in blocks(text):
        if info not in ("sh", ""):
            continue
        joined = body.replace("\\\n", " ")
        for k, raw in enumerate(joined.split("\n")):
            cmd = raw.split(" #")[0].strip()
            cmd = re.sub(r"^\$ ", "", cmd)
            # A launcher's part (mpirun -np 4, srun --cpu-bind=cores) is the launcher's to check.
            cmd = re.sub(r"^(mpirun|mpiexec|srun)( +-\S+( +[0-9]+)?)* +", "", cmd)
            if re.match(r"^(build/)?hvi ", cmd):
                yield cmd, line + k
    prose = re.sub(r"^```.*?^```", "", text, flags=re.M | re.S)
    for m in re.finditer(r"`((?:build/)?hvi [^`]+)`", prose):
        yield m.group(1), text.count("\n", 0, text.find(m.group(0))) + 1


def optional_marks_off(word):
    """`[--threads` -> `--threads`, `N]...` -> `N`: the brackets of an optional part, not those
    of a TOML array (`grid.lower=["0 mm", ...]`)."""
    if word.startswith("[") and len(word) > 1 and (word[1] == "-" or word[1].isupper()):
        word = word[1:]
    if "[" not in word:
        word = re.sub(r"\](\.\.\.)?$", "", word)
    return "" if word == "..." else word


def check_command(page, line, cmd):
    where = f"{page.relative_to(root)}:{line}: `{cmd}`"
    try:
        words = shlex.split(cmd)
    except ValueError as e:
        failures.append(f"{where}: cannot split: {e}")
        return
    words = [w for word in words for w in optional_marks_off(word).split("|") if w]
    if len(words) < 2:
        return
    command = words[1]
    text = help_of(command)
    if text is None:
        failures.append(f"{where}: `hvi {command}` is not a command")
        return
    for w in words[2:]:
        if w.startswith("--"):
            option = w.split("=")[0].rstrip(".")
            if re.search(re.escape(option) + r"\b", text) is None:
                failures.append(f"{where}: `hvi {command} --help` has no option {option}")
    target = next((w for w in words[2:] if not w.startswith("-")), None)
    if target is None or not (root / target).is_file():
        return
    overrides = []
    for i, w in enumerate(words):
        if w == "--set" and i + 1 < len(words):
            overrides += ["--set", words[i + 1]]
        elif w.startswith("--set="):
            overrides += ["--set", w[len("--set="):]]
    only = [x for i, w in enumerate(words) if w == "--only" and i + 1 < len(words) for x in ("--only", words[i + 1])]
    key = ("check" if command in scene_commands else command, target, tuple(overrides), tuple(only))
    if key in checked:
        return
    checked[key] = True
    with tempfile.TemporaryDirectory() as out:
        if command == "sweep":
            args = [hvi, "sweep", target, "--out", out, "--list"] + overrides + only
        elif command in scene_commands:
            args = [hvi, "check", target] + overrides
        else:
            return
        r = run(args, root)
    if r.returncode != 0:
        failures.append(f"{where}: `{' '.join(args[1:])}` exited {r.returncode}: {(r.stderr or r.stdout).strip()[-400:]}")


def cube_stl(a):
    """An ASCII STL of the cube [0, a]^3 (mm), outward normals: the snippets' `bracket.stl`."""
    corners = [(x, y, z) for x in (0, a) for y in (0, a) for z in (0, a)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    out = ["solid bracket"]
    for f in faces:
        for tri in ((f[0], f[1], f[2]), (f[0], f[2], f[3])):
            out += ["facet normal 0 0 0", "outer loop"]
            out += ["vertex {} {} {}".format(*corners[i]) for i in tri]
            out += ["endloop", "endfacet"]
    return "\n".join(out + ["endsolid bracket", ""])


def minimal_scene():
    readme = (root / "README.md").read_text()
    for info, body, _, _ in blocks(readme):
        if info == "toml" and "[grid]" in body:
            return body
    raise SystemExit("README.md has no whole scene")


def check_snippet(page, line, body, base):
    where = f"{page.relative_to(root)}:{line}"
    with tempfile.TemporaryDirectory() as tmp:
        if re.search(r"^scene\s*=", body, re.M):
            study = pathlib.Path(tmp) / "study.toml"
            study.write_text(body)
            args = [hvi, "sweep", str(study), "--out", str(pathlib.Path(tmp) / "out"), "--list"]
        else:
            scene = pathlib.Path(tmp) / "scene.toml"
            (pathlib.Path(tmp) / "bracket.stl").write_text(cube_stl(2.0))
            whole = "[grid]" in body or re.search(r"^\[run\]", body, re.M)
            scene.write_text(body if whole else base + "\n" + body)
            args = [hvi, "check", str(scene)]
        r = run(args, root)
    if r.returncode != 0:
        failures.append(f"{where}: TOML snippet fails `hvi {args[1]}` (exit {r.returncode}): {(r.stderr or r.stdout).strip()[-600:]}")


base = minimal_scene()
commands = snippets = 0
for page in pages:
    text = page.read_text()
    for cmd, line in command_lines(text):
        check_command(page, line, cmd)
        commands += 1
    for info, body, line, with_ in blocks(text):
        if info == "toml":
            check_snippet(page, line, body, (root / with_).read_text() if with_ else base)
            snippets += 1

print(f"{commands} command lines and {snippets} TOML snippets in {len(pages)} pages")
for f in failures:
    print(f)
sys.exit(1 if failures else 0)
