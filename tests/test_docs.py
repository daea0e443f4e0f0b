"""The documentation: the link checker of the built site, and (ROLLAWAY_TEST_DOCS=1) the build itself."""
import importlib.util
import os
import shutil
import subprocess

import pytest

from tests.conftest import ROOT


def _check_links():
    spec = importlib.util.spec_from_file_location("check_links", ROOT / "scripts" / "check-links.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_link_checker_finds_missing_pages_and_anchors(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "index.html").write_text(
        '<a href="sub/page.html#here">ok</a> <a href="sub/page.html#gone">bad anchor</a> '
        '<a href="missing.html">bad page</a> <img src="/sub/page.html"> <a href="https://example.org/x">ext</a>'
        '<a href="#top">self</a><h1 id="top">t</h1>')
    (tmp_path / "sub" / "page.html").write_text('<h2 id="here">h</h2><a href="../index.html">up</a>')
    broken, external = _check_links().broken_links(tmp_path)
    assert sorted(broken) == ["index.html: missing.html (no such file)",
                              "index.html: sub/page.html#gone (no element with id 'gone')"]
    assert external == {"example.org"}


@pytest.mark.skipif(os.environ.get("ROLLAWAY_TEST_DOCS") != "1" or shutil.which("mkdocs") is None,
                    reason="the docs build (~40 s) runs with ROLLAWAY_TEST_DOCS=1 and the docs extra installed")
def test_docs_build_executes_the_tutorials_and_documents_drum_model(tmp_path):
    out = tmp_path / "site"
    subprocess.run(["bash", "scripts/build-docs.sh"], cwd=ROOT, check=True, env={**os.environ, "SITE_DIR": str(out)})
    for name in ("regulation-check", "mujoco-rollaway", "sweep-design-chart", "bench-to-road"):
        page = (out / "tutorials" / f"{name}.html").read_text(encoding="utf-8")
        assert "data:image/png;base64" in page or "data:image/gif;base64" in page, name
    assert 'id="rollaway.model.drum_model.DrumModel"' in (out / "api.html").read_text(encoding="utf-8")
