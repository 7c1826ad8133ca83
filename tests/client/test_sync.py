"""The blocking client against a real server: every operation, typed results, the
service's problems as one exception, downloads that stream and never leave half a file."""

from __future__ import annotations

import asyncio
import io
from pathlib import Path
from typing import Any

import ezdxf
import httpx
import pytest

from arcspline.client import (
    ApproximateRequest,
    ApproximateResponse,
    AsyncClient,
    Client,
    DrawingResponse,
    PathResponse,
    Retry,
    ServiceError,
)
from tests.support.server import Server

PATH = {"path": "M 0 0 C 10 0 20 10 30 30 L 40 30 A 5 5 0 0 1 50 30", "tolerance": 0.01}
SVG = (
    '<svg xmlns="http://www.w3.org/2000/svg" width="60mm" height="40mm" viewBox="0 0 60 40">'
    '<path d="M 5 35 C 15 5 45 5 55 35 Z"/><circle cx="30" cy="25" r="6"/></svg>'
)
DRAWING = {"document": SVG, "format": "svg", "tolerance": 0.01}


@pytest.fixture(scope="module")
def client(server: Server) -> Any:
    with Client(server.url) as client:
        yield client


def test_a_spiral_gives_the_papers_twelve_arcs_as_a_typed_result(
    client: Client, paper_request: dict[str, Any]
) -> None:
    spline = client.approximate(paper_request)
    assert isinstance(spline, ApproximateResponse)
    assert spline.stats.arc_count == 12
    # The same request as the server's own model gives the same answer.
    assert client.approximate(ApproximateRequest.model_validate(paper_request)) == spline


def test_a_path_and_a_drawing_give_typed_results(client: Client) -> None:
    path = client.approximate_path(PATH)
    assert isinstance(path, PathResponse)
    assert path.stats.segment_count == sum(len(s.segments) for s in path.subpaths)
    drawing = client.approximate_drawing(DRAWING)
    assert isinstance(drawing, DrawingResponse)
    assert len(drawing.toolpaths) == 2


def test_a_refusal_is_a_service_error_with_the_problems_fields(
    client: Client, paper_request: dict[str, Any]
) -> None:
    with pytest.raises(ServiceError) as caught:
        client.approximate({**paper_request, "tolerance": 0})
    error = caught.value
    assert (error.status, error.kind) == (422, "validation")
    assert [e.loc for e in error.errors] == [["body", "tolerance"]]
    assert error.request_id
    assert "tolerance" in str(error)


def test_a_refused_document_names_its_element(client: Client) -> None:
    with pytest.raises(ServiceError) as caught:
        client.approximate_drawing({**DRAWING, "document": "<svg"})
    assert (caught.value.status, caught.value.kind) == (422, "invalid-document")
    assert caught.value.errors[0].element is not None


def test_a_request_of_the_wrong_kind_is_refused_before_sending(client: Client) -> None:
    with pytest.raises(ValueError, match="takes a spiral request"):
        client.approximate(PATH)
    with pytest.raises(ValueError, match="'spiral', 'path' or 'document'"):
        client.preview({"curve": 1})


def test_previews_are_svg_for_each_kind(client: Client, paper_request: dict[str, Any]) -> None:
    for request in (paper_request, PATH, DRAWING):
        picture = client.preview(request)
        assert picture.lstrip().startswith(("<svg", "<?xml")), picture[:80]
        assert picture.rstrip().endswith("</svg>")


def test_the_program_alone_is_the_program_of_the_json_answer(client: Client) -> None:
    request = {**DRAWING, "gcode": {"feed_rate": 600}}
    program = client.document(request, "gcode")
    assert program.media_type == "text/x-gcode"
    assert program.filename is not None
    assert program.filename.endswith(".ngc")
    assert program.content.decode() == client.approximate_drawing(request).gcode


def test_a_download_streams_the_dxf_into_the_file(client: Client, tmp_path: Path) -> None:
    target = tmp_path / "part.dxf"
    answer = client.download(DRAWING, "dxf", target)
    assert answer.content == b""
    assert answer.media_type == "image/vnd.dxf"
    # Read back by ezdxf: one entity per segment the JSON answer has.
    drawing = client.approximate_drawing(DRAWING)
    entities = ezdxf.readfile(target).modelspace().query("LINE ARC")
    assert len(entities) == drawing.stats.segment_count
    assert list(tmp_path.iterdir()) == [target]


def test_a_download_into_an_open_file(client: Client) -> None:
    sink = io.BytesIO()
    client.download(DRAWING, "svg", sink)
    assert sink.getvalue().lstrip().startswith((b"<svg", b"<?xml"))


def test_a_failed_download_leaves_no_file(client: Client, tmp_path: Path) -> None:
    target = tmp_path / "part.ngc"
    with pytest.raises(ServiceError) as caught:
        client.download(DRAWING, "gcode", target)  # no feed rate: nothing to write
    assert caught.value.status == 422
    assert list(tmp_path.iterdir()) == []


def test_health_and_readiness(client: Client) -> None:
    assert client.health().status == "ok"
    ready = client.ready()
    assert (ready.status, ready.workers) == ("ready", 2)


def test_an_unreachable_server_raises_the_connection_error_after_the_retries() -> None:
    with (
        Client("http://127.0.0.1:9", retry=Retry(attempts=2, backoff_s=0.01)) as client,
        pytest.raises(httpx.ConnectError),
    ):
        client.health()


def test_the_json_alone_is_the_services_bytes_of_the_typed_answer(
    client: Client, paper_request: dict[str, Any]
) -> None:
    raw = client.document(paper_request, "json")
    assert raw.media_type == "application/json"
    assert ApproximateResponse.model_validate_json(raw.content) == client.approximate(paper_request)


class _BrokenThenWhole(httpx.SyncByteStream):
    """A program that breaks off after its first line the first time it is sent."""

    sent = 0

    def __iter__(self) -> Any:
        type(self).sent += 1
        yield b"G17 G21\n"
        if type(self).sent == 1:
            raise httpx.ReadError("dropped")
        yield b"M2\n"


def test_a_download_tried_again_writes_the_document_once(tmp_path: Path) -> None:
    def handle(request: httpx.Request) -> httpx.Response:
        return httpx.Response(200, headers={"Content-Type": "text/x-gcode"},
                              stream=_BrokenThenWhole())  # fmt: skip

    quick = Retry(attempts=3, backoff_s=0.001)
    for target in (io.BytesIO(), str(tmp_path / "part.ngc")):
        _BrokenThenWhole.sent = 0
        with Client("http://x", transport=httpx.MockTransport(handle), retry=quick) as client:
            client.download(PATH, "gcode", target)
        written = target.getvalue() if isinstance(target, io.BytesIO) else Path(target).read_bytes()
        assert written == b"G17 G21\nM2\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["part.ngc"]


def test_the_async_download_streams_into_the_file(server: Server, tmp_path: Path) -> None:
    async def run() -> Any:
        async with AsyncClient(server.url) as client:
            return await client.download(DRAWING, "dxf", tmp_path / "part.dxf")

    answer = asyncio.run(run())
    assert (answer.media_type, answer.filename) == ("image/vnd.dxf", "drawing.dxf")
    with Client(server.url) as client:
        assert (tmp_path / "part.dxf").read_bytes() == client.document(DRAWING, "dxf").content
