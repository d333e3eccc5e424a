"""The docs site (`make docs`: MkDocs, Material, mkdocstrings) builds in strict mode with every
page in its navigation, every image, the search index and the API page; and the strict build
does fail on a broken link or a page left out of the navigation.

Needs the docs venv that `make docs` makes (scripts/install-docs-deps.sh); `make test` makes
it before the Python tests run."""

import html.parser
import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
MKDOCS = ROOT / os.environ.get("DOCS_VENV", ".venv-docs") / "bin" / "mkdocs"

pytestmark = pytest.mark.skipif(
    not MKDOCS.exists(), reason=f"{MKDOCS} missing: `make docs` installs it")


def build(project: Path, site: Path) -> subprocess.CompletedProcess:
    return subprocess.run(
        [str(MKDOCS), "build", "--strict", "--site-dir", str(site)], cwd=project,
        capture_output=True, text=True, timeout=300,
        env=dict(os.environ, NO_MKDOCS_2_WARNING="1"))


class ImageSources(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.sources = []

    def handle_starttag(self, tag, attrs):
        if tag == "img":
            self.sources.append(dict(attrs)["src"])


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    site = tmp_path_factory.mktemp("site")
    result = build(ROOT, site)
    assert result.returncode == 0, f"mkdocs build --strict failed:\n{result.stderr[-4000:]}"
    return site


def test_every_page_is_built_and_searchable(site):
    pages = sorted((ROOT / "docs").glob("*.md"))
    search_index = (site / "search" / "search_index.json").read_text()
    for page in pages:
        built = site / ("index.html" if page.stem == "index" else f"{page.stem}/index.html")
        assert built.exists(), f"{page.name} was not built"
        assert f'"location":"{"" if page.stem == "index" else page.stem + "/"}"' in search_index, (
            f"{page.name} is not in the search index")


def test_the_home_page_is_the_readme_and_every_image_resolves(site):
    home = (site / "index.html").read_text()
    assert "A first result in three commands" in home
    shown = set()
    for page in site.rglob("*.html"):
        parser = ImageSources()
        parser.feed(page.read_text())
        for source in parser.sources:
            if source.startswith(("http:", "https:", "data:")):
                continue
            image = (page.parent / source).resolve()
            assert image.exists(), f"{page.relative_to(site)} shows a missing image {source}"
            shown.add(image.relative_to(site.resolve()).as_posix())
    images = {path.relative_to(ROOT / "docs").as_posix()
              for path in (ROOT / "docs" / "images").rglob("*.png")}
    assert images <= shown, f"images no page shows: {sorted(images - shown)}"


def test_the_api_page_documents_the_package(site):
    api = (site / "api" / "index.html").read_text()
    for name in ("make_vec", "load_policy", "UpkieEnv", "import_sb3", "registered_env_ids"):
        assert f'id="upkie_rl.' in api and name in api, f"the API page lacks {name}"


def copy_project(destination: Path) -> Path:
    destination.mkdir()
    for name in ("mkdocs.yml", "README.md"):
        shutil.copy(ROOT / name, destination / name)
    shutil.copytree(ROOT / "docs", destination / "docs")
    shutil.copytree(ROOT / "python" / "upkie_rl", destination / "python" / "upkie_rl")
    (destination / "scripts").mkdir()
    shutil.copy(ROOT / "scripts" / "mkdocs_hooks.py", destination / "scripts")
    return destination


def test_a_broken_link_fails_the_strict_build(tmp_path):
    project = copy_project(tmp_path / "project")
    page = project / "docs" / "layout.md"
    page.write_text(page.read_text() + "\nSee [the missing page](missing-page.md).\n")
    result = build(project, tmp_path / "site")
    assert result.returncode != 0 and "missing-page.md" in result.stderr, result.stderr[-2000:]


def test_a_broken_readme_link_fails_the_strict_build(tmp_path):
    project = copy_project(tmp_path / "project")
    readme = project / "README.md"
    readme.write_text(readme.read_text() + "\n[gone](docs/gone.md)\n")
    result = build(project, tmp_path / "site")
    assert result.returncode != 0 and "gone.md" in result.stderr, result.stderr[-2000:]


def test_a_page_left_out_of_the_navigation_fails_the_strict_build(tmp_path):
    project = copy_project(tmp_path / "project")
    (project / "docs" / "orphan.md").write_text("# Orphan\n")
    result = build(project, tmp_path / "site")
    assert result.returncode != 0 and "orphan.md" in result.stderr, result.stderr[-2000:]
