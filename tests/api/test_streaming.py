"""Big answers without big memory (docs/http-api.md, "Batches"): a batch streamed as NDJSON
(one line per job, in order, each the JSON answer's entry, sent as the jobs finish), and gzip
when the client accepts it (the body unchanged once decompressed, media types kept)."""

from __future__ import annotations

import gzip
import json
from pathlib import Path
from typing import Any

import httpx
import pytest

from tests.support.server import running_server

from .conftest import running_app

pytestmark = pytest.mark.anyio

NDJSON = "application/x-ndjson"
SPIRAL: dict[str, Any] = {
    "start": [1.5, 3.0],
    "start_tangent": [1.0, 0.0],
    "turn_angle_deg": 51.34,
    "end_curvature": 0.41574,
}
#: Just above the paper spiral's tolerance floor (5.6525e-10): 1,278 arcs.
FLOOR = 5.66e-10
#: The same request id on both answers: problems carry it.
SAME_ID = {"X-Request-ID": "streaming-test"}


def _mixed_jobs() -> list[Any]:
    good = [{"spiral": SPIRAL, "tolerance": t} for t in (0.1, 1e-3, 1e-6, 1e-8, 0.01) * 5]
    return [
        *good[:3],
        "not a job",
        {"spiral": SPIRAL, "tolerance": 1e-14},  # below the floor: the core refuses
        *good[3:],
        {"spiral": {**SPIRAL, "turn_angle_deg": 95}, "tolerance": 0.1},  # schema refuses
    ]


def _lines(response: httpx.Response) -> list[Any]:
    assert response.status_code == 200, response.text[:300]
    assert response.headers["content-type"] == NDJSON
    text = response.text
    assert text.endswith("\n")
    return [json.loads(line) for line in text.splitlines()]


@pytest.mark.parametrize(
    ("url", "jobs"),
    [
        ("/v1/approximate/batch", _mixed_jobs()),
        (
            "/v1/paths/batch",
            [
                {"path": "M 0 0 C 1 2 3 2 4 0 L 6 0", "tolerance": 1e-4},
                {"path": "M 0 0 Q", "tolerance": 1e-4},
                {"path": "M 0 0 A 1 1 0 0 1 2 0 Z", "tolerance": 1e-6},
            ],
        ),
    ],
)
async def test_ndjson_has_one_line_per_job_in_order_equal_to_the_json_entries(
    url: str, jobs: list[Any]
) -> None:
    async with running_app() as (_, client):
        whole = await client.post(url, json={"jobs": jobs}, headers=SAME_ID)
        streamed = await client.post(
            url, json={"jobs": jobs}, headers={**SAME_ID, "Accept": NDJSON}
        )
    assert whole.status_code == 200
    assert whole.headers["content-type"] == "application/json"
    entries = whole.json()["results"]
    lines = _lines(streamed)
    assert lines == entries
    assert len(lines) == len(jobs)
    assert "error" in [line["status"] for line in lines]


@pytest.mark.parametrize(
    ("accept", "streams"),
    [
        (NDJSON, True),
        (f"application/json;q=0.5, {NDJSON}", True),
        (f"application/json, {NDJSON};q=0.5", False),
        (f"*/*;q=0.1, {NDJSON};q=0", False),
        ("*/*", False),
    ],
)
async def test_accept_chooses_between_json_and_ndjson(accept: str, streams: bool) -> None:
    async with running_app() as (_, client):
        response = await client.post(
            "/v1/approximate/batch",
            json={"jobs": [{"spiral": SPIRAL, "tolerance": 0.1}]},
            headers={"Accept": accept},
        )
    assert response.status_code == 200
    assert response.headers["content-type"] == (NDJSON if streams else "application/json")


async def test_a_streamed_job_past_the_budget_alone_gets_its_entry_in_place() -> None:
    jobs = [{"spiral": SPIRAL, "tolerance": t} for t in (0.1, FLOOR, 0.1)]
    async with running_app(batch_max_segments=1000) as (_, client):
        response = await client.post(
            "/v1/approximate/batch", json={"jobs": jobs}, headers={"Accept": NDJSON}
        )
    lines = _lines(response)
    assert [line["status"] for line in lines] == ["ok", "error", "ok"]
    assert lines[1]["error"]["type"] == "urn:arcspline:problem:work-too-large"
    assert lines[1]["error"]["limit"] == 1000


def test_lines_arrive_while_later_jobs_are_still_computed(tmp_path: Path) -> None:
    """A real server (uvicorn: a body that streams), one worker: quick jobs first, then
    hundreds of 1,278-arc ones. Once the first line is read, the batch is still running."""
    quick, slow = {"spiral": SPIRAL, "tolerance": 0.1}, {"spiral": SPIRAL, "tolerance": FLOOR}
    jobs = [quick] * 8 + [slow] * 400
    with running_server(tmp_path, pool_size=1) as server, httpx.Client(timeout=120) as client:
        url = f"{server.url}/v1/approximate/batch"
        with client.stream("POST", url, json={"jobs": jobs}, headers={"Accept": NDJSON}) as r:
            assert r.status_code == 200
            assert r.headers["content-encoding"] == "gzip"  # and streams through gzip
            lines = r.iter_lines()
            first = json.loads(next(lines))
            metrics = server.metrics()
            rest = [json.loads(line) for line in lines]
    assert first["status"] == "ok"
    assert metrics["arcspline_pool_in_flight"] >= 1  # later jobs of the batch still computing
    assert len(rest) == len(jobs) - 1
    assert all(line["status"] == "ok" for line in rest)
    assert {len(line["result"]["segments"]) for line in rest[7:]} == {1278}


async def test_gzip_when_accepted_the_same_bytes_and_media_types() -> None:
    batch = {"jobs": [{"spiral": SPIRAL, "tolerance": 1e-6}] * 20}
    gcode = {"spiral": SPIRAL, "tolerance": 1e-6, "gcode": {"feed_rate": 100}}
    bad = {"jobs": [{"spiral": SPIRAL, "tolerance": 0.1}] * 1001}  # a problem: too many jobs
    bad_fields = {"spiral": {**SPIRAL, **{f"field_{i}": i for i in range(60)}}, "tolerance": 1}
    identity = {**SAME_ID, "Accept-Encoding": "identity"}
    zipped = {**SAME_ID, "Accept-Encoding": "gzip"}
    async with running_app() as (_, client):
        for url, body in [
            ("/v1/approximate/batch", batch),
            ("/v1/approximate?output=gcode", gcode),
            ("/v1/approximate", bad_fields),
            ("/v1/approximate/batch", bad),
        ]:
            plain = await client.post(url, json=body, headers=identity)
            async with client.stream("POST", url, json=body, headers=zipped) as packed:
                raw = b"".join([part async for part in packed.aiter_raw()])
            assert "content-encoding" not in plain.headers
            assert packed.status_code == plain.status_code
            assert packed.headers["content-type"] == plain.headers["content-type"]
            if len(plain.content) < 1024:  # too small to be worth it
                assert "content-encoding" not in packed.headers
                assert raw == plain.content
                continue
            assert packed.headers["content-encoding"] == "gzip"
            assert "accept-encoding" in packed.headers["vary"].lower()  # for caches
            assert gzip.decompress(raw) == plain.content
            assert len(raw) < len(plain.content)
        media_types = {(await client.post(u, json=b)).headers["content-type"] for u, b in [
            ("/v1/approximate?output=gcode", gcode), ("/v1/approximate", bad_fields)
        ]}  # fmt: skip
        assert media_types == {"text/x-gcode; charset=utf-8", "application/problem+json"}
        small = await client.get("/healthz", headers=zipped)
        assert "content-encoding" not in small.headers
        stream = await client.post(
            "/v1/approximate/batch", json=batch, headers={**zipped, "Accept": NDJSON}
        )
        assert stream.headers["content-encoding"] == "gzip"
        whole = await client.post("/v1/approximate/batch", json=batch)
        assert _lines(stream) == whole.json()["results"]
