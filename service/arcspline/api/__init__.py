"""The thin HTTP layer: FastAPI app factory, schemas, routes, errors, probes and metrics."""
