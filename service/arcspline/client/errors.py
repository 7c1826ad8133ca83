"""What a request can end with besides its result: the service's problem details, raised as
one exception type (:class:`ServiceError`) with their fields."""

from __future__ import annotations

from typing import Any

import httpx
from pydantic import ValidationError

from arcspline.api.schemas import ProblemErrorResponse, ProblemResponse

PROBLEM_MEDIA_TYPE = "application/problem+json"
_TYPE_PREFIX = "urn:arcspline:problem:"


class ServiceError(Exception):
    """The service refused a request or could not complete it: its RFC 9457 problem details
    (docs/errors.md), or, for an answer that is not one (a proxy's error page), its status
    and text as ``detail``.

    ``kind`` is the last part of ``type`` (``validation``, ``tolerance-floor``, ``queue-full``,
    ...), ``about:blank`` for plain HTTP errors.
    """

    def __init__(self, problem: ProblemResponse) -> None:
        super().__init__(f"{problem.status} {problem.title}: {problem.detail}")
        self.problem = problem

    def __reduce__(self) -> tuple[object, ...]:
        # A batch's entries may cross a process boundary: pickle the problem itself.
        return (ServiceError, (self.problem,))

    @property
    def status(self) -> int:
        return self.problem.status

    @property
    def type(self) -> str:
        return self.problem.type

    @property
    def kind(self) -> str:
        return self.problem.type.removeprefix(_TYPE_PREFIX)

    @property
    def title(self) -> str:
        return self.problem.title

    @property
    def detail(self) -> str:
        return self.problem.detail

    @property
    def errors(self) -> list[ProblemErrorResponse]:
        return self.problem.errors or []

    @property
    def limit(self) -> float | None:
        return self.problem.limit

    @property
    def request_id(self) -> str | None:
        return self.problem.request_id

    @classmethod
    def from_body(cls, body: Any) -> ServiceError:
        """From a problem already parsed (a batch's error entry)."""
        return cls(ProblemResponse.model_validate(body))

    @classmethod
    def from_response(cls, response: httpx.Response) -> ServiceError:
        """From an answer that is not a success (read in full first)."""
        media_type = response.headers.get("content-type", "").split(";", 1)[0].strip()
        if media_type == PROBLEM_MEDIA_TYPE:
            try:
                return cls(ProblemResponse.model_validate_json(response.content))
            except ValidationError:
                pass  # not ours after all: said as plain text below
        reason = response.reason_phrase or "error"
        text = response.text.strip()[:500] or reason
        return cls(
            ProblemResponse(
                type="about:blank",
                title=reason,
                status=response.status_code,
                detail=text,
                request_id=response.headers.get("x-request-id"),
            )
        )
