"""Lengths given to the scripts with units ("0.5 mm"), read by hvi itself (`hvi units`), so that a
script takes every value a scene takes, the same way. The hvi program: $HVI, else build/hvi of this
checkout."""
import os
import pathlib
import subprocess


def hvi_program():
    return os.environ.get("HVI") or str(pathlib.Path(__file__).resolve().parent.parent / "build" / "hvi")


def lengths(option, text, names):
    """An option's comma-separated lengths in m, one per name of `names` ("X,Y")."""
    parts = text.split(",")
    count = len(names.split(","))
    if len(parts) != count:
        raise ValueError(f"{option} '{text}': expected {['one', 'two', 'three'][count - 1]} lengths {names}")
    done = subprocess.run([hvi_program(), "units", "--expect", "length", *parts], capture_output=True, text=True)
    if done.returncode != 0:
        raise ValueError(f"{option} {done.stderr.strip().removeprefix('hvi: ')}")
    return [float(v) for v in done.stdout.split()]


def length(text, option="length"):
    """One length in m."""
    return lengths(option, text, "value")[0]
