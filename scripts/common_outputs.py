#!/usr/bin/env python3
"""Do two run folders agree on everything the older one writes?

For builds far apart, whose outputs gained columns or keys since: history.csv's columns of
OLD must stand in NEW with the same text in every row, and every value of OLD's
results.json (less wall and CPU times) must stand at the same place in NEW, equal. Added
columns and keys are ignored; a number that differs, a missing column or key, or a text that
differs is printed, one line each (texts apart, since messages may name renamed modules).
Usage: scripts/common_outputs.py OLD_DIR NEW_DIR   (exit 0: numbers equal; 1: they are not)
"""
import csv
import json
import sys

TIMES = {"wall_time_s", "cpu_time_s"}


def leaves(value, path=""):
    """(path, leaf) pairs of a JSON value, less the keys that measure time."""
    if isinstance(value, dict):
        for k, v in value.items():
            if k not in TIMES:
                yield from leaves(v, f"{path}.{k}")
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from leaves(v, f"{path}[{i}]")
    else:
        yield path, value


def main(old_dir, new_dir):
    numbers, texts = [], []
    with open(f"{old_dir}/history.csv") as f:
        old = list(csv.DictReader(f))
    with open(f"{new_dir}/history.csv") as f:
        new = list(csv.DictReader(f))
    if len(old) != len(new):
        numbers.append(f"history.csv: {len(old)} rows against {len(new)}")
    elif old:
        for col in old[0]:
            if col not in new[0]:
                numbers.append(f"history.csv: column {col} missing")
            elif any(a[col] != b[col] for a, b in zip(old, new)):
                numbers.append(f"history.csv: column {col} differs")
    with open(f"{old_dir}/results.json") as f:
        old_json = dict(leaves(json.load(f)))
    with open(f"{new_dir}/results.json") as f:
        new_json = dict(leaves(json.load(f)))
    for path, value in old_json.items():
        if path not in new_json:
            numbers.append(f"results.json{path}: missing")
        elif new_json[path] != value:
            line = f"results.json{path}: {value!r} -> {new_json[path]!r}"
            (texts if isinstance(value, str) else numbers).append(line)
    for line in numbers:
        print("number:", line)
    for line in texts:
        print("text:", line)
    return 1 if numbers else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    sys.exit(main(sys.argv[1], sys.argv[2]))
