"""The documentation: README.md (the home page) and docs/, built as a site by MkDocs.

The site is built here as CI builds it, `mkdocs build --strict`: a link to a page or file
that is not there, an anchor that no heading or id gives, a page left out of the nav, all
warnings under mkdocs.yml's validation settings, fail the test (`make docs` builds the same
into out/site). The README stays the short page a newcomer reads, and every command has its
reference page, linked from the README's table.
"""

from __future__ import annotations

import argparse
import importlib
import os
import re
import shlex
import subprocess
import sys

import pytest

from conftest import ROOT

DEV = "the documentation's tools are dev dependencies: pip install -e '.[dev]'"


def _read(name: str) -> str:
    with open(os.path.join(ROOT, name), encoding="utf-8") as f:
        return f.read()


def _config() -> dict:
    try:
        import yaml  # PyYAML, which mkdocs brings
    except ImportError as e:
        pytest.fail(f"{e}: {DEV}")
    return yaml.safe_load(_read("mkdocs.yml"))  # mkdocs.yml uses no YAML tags


def _nav_pages(nav) -> list[str]:
    out = []
    for entry in nav:
        value = next(iter(entry.values())) if isinstance(entry, dict) else entry
        out += _nav_pages(value) if isinstance(value, list) else [value]
    return out


def _pages() -> list[str]:
    """Every markdown page under docs/, relative to it (the example adapter's folder is code)."""
    docs = os.path.join(ROOT, "docs")
    out = []
    for folder, subfolders, files in os.walk(docs):
        subfolders[:] = [s for s in subfolders if s != "example_adapter" and not s.startswith(".")]
        out += [os.path.relpath(os.path.join(folder, f), docs).replace(os.sep, "/") for f in files if f.endswith(".md")]
    return sorted(out)


def test_the_site_builds_strictly_without_a_warning(tmp_path):
    try:
        import mkdocs  # noqa: F401
        import mkdocs_include_markdown_plugin  # noqa: F401
    except ImportError as e:
        pytest.fail(f"{e}: {DEV}")
    site = tmp_path / "site"
    p = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--config-file",
                        os.path.join(ROOT, "mkdocs.yml"), "--site-dir", str(site)],
                       cwd=ROOT, capture_output=True, text=True, timeout=300)
    said = p.stdout + p.stderr
    warnings = [line for line in said.splitlines() if "WARNING" in line or "ERROR" in line]
    assert p.returncode == 0 and not warnings, "mkdocs build --strict:\n" + "\n".join(warnings or said.splitlines()[-20:])
    # the home page is README itself, its links rewritten to the pages and its picture shown
    home = (site / "index.html").read_text(encoding="utf-8")
    assert "A conformance and comparison suite for the X3D RigidBodyPhysics component" in home
    assert 'href="commands/compare.html"' in home
    for image in re.findall(r"!\[[^\]]*\]\(docs/([^)]+)\)", _read("README.md")):
        assert f'src="{image}"' in home and (site / image).is_file(), image


def test_the_site_is_checked_strictly_and_lists_every_page():
    config = _config()
    assert config.get("strict") is True
    # mkdocs's defaults leave some of these at "info", which --strict does not fail on
    for group, checks in config["validation"].items():
        for name, level in checks.items():
            assert level == "warn", f"mkdocs.yml validation.{group}.{name} is {level!r}: keep it 'warn'"
    assert set(config["validation"]["nav"]) >= {"omitted_files", "not_found"}
    assert set(config["validation"]["links"]) >= {"not_found", "anchors", "unrecognized_links"}
    nav = _nav_pages(config["nav"])
    assert sorted(nav) == _pages(), "mkdocs.yml's nav and the pages under docs/ differ"
    assert len(nav) == len(set(nav))


def test_the_home_page_is_the_readme_not_a_copy():
    index = _read("docs/index.md")
    assert re.fullmatch(r'\{%\s*include-markdown "\.\./README\.md"\s*rewrite-relative-urls=true\s*%\}\s*', index), index


def test_every_command_has_its_reference_page_linked_from_the_readme():
    from x3drbp import COMMANDS
    readme = _read("README.md")
    for command in COMMANDS:
        page = f"docs/commands/{command}.md"
        assert os.path.isfile(os.path.join(ROOT, page)), f"{command} has no reference page {page}"
        assert f"]({page})" in readme, f"README's table of commands does not link {page}"
        usage = _read(page).split("\n")[2]  # the title, a blank line, then the command's usage
        assert usage.startswith(f"`x3drbp {command}"), (page, usage)
    documented = {name[:-3] for name in os.listdir(os.path.join(ROOT, "docs", "commands"))}
    assert documented == set(COMMANDS), f"pages for no command: {sorted(documented - set(COMMANDS))}"


def _options(parser: argparse.ArgumentParser) -> set[str]:
    """Every long option of a command, its subcommands' included (x-ite cases, x-ite record)."""
    out = set()
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                out |= _options(sub)
        out.update(o for o in action.option_strings if o.startswith("--") and o != "--help")
    return out


def _commands() -> argparse._SubParsersAction:
    """Every command's parser, as `x3drbp` builds them."""
    from x3drbp import COMMANDS
    sub = argparse.ArgumentParser(prog="x3drbp").add_subparsers()
    for module in set(COMMANDS.values()):
        importlib.import_module(f"x3drbp.{module}").add_command(sub)
    return sub


def test_every_option_of_a_command_is_on_its_page():
    from x3drbp import COMMANDS
    sub = _commands()
    for command in COMMANDS:
        page = _read(f"docs/commands/{command}.md")
        missing = sorted(o for o in _options(sub.choices[command]) if not re.search(re.escape(o) + r"(?![\w-])", page))
        assert not missing, f"docs/commands/{command}.md does not name {missing}"


def test_the_readmes_command_lines_parse():
    """The worked example's commands are real: each `.venv/bin/x3drbp ...` line of README parses."""
    sub = _commands()
    lines = [line for line in _read("README.md").splitlines() if line.startswith(".venv/bin/x3drbp ")]
    assert lines
    for line in lines:
        command, *args = shlex.split(line)[1:]
        sub.choices[command].parse_args(args)  # a SystemExit (exit 2) names what does not parse


def test_the_readme_stays_a_page_read_in_ten_minutes():
    readme = _read("README.md")
    lines = readme.count("\n")
    assert lines <= 200, f"README.md has {lines} lines: move reference text to a page under docs/"
    for section in ("## Two commands", "## A worked example", "## Commands"):
        assert section in readme, section
