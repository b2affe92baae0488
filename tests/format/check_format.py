#!/usr/bin/python3
"""Every C++ file of hvi is formatted as the root .clang-format says (clang-format --dry-run
-Werror). Skipped (exit 77) where clang-format is not installed; scripts/setup.sh installs it.

Usage: check_format.py SOURCE_DIR
"""
import pathlib
import shutil
import subprocess
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else ".").resolve()
tool = shutil.which("clang-format")
if tool is None:
    print("clang-format not found: install the Debian package clang-format (scripts/setup.sh does)")
    sys.exit(77)
skip = {"build", ".git"}
files = sorted(p for p in root.rglob("*") if p.suffix in (".cpp", ".hpp")
               and not skip.intersection(p.relative_to(root).parts)
               and not p.relative_to(root).parts[0].startswith("build"))
failed = []
for chunk in range(0, len(files), 50):
    batch = files[chunk:chunk + 50]
    r = subprocess.run([tool, "--dry-run", "-Werror", "--style=file"] + [str(p) for p in batch],
                       cwd=root, capture_output=True, text=True)
    if r.returncode != 0:
        failed += sorted({line.split(":")[0] for line in r.stderr.splitlines() if ": error:" in line})
print(f"{len(files)} C++ files checked with {subprocess.run([tool, '--version'], capture_output=True, text=True).stdout.strip()}")
for f in failed:
    print(f"not formatted: {pathlib.Path(f).relative_to(root)} (run clang-format -i on it)")
sys.exit(1 if failed else 0)
