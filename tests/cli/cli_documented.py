#!/usr/bin/env python3
"""docs/cli.md cannot fall behind the code (issue 46): the option tables and the
statistics table in the code are the source.
- Every option a command's --help lists is documented in that command's section (the
  text from `## COMMAND` to the next `## `), read from the lines of `vkraycast COMMAND
  --help` that start with an option.
- Every field of --stats-json, from a GPU and a CPU render of a shard of the showcase
  (so that the optional ones appear), is named as `field` in "Statistics and version".

Usage: cli_documented.py VKRAYCAST REPO_ROOT"""
import json
import os
import re
import subprocess
import sys
import tempfile

COMMANDS = ["render", "compare", "merge", "tradeoff", "prepare"]


def help_options(binary, command):
    out = subprocess.run([binary, command, "--help"], capture_output=True, text=True).stdout
    options = []
    for line in out.splitlines():
        m = re.match(r"\s+((?:-\w, )?--[\w-]+)", line)
        if m:
            options.extend(re.findall(r"--[\w-]+|(?<![\w-])-\w\b", m.group(1)))
    return options


def stats_keys(binary, root):
    keys = set()
    with tempfile.TemporaryDirectory() as tmp:
        for backend in ("gpu", "cpu"):
            stats = os.path.join(tmp, "stats.json")
            subprocess.run([binary, "render", f"{root}/scenes/showcase.json", "-o", os.path.join(tmp, "part.exr"),
                            "--width", "16", "--height", "10", "--shard", "0/2", "--backend", backend, "--quiet",
                            "--stats-json", stats], check=True)
            keys |= set(json.load(open(stats)))
    return sorted(keys)


def main():
    binary, root = sys.argv[1], sys.argv[2]
    page = open(f"{root}/docs/cli.md", encoding="utf-8").read()
    missing, total = [], 0
    m = re.search(r"^## Statistics and version\b(.*?)(?=^## |\Z)", page, re.M | re.S)
    statistics = m.group(1) if m else ""
    for key in stats_keys(binary, root):
        total += 1
        if f"`{key}`" not in statistics:
            missing.append(f"--stats-json field {key}")
    for command in COMMANDS:
        m = re.search(rf"^## {command}\b(.*?)(?=^## |\Z)", page, re.M | re.S)
        section = m.group(1) if m else ""
        options = help_options(binary, command)
        if not options:
            missing.append(f"{command}: --help lists no options")
        for option in options:
            total += 1
            if not re.search(rf"(?<![\w-]){re.escape(option)}(?![\w-])", section):
                missing.append(f"{command} {option}")
    for item in missing:
        print(f"FAIL: not in docs/cli.md: {item}")
    print(f"{total - len(missing)} of {total} options and statistics fields documented")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
