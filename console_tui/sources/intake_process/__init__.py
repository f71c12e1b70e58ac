"""Live sources run in a child process (``parent.ProcessSource``, ``child``), records sent in batches."""
