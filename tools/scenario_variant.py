#!/usr/bin/env python3
"""Write a variant of a scenario file: its relative paths (scene.mesh, vehicle.heading_csv) made
absolute, so the copy runs from any folder, and each KEY=VALUE set (KEY a dotted path into the
scenario, made where missing; VALUE a number). The tools/ table scripts make their simulated cases
with it. Usage:
  tools/scenario_variant.py SOURCE DESTINATION BY [KEY=VALUE ...]
BY names the script, in the copy's first line."""
import os
import sys

import yaml

sys.dont_write_bytecode = True  # no __pycache__ left beside the tools


def main():
    if len(sys.argv) < 4:
        print("scenario_variant: usage: SOURCE DESTINATION BY [KEY=VALUE ...]", file=sys.stderr)
        sys.exit(2)
    src, dst, by, keys = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    with open(src, encoding="utf-8") as f:
        s = yaml.safe_load(f)
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
            print(f"scenario_variant: {key}: the value is not a number", file=sys.stderr)
            sys.exit(2)
    with open(dst, "w", encoding="utf-8") as f:
        f.write(f"# {src} with {','.join(keys) or 'nothing changed'} ({by})\n")
        yaml.safe_dump(s, f, sort_keys=False)


if __name__ == "__main__":
    main()
