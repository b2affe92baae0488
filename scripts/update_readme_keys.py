#!/usr/bin/env python3
"""Rewrites the Scene keys section of README.md from `hvi keys` (run after changing the schema).

Usage: scripts/update_readme_keys.py [path/to/hvi]   (default: build/hvi)
"""
import pathlib
import subprocess
import sys

root = pathlib.Path(__file__).resolve().parent.parent
hvi = sys.argv[1] if len(sys.argv) > 1 else str(root / "build" / "hvi")
keys = subprocess.run([hvi, "keys"], check=True, capture_output=True, text=True).stdout
readme = root / "README.md"
text = readme.read_text()
begin, end = "<!-- keys:begin -->\n", "<!-- keys:end -->"
head, rest = text.split(begin)
_, tail = rest.split(end)
readme.write_text(head + begin + keys + end + tail)
