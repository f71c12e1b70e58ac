"""Helpers the tests share: fixed records, file fixtures, node processes, app driving."""
