"""The docs hold together and their Python runs as printed.

- Every relative link of README.md and docs/*.md names a file of the checkout, and each #anchor a
  heading of the page it names (GitHub's rule for a heading's anchor) or an explicit id.
- docs/contact.md's table of headers names every header under include/massspring/contact/, and
  only headers that exist.
- Every ```python block of README.md and docs/python.md runs (one namespace per file, run from the
  checkout; interactive >>> blocks are shown output, not run), examples/python/drape.py writes
  its PNG, and examples/python/hanging_cloth.py runs.

The first two need only the checkout, not the compiled module, and run without this folder's
conftest.py (which imports it):

    python3 -m pytest --noconftest -p no:cacheprovider tests/python/test_docs.py \
        -k "links or slugs or headers"
"""

import glob
import os
import re
import subprocess
import sys

import pytest

SOURCE_DIR = os.environ.get("MASSSPRING_SOURCE_DIR") or os.path.abspath(
    os.path.join(os.path.dirname(__file__), "..", ".."))


def read(path):
    with open(path, encoding="utf-8") as handle:
        return handle.read()


def markdown_pages():
    """README.md and docs/*.md, as paths relative to the checkout."""
    docs = glob.glob(os.path.join(SOURCE_DIR, "docs", "*.md"))
    return ["README.md"] + sorted(os.path.relpath(p, SOURCE_DIR) for p in docs)


def prose_lines(text):
    """(line number, line) of the lines outside fenced code blocks, inline code spans blanked."""
    fence = None
    for number, line in enumerate(text.split("\n"), 1):
        stripped = line.lstrip()
        marker = re.match(r"(`{3,}|~{3,})", stripped)
        if marker:
            if fence is None:
                fence = marker.group(1)
                continue
            if stripped.startswith(fence):
                fence = None
                continue
        if fence is None:
            yield number, re.sub(r"(`+)(?:(?!\1).)+?\1", lambda m: " " * len(m.group(0)), line)


def heading_slug(heading):
    """GitHub's anchor of a heading: its text as rendered (code spans keep their text, links
    their label, emphasis markers go), lower case, every character that is not a letter, a digit,
    a space, '-' or '_' dropped, spaces made hyphens."""
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", heading)
    text = re.sub(r"<[^>]+>", "", text)
    text = text.replace("`", "").replace("*", "")
    text = re.sub(r"(^|\W)_+|_+(\W|$)", r"\1\2", text)
    text = text.strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def anchors(path):
    """Every anchor of a markdown page: its headings' (a repeated one gets -1, -2, ... as GitHub
    numbers them) and the ids and names of its HTML elements."""
    found, seen = set(), {}
    text = read(path)
    for _, line in prose_lines(text):
        heading = re.match(r" {0,3}(#{1,6})\s+(.*?)\s*#*\s*$", line)
        if heading:
            slug = heading_slug(heading.group(2))
            count = seen.get(slug, 0)
            seen[slug] = count + 1
            found.add(slug if count == 0 else f"{slug}-{count}")
    found.update(re.findall(r"<[^>]+\b(?:id|name)=\"([^\"]+)\"", text))
    return found


def relative_links(page):
    """(line, target) of every link and image of a page that is neither absolute nor a mail."""
    text = read(os.path.join(SOURCE_DIR, page))
    for number, line in prose_lines(text):
        for target in re.findall(r"\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)", line):
            if not re.match(r"[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                yield number, target


@pytest.mark.parametrize("page", markdown_pages())
def test_relative_links_resolve(page):
    broken = []
    folder = os.path.dirname(os.path.join(SOURCE_DIR, page))
    for number, target in relative_links(page):
        path, _, anchor = target.partition("#")
        resolved = os.path.normpath(os.path.join(folder, path)) if path else os.path.join(
            SOURCE_DIR, page)
        if not os.path.exists(resolved):
            missing = os.path.relpath(resolved, SOURCE_DIR)
            broken.append(f"{page}:{number}: {target}: no file {missing}")
        elif anchor and resolved.endswith(".md") and anchor not in anchors(resolved):
            broken.append(f"{page}:{number}: {target}: no heading with the anchor #{anchor}")
    assert not broken, "\n".join(broken)


def test_heading_slugs_follow_github():
    assert heading_slug("Collisions in 2D: FOSSSim's four responses") == \
        "collisions-in-2d-fosssims-four-responses"
    assert heading_slug("Contact inside BackwardEuler's solve") == \
        "contact-inside-backwardeulers-solve"
    assert heading_slug("`bench_step` and **the floor**") == "bench_step-and-the-floor"
    assert heading_slug("Sweeps: scale, round by round") == "sweeps-scale-round-by-round"
    assert heading_slug("A [linked](x.md) heading") == "a-linked-heading"


def test_contact_headers_table_names_every_header():
    root = os.path.join(SOURCE_DIR, "include", "massspring", "contact")
    headers = {os.path.relpath(p, root).replace(os.sep, "/")
               for p in glob.glob(os.path.join(root, "**", "*.hpp"), recursive=True)}
    assert headers, f"no header under {root}"
    text = read(os.path.join(SOURCE_DIR, "docs", "contact.md"))
    assert "| header | what |" in text, "docs/contact.md has no table headed | header | what |"
    start = text.index("| header | what |")
    rows = text[start:].split("\n\n", 1)[0].split("\n")[2:]
    named = [re.match(r"\|\s*`([^`]+)`\s*\|", row) for row in rows]
    assert all(named), "a row of docs/contact.md's table of headers does not start with a `path`"
    listed = [m.group(1) for m in named]
    assert len(listed) == len(set(listed)), "docs/contact.md's table names a header twice"
    missing = sorted(headers - set(listed))
    stale = sorted(set(listed) - headers)
    assert not missing, f"docs/contact.md's table of headers misses {missing}"
    assert not stale, f"docs/contact.md's table of headers names no such header: {stale}"


def blocks(name):
    with open(os.path.join(SOURCE_DIR, name)) as handle:
        text = handle.read()
    return [b for b in re.findall(r"```python\n(.*?)```", text, re.S)
            if not b.lstrip().startswith(">>>")]


@pytest.mark.parametrize("name", ["README.md", "docs/python.md"])
def test_python_blocks_run(name, monkeypatch, capsys):
    found = blocks(name)
    assert found, f"no python block in {name}"
    monkeypatch.chdir(SOURCE_DIR)
    namespace = {}
    for code in found:
        exec(compile(code, name, "exec"), namespace)  # noqa: S102: our own documentation


def test_drape_example_writes_a_png(tmp_path):
    pytest.importorskip("matplotlib")
    png = tmp_path / "drape.png"
    drape = os.path.join(SOURCE_DIR, "examples", "python", "drape.py")
    run = subprocess.run([sys.executable, drape, "--frames", "40", "--iterations", "5", "--png",
                          str(png)],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert "961 points" in run.stdout
    with open(png, "rb") as handle:
        assert handle.read(8) == b"\x89PNG\r\n\x1a\n"


def test_hanging_cloth_example_runs():
    script = os.path.join(SOURCE_DIR, "examples", "python", "hanging_cloth.py")
    run = subprocess.run([sys.executable, script], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "600 points; lowest after 2 s:" in run.stdout
