"""Serving HTTP: the bounds every connection is held to before the app sees a request
(``protocol``) and the file-descriptor rule that sizes the connection cap (``descriptors``).
See docs/deployment.md, "Connections"."""
