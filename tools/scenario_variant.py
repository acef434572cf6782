#!/usr/bin/env python3
"""Write a variant of a scenario file: its relative paths (scene.mesh, vehicle.heading_csv) made
absolute, so the copy runs from any folder, and each KEY=VALUE set (KEY a dotted path into the
scenario, made where missing; VALUE a number). The tools/ table scripts make their simulated cases
with it. Usage:
  tools/scenario_variant.py SOURCE DESTINATION BY [KEY=VALUE ...]
BY names the script, in the copy's first line, "# SOURCE with KEYS (BY)". A DESTINATION that exists
without that first line for the same BY (not a variant this script made for BY) is refused
(exit 2, named); the copy is written beside it and renamed into place."""
import os
import sys

import yaml

sys.dont_write_bytecode = True  # no __pycache__ left beside the tools


def fail(what):
    print(f"scenario_variant: {what}", file=sys.stderr)
    sys.exit(2)


def main():
    if len(sys.argv) < 4:
        fail("usage: SOURCE DESTINATION BY [KEY=VALUE ...]")
    src, dst, by, keys = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    if os.path.lexists(dst):
        try:
            with open(dst, encoding="utf-8") as f:
                first = f.readline()
        except (OSError, UnicodeDecodeError):
            first = ""
        if not (first.startswith("# ") and " with " in first and first.endswith(f" ({by})\n")):
            fail(f"{dst} exists and is not a scenario variant made for {by}; refusing")
    try:
        with open(src, encoding="utf-8") as f:
            s = yaml.safe_load(f)
    except (OSError, yaml.YAMLError) as e:
        fail(f"{src}: {e}")
    base = os.path.dirname(os.path.abspath(src))
    s["scene"]["mesh"] = os.path.join(base, s["scene"]["mesh"])
    if "heading_csv" in s.get("vehicle", {}):
        s["vehicle"]["heading_csv"] = os.path.join(base, s["vehicle"]["heading_csv"])
    for key in keys:
        path, _, value = key.partition("=")
        *sections, field = path.split(".")
        node = s
        for section in sections:
            if not node.get(section):
                node[section] = {}
            node = node[section]
        try:
            node[field] = float(value)
        except ValueError:
            fail(f"{key}: the value is not a number")
    partial = dst + ".partial"
    with open(partial, "w", encoding="utf-8") as f:
        f.write(f"# {src} with {','.join(keys) or 'nothing changed'} ({by})\n")
        yaml.safe_dump(s, f, sort_keys=False)
    os.replace(partial, dst)


if __name__ == "__main__":
    main()
