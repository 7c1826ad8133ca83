"""A Python client of the arcspline service, on httpx (docs/client.md).

:class:`Client` (blocking) and :class:`AsyncClient` (asyncio) send the service's own request
models, or plain mappings of the same JSON, and give back its own response models; a request
the service refuses raises :class:`ServiceError` with the problem details. Busy answers and
dropped connections are retried (:class:`Retry`, honouring ``Retry-After``); many requests go
through the batch endpoints in chunks under the service's limits::

    from arcspline.client import Client

    with Client("http://127.0.0.1:8000") as client:
        spline = client.approximate({
            "spiral": {"start": [1.5, 3.0], "start_tangent": [1.0, 0.0],
                       "turn_angle_deg": 51.34, "end_curvature": 0.41574},
            "tolerance": 0.001})
        print(spline.stats.arc_count)            # 12
        program = client.document({...same request, "gcode": {"feed_rate": 600}}, "gcode")

:func:`local_client` is the same service without a server, in this process.
"""

from arcspline.api.drawing_schemas import DrawingRequest, DrawingResponse
from arcspline.api.path_schemas import PathRequest, PathResponse
from arcspline.api.schemas import ApproximateRequest, ApproximateResponse, ProblemResponse

from .asynchronous import AsyncClient
from .config import DEFAULT_URL
from .errors import ServiceError
from .files import atomic_writer
from .local import local_client
from .operations import Document, Output
from .retry import Retry
from .sync import Client

__all__ = [
    "DEFAULT_URL",
    "ApproximateRequest",
    "ApproximateResponse",
    "AsyncClient",
    "Client",
    "Document",
    "DrawingRequest",
    "DrawingResponse",
    "Output",
    "PathRequest",
    "PathResponse",
    "ProblemResponse",
    "Retry",
    "ServiceError",
    "atomic_writer",
    "local_client",
]
