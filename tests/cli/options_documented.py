#!/usr/bin/env python3
"""Every option a command's --help lists is documented in that command's section of
docs/cli.md (issue 46: the option tables in the code are the source; the page must not
fall behind them). Options are read from `vkraycast COMMAND --help`, the lines that start
with an option; a section is the text from `## COMMAND` to the next `## `.

Usage: options_documented.py VKRAYCAST REPO_ROOT"""
import re
import subprocess
import sys

COMMANDS = ["render", "compare", "merge", "tradeoff"]


def help_options(binary, command):
    out = subprocess.run([binary, command, "--help"], capture_output=True, text=True).stdout
    options = []
    for line in out.splitlines():
        m = re.match(r"\s+((?:-\w, )?--[\w-]+)", line)
        if m:
            options.extend(re.findall(r"--[\w-]+|(?<![\w-])-\w\b", m.group(1)))
    return options


def main():
    binary, root = sys.argv[1], sys.argv[2]
    page = open(f"{root}/docs/cli.md", encoding="utf-8").read()
    missing, total = [], 0
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
    print(f"{total - len(missing)} of {total} options documented")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
