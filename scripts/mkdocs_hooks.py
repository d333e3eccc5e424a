"""MkDocs hook (mkdocs.yml): the site's home page is README.md.

docs/index.md holds a placeholder; its Markdown is replaced by README.md's, whose links into
docs/ (`docs/training.md`, `docs/images/...`) are made relative to docs/. MkDocs then checks
those links as it checks every page's, so a README link to a missing page fails the strict
build.
"""

import re
from pathlib import Path

README_LINK = re.compile(r"\]\(docs/")


def on_page_markdown(markdown, page, config, files):
    if page.file.src_uri != "index.md":
        return markdown
    readme = Path(config.config_file_path).parent / "README.md"
    return README_LINK.sub("](", readme.read_text())
