"""Every relative link of every Markdown file the repository tracks resolves: the file exists and, for a link to
a Markdown file with ``#anchor``, the anchor is one of its headings (GitHub's slugs, which the site's MyST
heading anchors repeat). Run by ``make docs`` after the Sphinx build, whose own reference checks cover the
pages of the site; this covers the README, the validation cases and the studies as a repository browser shows
them. Links with a scheme (``https:``, ``mailto:``) are not followed.

Usage: ``python docs/check_links.py`` from anywhere; prints each broken link as ``file:line: target (why)`` and
exits 1 if there is any.
"""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: ``[text](target)`` and ``![alt](target)``, target without spaces; inline code is removed first.
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
CODE = re.compile(r"`[^`]*`")
HEADING = re.compile(r"^#{1,6}\s+(.*?)\s*#*\s*$")
#: MyST label lines ``(name)=`` before a heading define an anchor too.
LABEL = re.compile(r"^\((\S+)\)=\s*$")


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, markup and punctuation dropped, spaces to hyphens."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # a link in a heading keeps its text
    text = re.sub(r"[^\w\- ]", "", text.lower().replace("`", ""))
    return text.replace(" ", "-")


def anchors(path: Path) -> set[str]:
    """The anchors of a Markdown file: its headings' slugs (repeats numbered as GitHub does) and MyST labels."""
    seen: dict[str, int] = {}
    found: set[str] = set()
    fenced = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.lstrip().startswith(("```", "~~~")):
            fenced = not fenced
        if fenced:
            continue
        label = LABEL.match(line)
        if label:
            found.add(label.group(1))
        match = HEADING.match(line)
        if match:
            base = slug(match.group(1))
            n = seen.get(base, 0)
            seen[base] = n + 1
            found.add(base if n == 0 else f"{base}-{n}")
    return found


def markdown_files() -> list[Path]:
    """The Markdown files git tracks, and the new ones it does not ignore."""
    out = subprocess.run(["git", "ls-files", "--cached", "--others", "--exclude-standard", "*.md"], cwd=ROOT,
                         capture_output=True, text=True, check=True).stdout.split()
    return [ROOT / name for name in out if (ROOT / name).is_file()]


def broken_links(path: Path) -> list[str]:
    """``file:line: target (why)`` for each relative link of ``path`` that does not resolve."""
    problems = []
    fenced = False
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if line.lstrip().startswith(("```", "~~~")):
            fenced = not fenced
        if fenced or line.startswith("    "):  # code blocks hold no links
            continue
        for target in LINK.findall(CODE.sub("", line)):
            why = check_target(path, target)
            if why:
                problems.append(f"{path.relative_to(ROOT)}:{number}: {target} ({why})")
    return problems


def check_target(path: Path, target: str) -> str:
    """Why ``target`` (a link in ``path``) does not resolve, or ``""``."""
    if re.match(r"^[a-z][a-z0-9+.-]*:", target):  # https:, mailto:, doi: ...
        return ""
    file, _, anchor = target.partition("#")
    dest = (path.parent / file).resolve() if file else path
    if not dest.exists():
        return "no such file"
    if ROOT not in dest.parents and dest != ROOT:
        return "outside the repository"
    if anchor and dest.suffix == ".md" and anchor not in anchors(dest):
        return f"no heading '{anchor}' in {dest.relative_to(ROOT)}"
    return ""


def main() -> int:
    files = markdown_files()
    problems = [p for f in files for p in broken_links(f)]
    for problem in problems:
        print(problem)
    print(f"check_links: {len(files)} Markdown files, {len(problems)} broken links")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
