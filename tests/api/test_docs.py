"""``/docs`` and ``/redoc`` work offline: every script, style and icon they load is served
by the service itself, with its media type, and neither page is in the OpenAPI document."""

from __future__ import annotations

from collections.abc import AsyncIterator
from html.parser import HTMLParser

import httpx
import pytest

from arcspline.api.app import create_app
from arcspline.settings import Settings

pytestmark = pytest.mark.anyio

MEDIA_TYPES = {
    ".js": ("text/javascript", "application/javascript"),
    ".css": ("text/css",),
    ".png": ("image/png",),
}


class _References(HTMLParser):
    """The URLs a page loads: ``<script src>``, ``<link href>``, ``<img src>``."""

    def __init__(self) -> None:
        super().__init__()
        self.urls: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        wanted = {"script": "src", "link": "href", "img": "src"}.get(tag)
        self.urls += [value for name, value in attrs if name == wanted and value]


@pytest.fixture(scope="module")
async def pages() -> AsyncIterator[httpx.AsyncClient]:
    # No lifespan: the pages need no workers.
    transport = httpx.ASGITransport(app=create_app(Settings()))
    async with httpx.AsyncClient(transport=transport, base_url="http://testserver") as pages:
        yield pages


@pytest.mark.parametrize("page", ["/docs", "/redoc"])
async def test_the_page_loads_only_what_the_service_serves(
    pages: httpx.AsyncClient, page: str
) -> None:
    response = await pages.get(page)
    assert response.status_code == 200
    assert response.headers["content-type"].startswith("text/html")
    assert "fonts.googleapis" not in response.text
    parser = _References()
    parser.feed(response.text)
    assert len(parser.urls) >= 2  # the script, and a style or the icon
    for url in parser.urls:
        assert url.startswith("/"), url  # the service's own: no scheme,
        assert not url.startswith("//"), url  # nor another host
        asset = await pages.get(url)
        assert asset.status_code == 200, url
        suffix = url[url.rindex(".") :]
        assert asset.headers["content-type"].split(";")[0] in MEDIA_TYPES[suffix], url
        assert len(asset.content) > 1000, url
    assert "/openapi.json" in response.text


async def test_the_pages_are_not_part_of_the_contract(pages: httpx.AsyncClient) -> None:
    paths = (await pages.get("/openapi.json")).json()["paths"]
    assert not [path for path in paths if path.startswith(("/docs", "/redoc"))]


async def test_an_unknown_asset_is_a_404_problem(pages: httpx.AsyncClient) -> None:
    response = await pages.get("/docs-assets/nothing.js")
    assert response.status_code == 404
    assert response.headers["content-type"] == "application/problem+json"
